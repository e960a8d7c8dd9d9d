#include "geometry/plate/threemf_package.h"

#include <fmt/format.h>

#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <optional>
#include <pugixml.hpp>
#include <set>

#include "geometry/plate/zip.h"

namespace tranche::plate::threemf {
namespace {

constexpr uint64_t kPartLimit = uint64_t{1} << 31;  // bytes of one XML part we inflate ourselves
constexpr uint64_t kReadAhead = uint64_t{4} << 20;   // a model part from this size on is inflated ahead
constexpr const char* kProductionNs = "http://schemas.microsoft.com/3dmanufacturing/production/2015/06";
constexpr int kMaxDepth = 16;  // nested components
constexpr const char* kContentTypes =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Types "
    "xmlns=\"http://schemas.openxmlformats.org/package/2006/content-types\"><Default Extension=\"rels\" "
    "ContentType=\"application/vnd.openxmlformats-package.relationships+xml\"/><Default Extension=\"model\" "
    "ContentType=\"application/vnd.ms-package.3dmanufacturing-3dmodel+xml\"/></Types>";
constexpr const char* kRels =
    "<?xml version=\"1.0\" encoding=\"UTF-8\"?><Relationships "
    "xmlns=\"http://schemas.openxmlformats.org/package/2006/relationships\"><Relationship "
    "Target=\"/3D/3dmodel.model\" Id=\"rel0\" "
    "Type=\"http://schemas.microsoft.com/3dmanufacturing/2013/01/3dmodel\"/></Relationships>";

bool ends_with_ci(std::string_view s, std::string_view tail) {
  if (s.size() < tail.size()) return false;
  for (size_t i = 0; i < tail.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(s[s.size() - tail.size() + i])) !=
        std::tolower(static_cast<unsigned char>(tail[i])))
      return false;
  return true;
}

// A package of `model` alone, as 3D/3dmodel.model, with the content types of `zip`.
Result<std::string> single_part_package(const ZipArchive& zip, std::string model) {
  std::string types = kContentTypes;
  if (const ZipEntry* ct = zip.find("[Content_Types].xml")) {
    auto t = zip.read(*ct, kPartLimit);
    if (!t) return t.error();
    types = std::move(*t);
  }
  return write_stored_zip({{"[Content_Types].xml", types}, {"_rels/.rels", kRels}, {"3D/3dmodel.model", model}});
}

std::string_view unslashed(std::string_view part) { return part.starts_with('/') ? part.substr(1) : part; }

std::string listing(const ZipArchive& zip) {
  std::string out;
  const auto& e = zip.entries();
  for (size_t i = 0; i < e.size() && i < 6; ++i) out += (i ? ", " : "") + e[i].name;
  if (e.size() > 6) out += fmt::format(" and {} more", e.size() - 6);
  return e.empty() ? "nothing" : out;
}

std::string not_3mf(const ZipArchive& zip, const std::string& why) {
  bool model_inside = false;
  for (const auto& e : zip.entries())
    for (const char* ext : {".stl", ".3mf", ".obj"}) model_inside |= ends_with_ci(e.name, ext);
  return fmt::format("this is a ZIP archive but not a 3MF package: {} (it holds {}){}", why, listing(zip),
                     model_inside ? "; extract the model from the archive and slice that" : "");
}

Result<pugi::xml_document> parse_part(const ZipArchive& zip, const ZipEntry& entry, const std::string& file) {
  auto text = zip.read(entry, kPartLimit);
  if (!text) return text.error();
  pugi::xml_document doc;
  const pugi::xml_parse_result r = doc.load_buffer(text->data(), text->size());
  if (!r)
    return Error{file + ", " + entry.name,
                 fmt::format("broken XML at byte {}: {}; export the file again", r.offset, r.description())};
  return doc;
}

// The model part _rels/.rels names as the 3D model; `dangling` is set when it also names parts
// the package lacks (PrusaSlicer's command line names a thumbnail it does not write), which
// lib3mf 1.8 refuses to read.
Result<std::string> root_part(const ZipArchive& zip, const std::string& file, bool& dangling) {
  const ZipEntry* rels = zip.find("_rels/.rels");
  if (!rels) return Error{file, not_3mf(zip, "it has no _rels/.rels")};
  auto doc = parse_part(zip, *rels, file);
  if (!doc) return doc.error();
  for (auto r : doc->child("Relationships").children("Relationship"))
    dangling |= !zip.find(r.attribute("Target").as_string());
  for (auto r : doc->child("Relationships").children("Relationship")) {
    if (!ends_with_ci(r.attribute("Type").as_string(), "/3dmodel")) continue;
    std::string target = r.attribute("Target").as_string();
    while (!target.empty() && target.front() == '/') target.erase(0, 1);
    if (!zip.find(target))
      return Error{file, fmt::format("the 3MF package has no model part '{}', which _rels/.rels names (it holds {}); "
                                     "the file is damaged — export it again",
                                     target, listing(zip))};
    return target;
  }
  return Error{file, not_3mf(zip, "_rels/.rels names no 3D model")};
}

// PrusaSlicer: volumes (triangle ranges) and their types; object settings are only noted.
Status read_prusa(const ZipArchive& zip, const ZipEntry& entry, const std::string& file, Package& pkg,
                  Report& report) {
  auto doc = parse_part(zip, entry, file);
  if (!doc) return doc.error();
  std::set<std::string> settings;
  for (auto o : doc->child("config").children("object")) {
    PrusaObject& po = pkg.prusa[o.attribute("id").as_uint()];
    for (auto m : o.children("metadata")) {
      const std::string key = m.attribute("key").as_string();
      if (key == "name") po.name = m.attribute("value").as_string();
      else settings.insert(key);
    }
    for (auto v : o.children("volume")) {
      Volume vol{v.attribute("firstid").as_uint(), v.attribute("lastid").as_uint(), "ModelPart", ""};
      for (auto m : v.children("metadata")) {
        const std::string key = m.attribute("key").as_string(), value = m.attribute("value").as_string();
        if (key == "volume_type") vol.type = value;
        else if (key == "modifier" && value == "1") vol.type = "ParameterModifier";
        else if (key == "name") vol.name = value;
      }
      po.volumes.push_back(vol);
    }
  }
  if (!settings.empty()) {
    std::string keys;
    for (const auto& k : settings) keys += (keys.empty() ? "" : ", ") + k;
    report.warn("3mf-ignored", file + ", " + entry.name,
                fmt::format("PrusaSlicer's per-object settings ({}) are ignored; Tranche's rules decide every "
                            "setting",
                            keys));
  }
  return ok_status();
}

// OrcaSlicer / Bambu Studio: object names, and which components are parts (normal_part).
struct OrcaObject {
  std::string name;
  std::map<uint32_t, std::string> part_subtype;  // component object id -> subtype
};

Result<std::map<uint32_t, OrcaObject>> read_orca(const ZipArchive& zip, const ZipEntry& entry,
                                                  const std::string& file, Report& report) {
  auto doc = parse_part(zip, entry, file);
  if (!doc) return doc.error();
  std::map<uint32_t, OrcaObject> out;
  std::set<std::string> settings;
  for (auto o : doc->child("config").children("object")) {
    OrcaObject& oo = out[o.attribute("id").as_uint()];
    for (auto m : o.children("metadata")) {
      const std::string key = m.attribute("key").as_string();
      if (key == "name") oo.name = m.attribute("value").as_string();
      else if (key != "extruder") settings.insert(key);
    }
    for (auto p : o.children("part"))
      oo.part_subtype[p.attribute("id").as_uint()] = p.attribute("subtype").as_string("normal_part");
  }
  if (!settings.empty()) {
    std::string keys;
    for (const auto& k : settings) keys += (keys.empty() ? "" : ", ") + k;
    report.warn("3mf-ignored", file + ", " + entry.name,
                fmt::format("the slicer's per-object settings ({}) are ignored; Tranche's rules decide every "
                            "setting",
                            keys));
  }
  return out;
}

void note_print_settings(const ZipArchive& zip, const std::string& file, Report& report) {
  std::vector<std::string> found;
  for (const auto& e : zip.entries()) {
    for (const char* name : {"Metadata/Slic3r_PE.config", "Metadata/project_settings.config",
                             "Metadata/Slic3r_PE_layer_heights_profile.txt", "Metadata/layer_heights_profile.txt",
                             "Metadata/Prusa_Slicer_layer_config_ranges.xml", "Metadata/layer_config_ranges.xml"})
      if (e.name.size() == std::string_view(name).size() && ends_with_ci(e.name, name)) found.push_back(e.name);
    if (e.name.starts_with("Cura/")) found.push_back(e.name);
  }
  if (found.empty()) return;
  std::string names;
  for (const auto& n : found) names += (names.empty() ? "" : ", ") + n;
  report.warn("3mf-ignored", file,
              fmt::format("the slicer settings stored in this 3MF ({}) are ignored: Tranche slices with its "
                          "printer and material profiles and your rules",
                          names));
}

// Inlines the objects of other model parts (components with p:path) into the root model, and
// applies Orca/Bambu part types and names, so that lib3mf 1.8 reads one model part.
class Repacker {
 public:
  Repacker(const ZipArchive& zip, std::string root, const std::string& file, Report& report)
      : zip_(zip), root_(std::move(root)), file_(file), report_(report) {}

  Result<std::string> run(const std::map<uint32_t, OrcaObject>& orca) {
    auto doc = parse_part(zip_, *zip_.find(root_), file_);
    if (!doc) return doc.error();
    root_doc_ = std::move(*doc);
    model_ = root_doc_.child("model");
    resources_ = model_.child("resources");
    path_attr_ = production_prefix(model_) + ":path";
    for (auto o : resources_.children("object")) next_id_ = std::max(next_id_, o.attribute("id").as_uint() + 1);
    int left_out = 0;
    std::vector<pugi::xml_node> root_objects(resources_.children("object").begin(), resources_.children("object").end());
    for (auto o : root_objects) {
      const uint32_t id = o.attribute("id").as_uint();
      const auto it = orca.find(id);
      if (it != orca.end() && !it->second.name.empty() && !o.attribute("name"))
        o.append_attribute("name") = it->second.name.c_str();
      std::vector<pugi::xml_node> drop;
      for (auto c : o.child("components").children("component")) {
        if (it != orca.end()) {
          const auto sub = it->second.part_subtype.find(c.attribute("objectid").as_uint());
          if (sub != it->second.part_subtype.end() && sub->second != "normal_part") {
            drop.push_back(c);
            continue;
          }
        }
        if (Status s = follow(c, "/" + root_, 0); !s) return s.error();
      }
      for (auto c : drop) c.parent().remove_child(c);
      left_out += static_cast<int>(drop.size());
    }
    if (left_out > 0)
      report_.warn("3mf-ignored", file_,
                   fmt::format("{} volume{} that {} not part of the print (modifiers, negative volumes, support "
                               "blockers or enforcers) {} left out",
                               left_out, left_out == 1 ? "" : "s", left_out == 1 ? "is" : "are",
                               left_out == 1 ? "is" : "are"));
    pugi::xml_node anchor;
    for (auto& n : staged_) {
      anchor = anchor ? resources_.insert_copy_after(n, anchor) : resources_.prepend_copy(n);
    }
    struct Writer : pugi::xml_writer {
      std::string out;
      void write(const void* data, size_t size) override { out.append(static_cast<const char*>(data), size); }
    } w;
    root_doc_.save(w, "", pugi::format_raw);
    return single_part_package(zip_, std::move(w.out));
  }

 private:
  static std::string production_prefix(pugi::xml_node model) {
    for (auto a : model.attributes()) {
      const std::string_view name = a.name();
      if (name.starts_with("xmlns:") && std::string_view(a.value()) == kProductionNs)
        return std::string(name.substr(6));
    }
    return "p";
  }

  // Points component `c` (of a part at `here`) at an object of the root model, importing it.
  Status follow(pugi::xml_node c, const std::string& here, int depth) {
    pugi::xml_attribute path = c.attribute(path_attr_.c_str());
    const std::string part = path ? path.as_string() : here;
    if (part == "/" + root_ && depth == 0) return ok_status();
    auto id = import(part, c.attribute("objectid").as_uint(), depth + 1);
    if (!id) return id.error();
    c.attribute("objectid") = *id;
    if (path) c.remove_attribute(path);
    return ok_status();
  }

  Result<uint32_t> import(const std::string& part, uint32_t id, int depth) {
    if (depth > kMaxDepth) return Error{file_, "components are nested too deeply (a component refers to itself?)"};
    if (auto it = imported_.find({part, id}); it != imported_.end()) return it->second;
    auto doc = part_doc(part);
    if (!doc) return doc.error();
    pugi::xml_node found;
    for (auto o : (*doc)->child("model").child("resources").children("object"))
      if (o.attribute("id").as_uint() == id) found = o;
    if (!found)
      return Error{file_ + ", " + std::string(unslashed(part)),
                   fmt::format("a component refers to object {}, which this model part does not have", id)};
    pugi::xml_node copy = staging_.append_copy(found);
    for (auto c : copy.child("components").children("component"))
      if (Status s = follow(c, part, depth); !s) return s.error();
    const uint32_t fresh = next_id_++;
    copy.attribute("id") = fresh;
    staged_.push_back(copy);
    imported_[{part, id}] = fresh;
    return fresh;
  }

  Result<pugi::xml_document*> part_doc(const std::string& part) {
    if (auto it = parts_.find(part); it != parts_.end()) return it->second.get();
    const ZipEntry* e = zip_.find(part);
    if (!e)
      return Error{file_, fmt::format("a component refers to the model part '{}', which the package does not have; "
                                      "the file is damaged — export it again",
                                      part)};
    auto doc = parse_part(zip_, *e, file_);
    if (!doc) return doc.error();
    auto owned = std::make_unique<pugi::xml_document>(std::move(*doc));
    for (auto a : owned->child("model").attributes()) {  // the prefixes its objects use
      const std::string_view name = a.name();
      if (name.starts_with("xmlns:") && !model_.attribute(a.name())) model_.append_attribute(a.name()) = a.value();
    }
    return (parts_[part] = std::move(owned)).get();
  }

  const ZipArchive& zip_;
  std::string root_;
  const std::string& file_;
  Report& report_;
  pugi::xml_document root_doc_, staging_;
  pugi::xml_node model_, resources_;
  std::string path_attr_;
  uint32_t next_id_ = 1;
  std::map<std::string, std::unique_ptr<pugi::xml_document>> parts_;
  std::map<std::pair<std::string, uint32_t>, uint32_t> imported_;
  std::vector<pugi::xml_node> staged_;
};

// A ZIP entry inflated ahead on a thread of its own, a few chunks at a time, while the caller
// scans what came before, where it was inflated: inflating (one thread, as deflate is) and
// reading the meshes overlap.
class ReadAhead : public Chunks {
 public:
  // The chunks in one piece of memory, in huge pages where the system grants them (ZipBytes: not
  // zeroed, as every byte is written before it is read).
  explicit ReadAhead(ZipStream& in) : in_(in), memory_(kChunks * (kRoom + kChunk)) {
    for (int i = 0; i < kChunks; ++i) free_.push_back(memory_.data() + i * (kRoom + kChunk));
    thread_ = std::thread([this] { run(); });
  }
  ReadAhead(const ReadAhead&) = delete;
  ReadAhead& operator=(const ReadAhead&) = delete;
  ~ReadAhead() override {
    {
      std::lock_guard lock(m_);
      stop_ = true;
    }
    cv_.notify_all();
    thread_.join();
  }

  // Nothing for an error (its words are the whole read's to give).
  std::optional<Chunk> next() override {
    std::unique_lock lock(m_);
    cv_.wait(lock, [&] { return !ready_.empty() || ended_ || failed_; });
    if (ready_.empty()) {
      if (failed_) return std::nullopt;
      return Chunk{};
    }
    const Chunk c = ready_.front();
    ready_.pop_front();
    return c;
  }
  void give_back(char* data) override {
    {
      std::lock_guard lock(m_);
      free_.push_back(data);
    }
    cv_.notify_all();
  }

 private:
  static constexpr int kChunks = 4;
  static constexpr size_t kChunk = size_t{1} << 20;

  void run() {
    for (;;) {
      Chunk c;
      {
        std::unique_lock lock(m_);
        cv_.wait(lock, [&] { return !free_.empty() || stop_; });
        if (stop_) return;
        c.data = free_.back();
        free_.pop_back();
      }
      bool end = false, bad = false;
      try {  // an exception must not leave this thread: it only fails the stream (read whole then)
        while (c.size < kChunk) {
          auto got = in_.read(c.data + kRoom + c.size, kChunk - c.size);
          if (!got) {
            bad = true;
            break;
          }
          if (*got == 0) {
            end = true;
            break;
          }
          c.size += *got;
        }
      } catch (...) {
        bad = true;
      }
      {
        std::lock_guard lock(m_);
        if (c.size > 0 && !bad) ready_.push_back(c);
        else free_.push_back(c.data);
        ended_ = end;
        failed_ = bad;
      }
      cv_.notify_all();
      if (end || bad) return;
    }
  }

  ZipStream& in_;
  ZipBytes memory_;
  std::mutex m_;
  std::condition_variable cv_;
  std::deque<Chunk> ready_;
  std::vector<char*> free_;
  bool ended_ = false, failed_ = false, stop_ = false;
  std::thread thread_;  // last: started once the rest is made
};

}  // namespace

Result<Package> inspect_package(std::string_view bytes, const std::string& file, Report& report) {
  auto zip = ZipArchive::open(bytes, file);
  if (!zip) return zip.error();
  bool dangling = false;
  auto root = root_part(*zip, file, dangling);
  if (!root) return root.error();
  Package pkg;
  pkg.root = *root;
  note_print_settings(*zip, file, report);
  if (const ZipEntry* e = zip->find("Metadata/Slic3r_PE_model.config"))
    if (Status s = read_prusa(*zip, *e, file, pkg, report); !s) return s.error();
  std::map<uint32_t, OrcaObject> orca;
  const ZipEntry* orca_entry = zip->find("Metadata/model_settings.config");
  if (orca_entry) {
    auto o = read_orca(*zip, *orca_entry, file, report);
    if (!o) return o.error();
    orca = std::move(*o);
  }
  bool other_parts = false;
  for (const auto& e : zip->entries()) other_parts |= ends_with_ci(e.name, ".model") && e.name != pkg.root;
  if (other_parts || orca_entry) {
    Repacker r(*zip, pkg.root, file, report);
    auto packed = r.run(orca);
    if (!packed) return packed.error();
    pkg.repacked = std::move(*packed);
  } else if (dangling) {  // the model part alone, under relationships that name only it
    auto model = zip->read(*zip->find(pkg.root), kPartLimit);
    if (!model) return model.error();
    auto packed = single_part_package(*zip, std::move(*model));
    if (!packed) return packed.error();
    pkg.repacked = std::move(*packed);
  }
  return pkg;
}

Result<std::string> without_meshes(std::string_view bytes, const std::string& root, const std::string& file,
                                   SplitModel& split) {
  auto zip = ZipArchive::open(bytes, file);
  const ZipEntry* model = zip ? zip->find(root) : nullptr;
  if (!model) return std::string();
  // The part read in a stream, its meshes as they come; read whole (split_meshes) when the stream
  // cannot say what split_meshes would (threemf_meshes.h), or the part is damaged (the whole read
  // then says how).
  // A large part is inflated ahead on a second thread.
  std::optional<SplitModel> streamed;
  if (auto in = zip->stream(*model, kPartLimit)) {
    if (model->size >= kReadAhead) {
      ReadAhead ahead(*in);
      streamed = split_meshes_streamed(ahead);
    } else {
      streamed = split_meshes_streamed([&](char* out, size_t n) -> std::optional<size_t> {
        auto got = in->read(out, n);
        return got ? std::optional<size_t>(*got) : std::nullopt;
      });
    }
  }
  if (streamed) {
    split = std::move(*streamed);
  } else {
    auto xml = zip->read_bytes(*model, kPartLimit);
    if (!xml) return xml.error();
    split = split_meshes(xml->view());
    if (!split.bad.empty()) {
      Error e{file + ", " + model->name, split.bad + "; the file is damaged — export it again"};
      split = SplitModel{};
      return e;
    }
  }
  if (split.meshes.empty()) return std::string();
  std::vector<std::pair<std::string, std::string>> parts;
  for (const ZipEntry& e : zip->entries()) {
    if (&e == model) {
      parts.emplace_back(e.name, std::move(split.model));
      continue;
    }
    auto part = zip->read(e, kPartLimit);
    if (!part) {
      split = SplitModel{};
      return part.error();
    }
    parts.emplace_back(e.name, std::move(*part));
  }
  return write_stored_zip(parts);
}

Status check_model_xml(std::string_view bytes, const std::string& root, const std::string& file) {
  auto zip = ZipArchive::open(bytes, file);
  if (!zip) return zip.error();
  const ZipEntry* e = zip->find(root);
  if (!e) return ok_status();
  auto doc = parse_part(*zip, *e, file);
  if (!doc) return doc.error();
  return ok_status();
}

}  // namespace tranche::plate::threemf
