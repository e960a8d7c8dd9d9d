#include "geometry/plate/threemf.h"

#include <Common/NMR_ErrorConst.h>
#include <Model/COM/NMR_DLLInterfaces.h>
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "geometry/mesh/weld.h"
#include "geometry/plate/threemf_meshes.h"
#include "geometry/plate/threemf_package.h"

namespace tranche::plate {
namespace {

using namespace NMR;  // lib3mf's C interface

constexpr int kMaxDepth = 16;             // nested components
constexpr double kMinDeterminant = 1e-12;  // below: the transform flattens the object

// Owns one lib3mf instance (model, reader, iterator, resource...).
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

std::string lib3mf_message(PLib3MFBase* instance, DWORD* code_out = nullptr) {
  DWORD code = 0;
  LPCSTR msg = nullptr;
  lib3mf_getlasterror(instance, &code, &msg);
  if (code_out) *code_out = code;
  return msg && *msg ? msg : fmt::format("error {:#x}", static_cast<unsigned>(code));
}

Error read_error(const std::string& file, PLib3MFBase* reader) {
  DWORD code = 0;
  const std::string msg = lib3mf_message(reader, &code);
  std::string what;
  switch (code) {
    case NMR_ERROR_COULDNOTREADZIPFILE: what = "the ZIP archive is damaged or truncated"; break;
    case NMR_ERROR_INVALIDMODELNODEINDEX:
    case NMR_ERROR_INVALIDMODELCOORDINATEINDICES:
      what = "a triangle refers to a vertex that does not exist (an index out of range)";
      break;
    case NMR_ERROR_MODELCOORDINATEMISSING:
    case NMR_ERROR_INVALIDMODELCOORDINATES: what = "a vertex has a missing or invalid coordinate"; break;
    case NMR_ERROR_COULDNOTCREATEOPCPART: what = "a part the package refers to is missing"; break;
    case NMR_ERROR_NOBUILD: what = "the model has no build section: its XML is broken or cut short"; break;
    case NMR_ERROR_COULDNOTFINDCOMPONENTOBJECT:
      what = "a component refers to an object that is not defined before it (or to itself)";
      break;
    default: what = "the 3MF model cannot be read"; break;
  }
  return Error{file, fmt::format("{} (lib3mf: {}); export the file again", what, msg)};
}

template <class Getter>
std::string utf8(PLib3MFBase* p, Getter get) {
  ULONG need = 0;
  if (get(p, nullptr, 0, &need) != LIB3MF_OK || need == 0) return {};
  std::string s(need + 1, '\0');
  if (get(p, s.data(), need + 1, &need) != LIB3MF_OK) return {};
  s.resize(std::min<size_t>(need, s.size()));
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}

Eigen::Affine3d to_affine(const MODELTRANSFORM& m) {
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) t.matrix()(r, c) = m.m_fFields[r][c];
  return t;
}

double unit_mm(DWORD unit) {
  switch (unit) {
    case MODELUNIT_MICROMETER: return 0.001;
    case MODELUNIT_CENTIMETER: return 10;
    case MODELUNIT_INCH: return 25.4;
    case MODELUNIT_FOOT: return 304.8;
    case MODELUNIT_METER: return 1000;
    default: return 1;
  }
}

// The triangles of one object, its components flattened, as float corners in object mm.
class Collector {
 public:
  // `meshes`: the meshes the scanner read, by object id (their objects hold placeholders).
  Collector(const std::string& file, const threemf::Package& pkg, const std::map<uint32_t, threemf::MeshData>& meshes,
            Report& report)
      : file_(file), pkg_(pkg), meshes_(meshes), report_(report) {}

  Status collect(PLib3MFBase* obj, const Eigen::Affine3d& to_object, int depth) {
    if (depth > kMaxDepth) return Error{file_, "components are nested too deeply (a component refers to itself?)"};
    BOOL is_mesh = false, is_components = false;
    lib3mf_object_ismeshobject(obj, &is_mesh);
    lib3mf_object_iscomponentsobject(obj, &is_components);
    if (is_mesh) return mesh(obj, to_object);
    if (!is_components) return ok_status();
    DWORD n = 0;
    if (lib3mf_componentsobject_getcomponentcount(obj, &n) != LIB3MF_OK) return Error{file_, lib3mf_message(obj)};
    for (DWORD i = 0; i < n; ++i) {
      Handle component, child;
      if (lib3mf_componentsobject_getcomponent(obj, i, component.out()) != LIB3MF_OK ||
          lib3mf_component_getobjectresource(component.get(), child.out()) != LIB3MF_OK)
        return Error{file_, lib3mf_message(obj)};
      MODELTRANSFORM m{};
      Eigen::Affine3d t = Eigen::Affine3d::Identity();
      BOOL has = false;
      if (lib3mf_component_hastransform(component.get(), &has) == LIB3MF_OK && has &&
          lib3mf_component_gettransform(component.get(), &m) == LIB3MF_OK)
        t = to_affine(m);
      if (!(std::fabs(t.linear().determinant()) > kMinDeterminant))
        return Error{file_, fmt::format("component {} of an object has a transform that flattens it (determinant "
                                        "{:g}): it has no volume to print; fix the model",
                                        i + 1, t.linear().determinant())};
      if (Status s = collect(child.get(), to_object * t, depth + 1); !s) return s;
    }
    return ok_status();
  }

  std::vector<float>& corners() { return corners_; }

 private:
  Status mesh(PLib3MFBase* obj, const Eigen::Affine3d& t) {
    DWORD nv = 0, nt = 0, got = 0;
    if (lib3mf_meshobject_getvertexcount(obj, &nv) != LIB3MF_OK ||
        lib3mf_meshobject_gettrianglecount(obj, &nt) != LIB3MF_OK)
      return Error{file_, lib3mf_message(obj)};
    std::vector<MODELMESHVERTEX> v(nv);
    std::vector<MODELMESHTRIANGLE> tri(nt);
    if ((nv && lib3mf_meshobject_getvertices(obj, v.data(), nv, &got) != LIB3MF_OK) ||
        (nt && lib3mf_meshobject_gettriangleindices(obj, tri.data(), nt, &got) != LIB3MF_OK))
      return Error{file_, lib3mf_message(obj)};
    DWORD id = 0;
    lib3mf_resource_getresourceid(obj, &id);
    const std::string name = utf8(obj, lib3mf_object_getnameutf8);
    // A placeholder stands for a mesh the scanner read (threemf_meshes.h).
    if (nv == 3 && nt == 1)
      if (auto mark = threemf::placeholder_id(v[0].m_fPosition, v[1].m_fPosition, v[2].m_fPosition))
        if (auto it = meshes_.find(*mark); it != meshes_.end()) {
          const threemf::MeshData& d = it->second;
          const size_t n = d.triangles.size() / 3;
          return add(d.vertices.size() / 3, n, kept_triangles(id, n, name), t,
                     [&](size_t i) { return &d.vertices[3 * i]; }, [&](size_t i) { return &d.triangles[3 * i]; });
        }
    return add(nv, nt, kept_triangles(id, nt, name), t, [&](size_t i) { return v[i].m_fPosition; },
               [&](size_t i) { return tri[i].m_nIndices; });
  }

  // The triangles of a mesh of `nv` vertices (vertex(i): x, y, z) and `nt` triangles (triangle(i):
  // three vertex indices), those `keep` keeps, through `t` into corners.
  template <class Vertex, class Triangle>
  Status add(size_t nv, size_t nt, const std::vector<bool>& keep, const Eigen::Affine3d& t, Vertex vertex,
             Triangle triangle) {
    const bool mirror = t.linear().determinant() < 0;
    corners_.reserve(corners_.size() + 9 * nt);
    for (size_t i = 0; i < nt; ++i) {
      if (!keep.empty() && !keep[i]) continue;
      const auto* idx = triangle(i);
      for (int k = 0; k < 3; ++k)
        if (idx[k] >= nv)
          return Error{file_, fmt::format("triangle {} refers to vertex {}, but the object has {} vertices (an index "
                                          "out of range); the file is damaged — export it again",
                                          i + 1, idx[k], nv)};
      for (int k : {0, mirror ? 2 : 1, mirror ? 1 : 2}) {
        const float* p = vertex(idx[k]);
        const Eigen::Vector3d q = t * Eigen::Vector3d(p[0], p[1], p[2]);
        for (int d = 0; d < 3; ++d) corners_.push_back(static_cast<float>(q[d]));
      }
    }
    return ok_status();
  }

  // PrusaSlicer keeps modifiers and negative volumes as triangle ranges of the object's mesh.
  std::vector<bool> kept_triangles(DWORD id, size_t nt, const std::string& name) {
    const auto it = pkg_.prusa.find(id);
    if (it == pkg_.prusa.end() || it->second.volumes.empty()) return {};
    const threemf::PrusaObject& po = it->second;
    if (!po.name.empty() && !name.empty() && po.name != name) return {};  // not numbered as we assume
    std::vector<bool> keep(nt, true);
    std::string left_out;
    int count = 0;
    for (const auto& vol : po.volumes) {
      if (vol.type == "ModelPart") continue;
      if (vol.first > vol.last || vol.last >= nt) {
        report_.warn("3mf-ignored", file_,
                     fmt::format("PrusaSlicer's volume '{}' of object '{}' lies outside its triangles; the whole "
                                 "mesh is printed",
                                 vol.name, po.name));
        return {};
      }
      for (uint32_t i = vol.first; i <= vol.last; ++i) keep[i] = false;
      left_out += fmt::format("{}'{}' ({})", count++ ? ", " : "", vol.name, vol.type);
    }
    if (count)
      report_.warn("3mf-ignored", file_,
                   fmt::format("object '{}': {} left out — PrusaSlicer's modifiers, negative volumes and support "
                               "blockers or enforcers are not parts of the print here; write rules instead",
                               po.name.empty() ? name : po.name, left_out));
    return keep;
  }

  const std::string& file_;
  const threemf::Package& pkg_;
  const std::map<uint32_t, threemf::MeshData>& meshes_;
  Report& report_;
  std::vector<float> corners_;
};

// lib3mf's warnings, but for the missing UUIDs most writers leave out.
void forward_warnings(PLib3MFBase* reader, const std::string& file, Report& report) {
  DWORD n = 0;
  lib3mf_reader_getwarningcount(reader, &n);
  for (DWORD i = 0; i < n; ++i) {
    DWORD code = 0;
    ULONG need = 0;
    char buf[512] = {};
    if (lib3mf_reader_getwarningutf8(reader, i, &code, buf, sizeof buf, &need) != LIB3MF_OK) continue;
    if (code == NMR_ERROR_MISSINGUUID) continue;
    report.warn("3mf-warning", file, fmt::format("lib3mf: {}", buf));
  }
}

// The build items of a model read by lib3mf, one object each.
class Build {
 public:
  Build(const std::string& file, const threemf::Package& pkg, const std::map<uint32_t, threemf::MeshData>& meshes,
        double mm, Report& report)
      : file_(file), pkg_(pkg), meshes_(meshes), to_mm_(Eigen::Scaling(mm)), report_(report),
        stem_(std::filesystem::path(file).stem().string()) {}

  // Adds build item `number` (from 1); items that are no model, or empty, are left out with a warning.
  Status add(PLib3MFBase* item, int number) {
    Handle obj;
    if (lib3mf_builditem_getobjectresource(item, obj.out()) != LIB3MF_OK)
      return Error{file_, fmt::format("build item {}: {}", number, lib3mf_message(item))};
    DWORD id = 0, type = MODELOBJECTTYPE_MODEL;
    lib3mf_resource_getresourceid(obj.get(), &id);
    lib3mf_object_gettype(obj.get(), &type);
    std::string name = utf8(obj.get(), lib3mf_object_getnameutf8);
    if (name.empty()) {
      const auto p = pkg_.prusa.find(id);
      name = p != pkg_.prusa.end() && !p->second.name.empty() ? p->second.name : stem_;
    }
    const std::string where = fmt::format("{}, object '{}'", file_, name);
    if (type != MODELOBJECTTYPE_MODEL) {
      report_.warn("3mf-ignored", where, "not a model object (a support or surface object): left out");
      return ok_status();
    }
    MODELTRANSFORM m{};
    Eigen::Affine3d t = Eigen::Affine3d::Identity();
    BOOL has = false;
    if (lib3mf_builditem_hasobjecttransform(item, &has) == LIB3MF_OK && has &&
        lib3mf_builditem_getobjecttransform(item, &m) == LIB3MF_OK)
      t = to_affine(m);
    if (!(std::fabs(t.linear().determinant()) > kMinDeterminant))
      return Error{where, fmt::format("build item {} has a transform that flattens the object (determinant {:g}): "
                                      "it has no volume to print; fix the item's transform",
                                      number, t.linear().determinant())};
    Object o;
    o.name = name;
    o.file = file_;
    o.placed = true;
    o.copy = instances_[id]++;
    o.transform = to_mm_ * t * to_mm_.inverse();
    if (auto it = first_.find(id); it != first_.end()) {
      o.mesh = objects_[it->second].mesh;
    } else {
      Collector c(file_, pkg_, meshes_, report_);
      if (Status s = c.collect(obj.get(), to_mm_, 0); !s) return s;
      if (c.corners().empty()) {
        report_.warn("3mf-empty", where, "the object has no triangles to print: left out");
        return ok_status();
      }
      auto mesh = geo::weld_corners(c.corners(), where, report_);
      if (!mesh) return mesh.error();
      o.mesh = std::move(*mesh);
      o.mesh.name = name;
      first_[id] = objects_.size();
    }
    objects_.push_back(std::move(o));
    return ok_status();
  }

  std::vector<Object>& objects() { return objects_; }

 private:
  const std::string& file_;
  const threemf::Package& pkg_;
  const std::map<uint32_t, threemf::MeshData>& meshes_;
  const Eigen::Affine3d to_mm_;
  Report& report_;
  const std::string stem_;
  std::vector<Object> objects_;
  std::map<DWORD, int> instances_;  // resource id -> build items seen
  std::map<DWORD, size_t> first_;   // resource id -> index in objects_ of its first instance
};

}  // namespace

Result<std::vector<Object>> parse_3mf(std::string_view bytes, const std::string& file, Report& report) {
  auto pkg = threemf::inspect_package(bytes, file, report);
  if (!pkg) return pkg.error();
  const std::string_view whole = pkg->repacked.empty() ? bytes : std::string_view(pkg->repacked);
  // The plain meshes are read here, the rest by lib3mf from the package without them.
  threemf::SplitModel split;
  std::string light = threemf::without_meshes(whole, pkg->repacked.empty() ? pkg->root : "3D/3dmodel.model", file, split);
  const std::string_view input = light.empty() ? whole : std::string_view(light);
  Handle model, reader;
  if (lib3mf_createmodel(model.out()) != LIB3MF_OK ||
      lib3mf_model_queryreader(model.get(), MODELREADERCLASS_3MF, reader.out()) != LIB3MF_OK)
    return Error{file, "lib3mf could not start"};
  if (lib3mf_reader_readfrombuffer(reader.get(), reinterpret_cast<BYTE*>(const_cast<char*>(input.data())),
                                   input.size()) != LIB3MF_OK)
    return read_error(file, reader.get());
  forward_warnings(reader.get(), file, report);
  DWORD unit = MODELUNIT_MILLIMETER;
  lib3mf_model_getunit(model.get(), &unit);
  Handle items;
  if (lib3mf_model_getbuilditems(model.get(), items.out()) != LIB3MF_OK) return read_error(file, model.get());
  Build build(file, *pkg, split.meshes, unit_mm(unit), report);
  BOOL has = false;
  int number = 0;
  while (lib3mf_builditemiterator_movenext(items.get(), &has) == LIB3MF_OK && has) {
    Handle item;
    if (lib3mf_builditemiterator_getcurrent(items.get(), item.out()) != LIB3MF_OK)
      return Error{file, fmt::format("build item {}: {}", number + 1, lib3mf_message(items.get()))};
    if (Status s = build.add(item.get(), ++number); !s) return s.error();
  }
  if (build.objects().empty() && number == 0)
    if (Status s = threemf::check_model_xml(whole, pkg->repacked.empty() ? pkg->root : "3D/3dmodel.model", file); !s)
      return s.error();
  if (build.objects().empty())
    return Error{file, number == 0 ? "the 3MF has no build items: nothing to print"
                                   : "no build item of the 3MF has anything to print"};
  return std::move(build.objects());
}

}  // namespace tranche::plate
