// --export-layers: the JSON parses back (with a tiny parser written here) to the same geometry.
#include <doctest/doctest.h>

#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "geometry/io/text_out.h"
#include "geometry/export/layers_json.h"
#include "geometry/mesh/primitives.h"
#include "geometry/slice/layer_heights.h"
#include "geometry/slice/simple_islands.h"
#include "geometry/slice/slicer.h"
#include "tests/support/fixtures.h"

using namespace tranche;
using namespace tranche::geo;
using namespace tranche::exports;

namespace {

// A minimal strict JSON reader: enough to check that the export is well-formed.
struct Json {
  std::variant<std::nullptr_t, bool, double, std::string, std::vector<Json>, std::map<std::string, Json>> v;
  const Json& operator[](const std::string& k) const {
    return std::get<std::map<std::string, Json>>(v).at(k);
  }
  const Json& operator[](size_t i) const { return std::get<std::vector<Json>>(v).at(i); }
  size_t size() const { return std::get<std::vector<Json>>(v).size(); }
  double num() const { return std::get<double>(v); }
  const std::string& str() const { return std::get<std::string>(v); }
  bool has(const std::string& k) const { return std::get<std::map<std::string, Json>>(v).count(k) > 0; }
};

class Parser {
 public:
  explicit Parser(std::string s) : s_(std::move(s)) {}
  Json parse() {
    Json j = value();
    ws();
    if (p_ != s_.size()) fail("trailing characters");
    return j;
  }

 private:
  [[noreturn]] void fail(const std::string& what) {
    throw std::runtime_error(what + " at offset " + std::to_string(p_));
  }
  void ws() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  void expect(char c) {
    ws();
    if (p_ >= s_.size() || s_[p_] != c) fail(std::string("expected ") + c);
    ++p_;
  }
  Json value() {
    ws();
    if (p_ >= s_.size()) fail("unexpected end");
    char c = s_[p_];
    if (c == '{') {
      ++p_;
      std::map<std::string, Json> m;
      ws();
      if (s_[p_] == '}') return ++p_, Json{m};
      for (;;) {
        ws();
        std::string k = string();
        expect(':');
        if (m.count(k)) fail("duplicate key " + k);
        m[k] = value();
        ws();
        if (s_[p_] == ',') {
          ++p_;
          continue;
        }
        expect('}');
        return Json{m};
      }
    }
    if (c == '[') {
      ++p_;
      std::vector<Json> a;
      ws();
      if (s_[p_] == ']') return ++p_, Json{a};
      for (;;) {
        a.push_back(value());
        ws();
        if (s_[p_] == ',') {
          ++p_;
          continue;
        }
        expect(']');
        return Json{a};
      }
    }
    if (c == '"') return Json{string()};
    if (s_.compare(p_, 4, "true") == 0) return p_ += 4, Json{true};
    if (s_.compare(p_, 5, "false") == 0) return p_ += 5, Json{false};
    if (s_.compare(p_, 4, "null") == 0) return p_ += 4, Json{nullptr};
    size_t start = p_;
    if (s_[p_] == '-') ++p_;
    if (p_ >= s_.size() || !std::isdigit(static_cast<unsigned char>(s_[p_]))) fail("bad value");
    while (p_ < s_.size() &&
           (std::isdigit(static_cast<unsigned char>(s_[p_])) || std::strchr(".eE+-", s_[p_])))
      ++p_;
    return Json{std::stod(s_.substr(start, p_ - start))};
  }
  std::string string() {
    if (s_[p_] != '"') fail("expected string");
    ++p_;
    std::string out;
    while (p_ < s_.size() && s_[p_] != '"') {
      if (static_cast<unsigned char>(s_[p_]) < 0x20) fail("control character in string");
      if (s_[p_] == '\\') {
        ++p_;
        char e = s_[p_++];
        if (e == 'u') {
          out += static_cast<char>(std::stoi(s_.substr(p_, 4), nullptr, 16));
          p_ += 4;
        } else {
          out += e == 'n' ? '\n' : e;
        }
      } else {
        out += s_[p_++];
      }
    }
    expect('"');
    return out;
  }
  std::string s_;
  size_t p_ = 0;
};

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::vector<Layer> sliced(const Mesh& mesh) {
  auto plan = plan_layer_heights(mesh.bbox().max.z, {});
  REQUIRE(plan.ok());
  Report r;
  REQUIRE(slice_mesh(mesh, *plan, {}, r).ok());
  REQUIRE(make_islands(*plan).ok());
  return std::move(*plan);
}

Ring ring_of(const Json& j) {
  Ring r;
  for (size_t i = 0; i < j.size(); ++i) r.push_back(to_point(j[i][0].num(), j[i][1].num()));
  return r;
}

}  // namespace

TEST_CASE("append_mm prints exact millimetres") {
  auto s = [](coord_t u) {
    fmt::memory_buffer b;
    append_mm(b, u);
    return fmt::to_string(b);
  };
  CHECK(s(0) == "0");
  CHECK(s(12500000) == "12.5");
  CHECK(s(-1) == "-0.000001");
  CHECK(s(3000000) == "3");
  CHECK(s(-123456789) == "-123.456789");
  for (coord_t u : {coord_t{7}, coord_t{-999999}, coord_t{1073741823}, coord_t{-40000001}})
    CHECK(to_units(std::stod(s(u))) == u);
}

SCENARIO("the layers JSON of a plate with holes parses back exactly") {
  test::TempDir dir("json");
  Mesh m = plate_with_holes(30, 20, 1, 3, 2, 3, 16);
  m.transform(1.0, {-7.25, 3.5, 0});  // negative coordinates too
  const auto layers = sliced(m);
  const auto path = dir / "plate.json";
  REQUIRE(write_layers_json(path.string(), layers, "plate \"quoted\".stl").ok());
  Json j = Parser(read(path)).parse();
  CHECK(j["format"].str() == "tranche-layers");
  CHECK(j["version"].num() == 2);
  CHECK(j["units"].str() == "mm");
  CHECK(j["source"].str() == "plate \"quoted\".stl");
  REQUIRE(j["layer_count"].num() == layers.size());
  REQUIRE(j["layers"].size() == layers.size());
  for (size_t i = 0; i < layers.size(); ++i) {
    const Json& l = j["layers"][i];
    CHECK(l["index"].num() == layers[i].index);
    CHECK(l["z_bottom"].num() == layers[i].z_bottom);
    CHECK(l["z_top"].num() == layers[i].z_top);
    CHECK(l["z_slice"].num() == layers[i].z_slice());
    REQUIRE(l["islands"].size() == layers[i].islands.size());
    double total = 0;
    for (size_t k = 0; k < layers[i].islands.size(); ++k) {
      const Json& isl = l["islands"][k];
      const Island& want = layers[i].islands[k];
      Ring outer = ring_of(isl["outer"]);
      CHECK(outer == want.shape.outer);
      CHECK(area_mm2(outer) > 0);
      REQUIRE(isl["holes"].size() == want.shape.holes.size());
      for (size_t h = 0; h < want.shape.holes.size(); ++h) {
        Ring hole = ring_of(isl["holes"][h]);
        CHECK(hole == want.shape.holes[h]);
        CHECK(area_mm2(hole) < 0);
      }
      CHECK(isl["area"].num() == want.area_mm2);
      total += want.area_mm2;
    }
    CHECK(l["area"].num() == doctest::Approx(total));
  }
  // Six holes in the one island of every layer.
  CHECK(j["layers"][0]["islands"][0]["holes"].size() == 6);
}

TEST_CASE("the layers JSON of no layers, and of an empty layer, is valid") {
  test::TempDir dir("json-empty");
  std::vector<Layer> layers(1);
  layers[0].z_top = 0.2;
  REQUIRE(write_layers_json((dir / "a.json").string(), {}, "none").ok());
  REQUIRE(write_layers_json((dir / "b.json").string(), layers, "empty").ok());
  CHECK(Parser(read(dir / "a.json")).parse()["layers"].size() == 0);
  CHECK(Parser(read(dir / "b.json")).parse()["layers"][0]["islands"].size() == 0);
}

TEST_CASE("an export that cannot be written leaves nothing behind") {
  test::TempDir dir("json-fail");
  auto st = write_layers_json((dir / "missing-folder" / "x.json").string(), {}, "x");
  REQUIRE(!st.ok());
  CHECK(st.error().where.find("missing-folder") != std::string::npos);
  CHECK(std::distance(std::filesystem::directory_iterator(dir.path()),
                      std::filesystem::directory_iterator()) == 0);
}
