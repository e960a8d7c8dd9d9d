#include "geometry/plate/threemf.h"

#include <Common/NMR_ErrorConst.h>
#include <Model/COM/NMR_DLLInterfaces.h>
#include <fmt/format.h>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>

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
  Collector(const std::string& file, const threemf::Package& pkg, std::map<uint32_t, threemf::MeshData>& meshes,
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

  // The triangles the object will have.
  size_t triangle_count() const { return triangle_count_; }

  // The meshes collected, for one object.
  struct Piece {
    threemf::MeshData* data;                 // the scanner's mesh, or `own`
    std::unique_ptr<threemf::MeshData> own;  // a mesh lib3mf read
    std::vector<bool> keep;                  // the triangles kept; empty: all
    Eigen::Affine3d t;                       // to object mm
  };
  std::vector<Piece>& pieces() { return pieces_; }

  // The object's triangles from `pieces`: x, y, z of each vertex (object mm) in `vertices`, three
  // vertex indices per triangle in `triangles` (as the corners would be: mirrored by a mirroring
  // transform).
  static void gather(const std::vector<Piece>& pieces, std::vector<float>& vertices,
                     std::vector<std::array<uint32_t, 3>>& triangles) {
    size_t nv = 0, nt = 0;
    for (const Piece& p : pieces) {
      nv += p.data->vertices.size();
      nt += p.data->triangles.size();
    }
    vertices.reserve(3 * nv);
    triangles.reserve(nt);
    for (const Piece& p : pieces) {
      const bool mirror = p.t.linear().determinant() < 0;
      const uint32_t base = static_cast<uint32_t>(vertices.size() / 3);
      for (size_t i = 0, n = p.data->triangles.size(); i < n; ++i) {
        if (!p.keep.empty() && !p.keep[i]) continue;
        const auto& tri = p.data->triangles[i];
        triangles.push_back({base + tri[0], base + tri[mirror ? 2 : 1], base + tri[mirror ? 1 : 2]});
      }
      const size_t at = vertices.size();
      vertices.resize(at + 3 * p.data->vertices.size());
      float* out = vertices.data() + at;
      for (const geo::Vec3& in : p.data->vertices) {
        const Eigen::Vector3d q = p.t * Eigen::Vector3d(in.x, in.y, in.z);
        for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(q[k]);
        out += 3;
      }
    }
  }

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
    // A placeholder stands for a mesh the scanner read (threemf_meshes.h), its indices checked.
    if (nv == 3 && nt == 1)
      if (auto mark = threemf::placeholder_id(v[0].m_fPosition, v[1].m_fPosition, v[2].m_fPosition))
        if (auto it = meshes_.find(*mark); it != meshes_.end())
          return add(&it->second, nullptr, kept_triangles(id, it->second.triangles.size(), name), t);
    auto own = std::make_unique<threemf::MeshData>();
    own->vertices.reserve(nv);
    for (const auto& p : v) own->vertices.push_back(geo::Vec3{p.m_fPosition[0], p.m_fPosition[1], p.m_fPosition[2]});
    own->triangles.reserve(nt);
    for (const auto& p : tri) own->triangles.push_back({p.m_nIndices[0], p.m_nIndices[1], p.m_nIndices[2]});
    std::vector<bool> keep = kept_triangles(id, nt, name);
    for (size_t i = 0; i < nt; ++i) {
      if (!keep.empty() && !keep[i]) continue;
      for (int k = 0; k < 3; ++k)
        if (tri[i].m_nIndices[k] >= nv)
          return Error{file_, fmt::format("triangle {} refers to vertex {}, but the object has {} vertices (an index "
                                          "out of range); the file is damaged — export it again",
                                          i + 1, tri[i].m_nIndices[k], nv)};
    }
    threemf::MeshData* d = own.get();
    return add(d, std::move(own), std::move(keep), t);
  }

  // A mesh `d` (whose indices are in range), those of its triangles `keep` keeps, through `t`.
  Status add(threemf::MeshData* d, std::unique_ptr<threemf::MeshData> own, std::vector<bool> keep,
             const Eigen::Affine3d& t) {
    vertex_count_ += d->vertices.size();
    if (vertex_count_ > UINT32_MAX)
      return Error{file_, fmt::format("{} vertices in one object are more than Tranche can load", vertex_count_)};
    const size_t nt = d->triangles.size();
    triangle_count_ += keep.empty() ? nt : static_cast<size_t>(std::count(keep.begin(), keep.end(), true));
    pieces_.push_back(Piece{d, std::move(own), std::move(keep), t});
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
  std::map<uint32_t, threemf::MeshData>& meshes_;
  Report& report_;
  std::vector<Piece> pieces_;
  size_t vertex_count_ = 0, triangle_count_ = 0;
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

// The build items of a model read by lib3mf, one object each. Items are read in order; the
// welding of their meshes waits for finish(), which welds all objects at once, in parallel, and
// then reports each item's warnings and the first error as reading them one by one would have.
class Build {
 public:
  Build(const std::string& file, const threemf::Package& pkg, std::map<uint32_t, threemf::MeshData>& meshes,
        double mm)
      : file_(file), pkg_(pkg), meshes_(meshes), to_mm_(Eigen::Scaling(mm)),
        stem_(std::filesystem::path(file).stem().string()) {}

  // Adds build item `number` (from 1); items that are no model, or empty, are left out with a warning.
  Status add(PLib3MFBase* item, int number) {
    Report& report = log_.emplace_back();  // this item's warnings
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
    std::string where = fmt::format("{}, object '{}'", file_, name);
    if (type != MODELOBJECTTYPE_MODEL) {
      report.warn("3mf-ignored", where, "not a model object (a support or surface object): left out");
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
      copies_.emplace_back(objects_.size(), it->second);
    } else {
      Collector c(file_, pkg_, meshes_, report);
      if (Status s = c.collect(obj.get(), to_mm_, 0); !s) return s;
      if (c.triangle_count() == 0) {
        report.warn("3mf-empty", where, "the object has no triangles to print: left out");
        return ok_status();
      }
      first_[id] = objects_.size();
      welds_.push_back(Weld{objects_.size(), log_.size() - 1, std::move(where), std::move(c.pieces()), std::nullopt});
    }
    objects_.push_back(std::move(o));
    return ok_status();
  }

  // Welds the objects' meshes; the warnings go to `report`. `stop`: the error reading the items
  // ended with, reported after the items before it, as their welding would have come first.
  Status finish(Status stop, Report& report) {
    // A mesh only one piece of one object uses may give its memory to the object's mesh.
    std::map<const threemf::MeshData*, int> uses;
    for (const Weld& w : welds_)
      for (const Collector::Piece& p : w.pieces) ++uses[p.data];
    tbb::parallel_for(size_t{0}, welds_.size(), [&](size_t i) {
      Weld& w = welds_[i];
      // A mesh the scanner read (in the welder's order already), taken whole, in mm, unturned: only
      // the welding's last step is left (the identity would give the same floats, but for -0,
      // which the welding makes +0 either way). Any other: gathered, through its transform.
      if (w.pieces.size() == 1 && w.pieces[0].keep.empty() && w.pieces[0].t.matrix() == Eigen::Matrix4d::Identity() &&
          w.pieces[0].data->ordered) {
        threemf::MeshData& d = *w.pieces[0].data;
        w.mesh = uses.at(&d) == 1 ? geo::weld_ordered(std::move(d.vertices), std::move(d.triangles), w.where,
                                                      log_[w.item], d.degenerate)
                                  : geo::weld_ordered(std::vector(d.vertices), std::vector(d.triangles), w.where,
                                                      log_[w.item], d.degenerate);
        w.pieces.clear();
        return;
      }
      std::vector<float> vertices;
      std::vector<std::array<uint32_t, 3>> triangles;
      Collector::gather(w.pieces, vertices, triangles);
      w.pieces.clear();
      w.mesh = geo::weld_indexed(vertices, std::move(triangles), w.where, log_[w.item]);
    });
    size_t next = 0;  // of welds_, in item order
    for (size_t item = 0; item < log_.size(); ++item) {
      for (const Warning& w : log_[item].warnings()) report.warn(w.code, w.where, w.message);
      if (next < welds_.size() && welds_[next].item == item) {
        Weld& w = welds_[next++];
        if (!*w.mesh) return w.mesh->error();
        objects_[w.object].mesh = std::move(**w.mesh);
        objects_[w.object].mesh.name = objects_[w.object].name;
      }
    }
    if (!stop) return stop;
    for (const auto& [copy, first] : copies_) objects_[copy].mesh = objects_[first].mesh;
    return ok_status();
  }

  std::vector<Object>& objects() { return objects_; }

 private:
  struct Weld {
    size_t object;  // in objects_
    size_t item;    // in log_
    std::string where;
    std::vector<Collector::Piece> pieces;
    std::optional<Result<geo::Mesh>> mesh;
  };

  const std::string& file_;
  const threemf::Package& pkg_;
  std::map<uint32_t, threemf::MeshData>& meshes_;
  const Eigen::Affine3d to_mm_;
  const std::string stem_;
  std::vector<Object> objects_;
  std::deque<Report> log_;  // by build item read
  std::deque<Weld> welds_;  // a deque: a Weld is not copied, and its move may throw
  std::vector<std::pair<size_t, size_t>> copies_;  // (object, object of its first instance)
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
  auto light = threemf::without_meshes(whole, pkg->repacked.empty() ? pkg->root : "3D/3dmodel.model", file, split);
  if (!light) return light.error();
  const std::string_view input = light->empty() ? whole : std::string_view(*light);
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
  Build build(file, *pkg, split.meshes, unit_mm(unit));
  BOOL has = false;
  int number = 0;
  Status stop = ok_status();
  while (stop && lib3mf_builditemiterator_movenext(items.get(), &has) == LIB3MF_OK && has) {
    Handle item;
    if (lib3mf_builditemiterator_getcurrent(items.get(), item.out()) != LIB3MF_OK)
      stop = Error{file, fmt::format("build item {}: {}", number + 1, lib3mf_message(items.get()))};
    else
      stop = build.add(item.get(), ++number);
  }
  if (Status s = build.finish(std::move(stop), report); !s) return s.error();
  if (build.objects().empty() && number == 0)
    if (Status s = threemf::check_model_xml(whole, pkg->repacked.empty() ? pkg->root : "3D/3dmodel.model", file); !s)
      return s.error();
  if (build.objects().empty())
    return Error{file, number == 0 ? "the 3MF has no build items: nothing to print"
                                   : "no build item of the 3MF has anything to print"};
  return std::move(build.objects());
}

}  // namespace tranche::plate
