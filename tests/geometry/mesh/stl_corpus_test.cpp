// Loads every file of the npm package `stl-models` (fetched by scripts/fetch-models.sh into
// $TRANCHE_MODELS_DIR or ~/.cache/tranche/models); skipped, and passing, when it is absent.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "geometry/mesh/stl.h"

using namespace tranche;
namespace fs = std::filesystem;

namespace {

fs::path models_dir() {
  if (const char* d = std::getenv("TRANCHE_MODELS_DIR"); d && *d) return d;
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache/tranche/models";
  return {};
}

// What each known file must give: "ok", "ok+CODE" (loads with that warning), or an error excerpt.
// Files not listed must load (outside broken/) or load-or-fail cleanly (in broken/).
const std::map<std::string, std::string>& expected() {
  static const std::map<std::string, std::string> m = {
      {"broken/empty.stl", "the file is empty"},
      {"broken/fourVertices.ascii.stl", ":2: facet has 4 vertices"},
      {"broken/quad.ascii.stl", ":2: facet has 4 vertices"},
      {"broken/twoVertices.ascii.stl", ":2: facet has 2 vertices"},
      {"broken/incorrectFaceCounter.bin.stl", "header says 66 triangles, file holds 4 complete ones"},
      {"broken/missingEndsolid.ascii.stl", "the file ends without 'endsolid'"},
      {"broken/missingFace.ascii.stl", "ok"},  // an open mesh is the slicer's problem, not the loader's
      {"broken/singleFace.ascii.stl", "ok"},
      {"broken/wrongHeader.bin.stl", "ok"},     // binary despite its "solid" header: the size agrees
      {"broken/wrongNormals.ascii.stl", "ok"},  // all-zero normals are allowed
      {"broken/missingNormal.ascii.stl", "ok+stl-normal"},
      {"broken/notANumberNormal.ascii.stl", "ok+stl-normal"},
      {"broken/wrongNormal.ascii.stl", "ok+stl-normal"},
      {"broken/solidNameMismatch.ascii.stl", "ok+stl-name"},
      // Outside broken/, yet a solid with no facets: nothing to slice, so a clear error by design.
      {"misc/faceless.ascii.stl", "the file has no facets"},
      // Mangled by a text conversion upstream (bytes >= 0x80 became U+FFFD): 49 bytes too many.
      {"misc/multiWordName.bin.stl", "ok+stl-extra-data"},
  };
  return m;
}

}  // namespace

TEST_CASE("corpus: every stl-models file loads or fails with a clear error") {
  const fs::path root = models_dir();
  std::error_code ec;
  if (root.empty() || !fs::is_directory(root / "broken", ec)) {
    MESSAGE("skipped: stl-models not found in "
            << (root.empty() ? "(no HOME)" : root.string())
            << "; run scripts/fetch-models.sh (needs npm and the registry)");
    return;
  }
  std::vector<fs::path> files;
  for (auto it = fs::recursive_directory_iterator(root, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec)) {
    if (it->is_directory() && it->path().filename() == "node_modules") it.disable_recursion_pending();
    if (it->is_regular_file() && it->path().extension() == ".stl") files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 20);

  std::string table = "\n";
  std::map<std::string, size_t> triangles;  // by path without ".ascii"/".bin", to compare pairs
  size_t seen_expected = 0;
  for (const auto& file : files) {
    const std::string rel = fs::relative(file, root).generic_string();
    const bool broken = rel.starts_with("broken/");
    Report report;
    const auto mesh = geo::load_stl(file.string(), report);
    std::string outcome;
    if (mesh.ok()) {
      outcome = "ok, " + std::to_string(mesh->triangles.size()) + " triangles";
      for (const auto& w : report.warnings())
        outcome += "; warning " + w.code + " at " + w.where + ": " + w.message;
    } else {
      outcome = "error: " + mesh.error().to_string();
      CHECK_MESSAGE(mesh.error().to_string().find(file.string()) != std::string::npos, rel);
    }
    table += rel + " -> " + outcome + "\n";

    const auto e = expected().find(rel);
    if (e != expected().end()) {
      ++seen_expected;
      const std::string& want = e->second;
      if (want.starts_with("ok")) {
        CHECK_MESSAGE(mesh.ok(), rel, " should load: ", outcome);
        if (want.size() > 3) {
          CHECK_MESSAGE(report.count(want.substr(3)) >= 1, rel, " should warn ", want.substr(3));
        } else {
          CHECK_MESSAGE(report.empty(), rel, " should load without warnings: ", outcome);
        }
      } else {
        CHECK_MESSAGE(!mesh.ok(), rel, " should fail with '", want, "'");
        if (!mesh.ok()) CHECK_MESSAGE(mesh.error().to_string().find(want) != std::string::npos, outcome);
      }
    } else if (!broken) {
      CHECK_MESSAGE(mesh.ok(), rel, ": ", outcome);
    }
    if (rel == "polytopes/tetrahedronMinusZero.bin.stl" && mesh.ok()) {
      // Its -0s are in the normals only; -0/+0 welding is tested on generated data in stl_binary_test.
      CHECK_MESSAGE(mesh->vertices.size() == 4, "a tetrahedron has 4 vertices");
    }
    if (mesh.ok() && !broken) {
      std::string key = rel;
      for (const std::string tag : {".ascii", ".binary", ".bin"}) {
        if (auto pos = key.find(tag + ".stl"); pos != std::string::npos) key.erase(pos, tag.size());
      }
      if (auto [it, fresh] = triangles.emplace(key, mesh->triangles.size()); !fresh) {
        CHECK_MESSAGE(it->second == mesh->triangles.size(), key, ": ASCII and binary versions differ");
      }
    }
  }
  MESSAGE(table);
  CHECK(seen_expected == expected().size());
}
