# tranche_module(NAME DIR <folder> [DEPS public-libs...] [PRIVATE_DEPS libs...])
# One static library per pipeline folder. Sources are globbed so that adding a file to a
# folder needs no CMake edit; headers are included from the project root
# ("geometry/mesh/mesh.h"). A folder with headers only becomes an INTERFACE library.
function(tranche_module name)
  cmake_parse_arguments(M "" "DIR" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB _srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${M_DIR}/*.cpp)
  if(_srcs)
    add_library(${name} STATIC ${_srcs})
    target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} PUBLIC ${M_DEPS} PRIVATE ${M_PRIVATE_DEPS} tranche_warnings)
  else()
    add_library(${name} INTERFACE)
    target_include_directories(${name} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${name} INTERFACE ${M_DEPS})
  endif()
endfunction()

# tranche_test_suite(NAME DIR <tests-subfolder> DEPS libs...)
# One doctest executable per tests/ subfolder, registered with CTest. The working directory is
# the build folder; TRANCHE_SOURCE_DIR points at the checkout for fixtures.
function(tranche_test_suite name)
  cmake_parse_arguments(T "" "DIR" "DEPS" ${ARGN})
  file(GLOB _srcs CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${T_DIR}/*.cpp)
  if(NOT _srcs)
    return()
  endif()
  add_executable(${name} ${_srcs})
  target_link_libraries(${name} PRIVATE tranche_test_main ${T_DEPS} tranche_warnings)
  add_test(NAME ${name} COMMAND ${name} --no-intro --duration=false)
  set_tests_properties(${name} PROPERTIES ENVIRONMENT "TRANCHE_SOURCE_DIR=${PROJECT_SOURCE_DIR};TRANCHE_BINARY_DIR=${PROJECT_BINARY_DIR}")
endfunction()
