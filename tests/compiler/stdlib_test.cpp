// stdlib/: every file compiles without warnings, and the built-in defaults (the C++ table used
// when no profile is loaded) say what stdlib/defaults.rules says.
#include <doctest/doctest.h>

#include <filesystem>

#include "compiler/check.h"
#include "compiler/codegen.h"
#include "compiler/diagnostics.h"
#include "compiler/frontend.h"
#include "runtime/context/defaults.h"
#include "runtime/vm/vm.h"
#include "tests/support/fixtures.h"

using namespace tranche;
namespace fs = std::filesystem;
using schema::FieldId;
using schema::PropId;

TEST_CASE("stdlib: every file checks without errors or warnings, on its own") {
  int files = 0;
  for (const auto& e : fs::recursive_directory_iterator(test::source_dir() / "stdlib")) {
    if (e.path().extension() != ".rules") continue;
    ++files;
    compiler::FrontendOptions o;
    o.stdlib_dir = (test::source_dir() / "stdlib").string();
    diag::Sink sink;
    auto p = compiler::compile({e.path().string()}, {}, o, sink);
    for (const auto& d : sink.all()) FAIL_CHECK(e.path().string() << ": " << compiler::render_text(p.sources, d, false));
    CHECK(p.checked);
  }
  CHECK(files >= 4);
}

TEST_CASE("stdlib: the built-in defaults agree with stdlib/defaults.rules") {
  compiler::FrontendOptions o;
  diag::Sink sink;
  auto ast = compiler::compile({(test::source_dir() / "stdlib" / "defaults.rules").string()}, {}, o, sink);
  REQUIRE(ast.checked);
  auto code = compiler::generate(ast);
  REQUIRE(code.ok());
  auto rs = vm::RuleSet::create(std::move(*code));
  REQUIRE(rs.ok());
  ctx::BuiltinDefaults builtin;
  for (int layer = 0; layer < 3; ++layer)
    for (int kind = 0; kind < 10; ++kind) {
      ctx::Context c;
      c.clear_from(schema::Level::Layer);
      c.set(FieldId::LayerIndex, layer);
      c.clear_from(schema::Level::Path);
      c.set(FieldId::PathKind, kind);
      auto a = ctx::PropertyValues::schema_defaults(), b = a;
      for (int s = 0; s < schema::kStageCount; ++s) {
        auto stage = static_cast<schema::Stage>(s);
        c.set_props(&a);
        REQUIRE(builtin.decide(stage, c, a).ok());
        c.set_props(&b);
        REQUIRE((*rs)->decide(stage, c, b).ok());
      }
      for (const auto& info : schema::properties()) {
        if (info.id == PropId::FillAngle) continue;  // computed below the rules (see defaults.rules)
        if (info.id == PropId::LayerHeight && layer == 0) continue;  // the cascade applies first_layer_height
        CHECK_MESSAGE(a[info.id] == b[info.id], info.name << " on layer " << layer << ", kind " << kind);
      }
    }
}
