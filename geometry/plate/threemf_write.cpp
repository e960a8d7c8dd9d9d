#include "geometry/plate/threemf_write.h"

#include <Model/COM/NMR_DLLInterfaces.h>
#include <fmt/format.h>

#include "base/output_file.h"

namespace tranche::plate {
namespace {

using namespace NMR;  // lib3mf's C interface

class Handle {
 public:
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (p_) lib3mf_release(p_);
  }
  PLib3MFBase* get() const { return p_; }
  PLib3MFBase** out() { return &p_; }

 private:
  PLib3MFBase* p_ = nullptr;
};

Error failed(PLib3MFBase* instance, const std::string& what) {
  DWORD code = 0;
  LPCSTR msg = nullptr;
  lib3mf_getlasterror(instance, &code, &msg);
  return Error{"", fmt::format("lib3mf could not {}: {}", what, msg ? msg : "unknown error")};
}

}  // namespace

Result<std::string> write_3mf_bytes(const std::vector<Object>& objects) {
  Handle model;
  if (lib3mf_createmodel(model.out()) != LIB3MF_OK) return Error{"", "lib3mf could not start"};
  for (const Object& o : objects) {
    Handle mesh, item;
    if (lib3mf_model_addmeshobject(model.get(), mesh.out()) != LIB3MF_OK) return failed(model.get(), "add an object");
    lib3mf_object_setnameutf8(mesh.get(), o.name.c_str());
    std::vector<MODELMESHVERTEX> v(o.mesh.vertices.size());
    for (size_t i = 0; i < v.size(); ++i) {
      const geo::Vec3& p = o.mesh.vertices[i];
      v[i].m_fPosition[0] = static_cast<float>(p.x);
      v[i].m_fPosition[1] = static_cast<float>(p.y);
      v[i].m_fPosition[2] = static_cast<float>(p.z);
    }
    std::vector<MODELMESHTRIANGLE> t(o.mesh.triangles.size());
    for (size_t i = 0; i < t.size(); ++i)
      for (int k = 0; k < 3; ++k) t[i].m_nIndices[k] = o.mesh.triangles[i][k];
    if (lib3mf_meshobject_setgeometry(mesh.get(), v.data(), static_cast<DWORD>(v.size()), t.data(),
                                      static_cast<DWORD>(t.size())) != LIB3MF_OK)
      return failed(mesh.get(), "set the mesh of '" + o.name + "'");
    MODELTRANSFORM m{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 4; ++c) m.m_fFields[r][c] = static_cast<float>(o.transform.matrix()(r, c));
    if (lib3mf_model_addbuilditem(model.get(), mesh.get(), &m, item.out()) != LIB3MF_OK)
      return failed(model.get(), "add a build item");
  }
  Handle writer;
  if (lib3mf_model_querywriter(model.get(), MODELWRITERCLASS_3MF, writer.out()) != LIB3MF_OK)
    return failed(model.get(), "make a writer");
  ULONG64 size = 0;
  if (lib3mf_writer_getstreamsize(writer.get(), &size) != LIB3MF_OK) return failed(writer.get(), "size the package");
  std::string out(size, '\0');
  if (lib3mf_writer_writetobuffer(writer.get(), reinterpret_cast<BYTE*>(out.data()), size) != LIB3MF_OK)
    return failed(writer.get(), "write the package");
  return out;
}

Status write_3mf(const std::string& path, const std::vector<Object>& objects) {
  auto bytes = write_3mf_bytes(objects);
  if (!bytes) return Error{path, bytes.error().message};
  auto file = OutputFile::create(path, "the 3MF file");
  if (!file) return file.error();
  if (Status s = file->write(*bytes); !s) return s;
  return file->commit();
}

}  // namespace tranche::plate
