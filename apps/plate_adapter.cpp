#include "apps/plate_adapter.h"

#include <stdlib.h>

#include <filesystem>
#include <fstream>

#include "geometry/mesh/stl.h"
#include "geometry/plate/detect.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"

namespace tranche::app {
namespace {

// A directory of our own under the system's temporary directory, removed with everything in it.
class ScratchDir {
 public:
  ScratchDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "tranche-plate-XXXXXX").string();
    if (mkdtemp(pattern.data())) path_ = pattern;
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  ~ScratchDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

void replace_all(std::string& s, const std::string& from, const std::string& to) {
  for (size_t at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size())) s.replace(at, from.size(), to);
}

// One STL file whose object is not turned or scaled: the pipeline reads the file itself.
bool as_is(const plate::Plate& plate, const std::vector<std::string>& files) {
  if (files.size() != 1 || plate.objects.size() != 1) return false;
  if (plate.objects[0].transform.linear() != Eigen::Matrix3d::Identity()) return false;
  std::ifstream in(files[0], std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(files[0], ec);
  return !ec && plate::detect_format(head, size).format == plate::Format::Stl;
}

}  // namespace

Result<plate::Bed> bed_from_profile(const pipeline::SliceOptions& options, const vm::RuleSet* rules) {
  std::vector<std::pair<std::string, std::string>> plain;
  for (const auto& [k, v] : options.sets)
    if (ctx::is_plain_override(k, v)) plain.emplace_back(k, v);
  auto cascade = ctx::Cascade::create(plain, rules, rules, rules);
  if (!cascade) return cascade.error();
  auto props = (*cascade)->print_props(ctx::Context{});
  if (!props) return props.error();
  plate::Bed bed;
  bed.size_x_mm = (*props)[schema::PropId::BedSizeX];
  bed.size_y_mm = (*props)[schema::PropId::BedSizeY];
  return bed;
}

Result<pipeline::SliceSummary> slice_plate(const pipeline::SliceOptions& options, const plate::Plate& plate,
                                           const std::vector<std::string>& files, const vm::RuleSet* rules,
                                           Report& report) {
  pipeline::SliceOptions o = options;
  if (as_is(plate, files)) {
    o.model = files[0];
    return pipeline::run_slice(o, rules, report);
  }
  ScratchDir dir;
  if (dir.path().empty()) return Error{"", "cannot make a temporary directory for the plate"};
  std::string label, stem;
  for (const auto& f : files) {
    if (!label.empty()) label.append(" + ");
    label.append(f);
    if (!stem.empty()) stem.push_back('+');
    stem.append(std::filesystem::path(f).stem().string());
  }
  o.model = dir.path() + "/" + (stem.size() > 100 ? "plate" : stem) + ".stl";
  if (Status s = geo::write_stl_binary(o.model, plate::merged_mesh(plate)); !s) return s.error();
  Report inner;
  auto result = pipeline::run_slice(o, rules, inner);
  for (auto w : inner.warnings()) {
    replace_all(w.where, o.model, label);
    replace_all(w.message, o.model, label);
    report.warn(w.code, w.where, w.message);
  }
  if (result) return result;
  Error e = result.error();
  replace_all(e.where, o.model, label);
  replace_all(e.message, o.model, label);
  return e;
}

}  // namespace tranche::app
