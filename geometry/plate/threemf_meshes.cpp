#include "geometry/plate/threemf_meshes.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace tranche::plate::threemf {
namespace {

// The placeholder's corners: (id, -7777, 0), (id, -7776, 0), (id, -7777, 1); ids below 2^24,
// which a float holds exactly.
constexpr float kMarkY = -7777.0f;
constexpr uint32_t kMaxId = 1u << 24;

bool space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

template <class T>
bool parse(std::string_view v, T& out) {
  const auto [end, ec] = std::from_chars(v.data(), v.data() + v.size(), out);
  return ec == std::errc() && end == v.data() + v.size();
}

// A cursor over the XML text that reads the few forms a plain mesh is written in.
class Scanner {
 public:
  Scanner(std::string_view s, size_t at) : s_(s), i_(at) {}
  size_t pos() const { return i_; }
  void skip_space() {
    while (i_ < s_.size() && space(s_[i_])) ++i_;
  }
  bool eat(std::string_view lit) {
    if (s_.compare(i_, lit.size(), lit) != 0) return false;
    i_ += lit.size();
    return true;
  }
  // `<name` followed by a space, '>' or '/': consumed.
  bool open(std::string_view name) {
    const size_t after = i_ + 1 + name.size();
    if (after >= s_.size() || s_[i_] != '<' || s_.compare(i_ + 1, name.size(), name) != 0) return false;
    const char c = s_[after];
    if (!space(c) && c != '>' && c != '/') return false;
    i_ = after;
    return true;
  }
  // Calls f(name, value) for each attribute of the tag (false from f: unreadable); then whether
  // the tag closed itself (`/>`), or nothing when the tag is not read to its end.
  template <class F>
  std::optional<bool> attributes(F f) {
    for (;;) {
      skip_space();
      if (i_ >= s_.size()) return std::nullopt;
      if (s_[i_] == '>') {
        ++i_;
        return false;
      }
      if (s_[i_] == '/') return eat("/>") ? std::optional<bool>(true) : std::nullopt;
      size_t n = i_;
      while (n < s_.size() && !space(s_[n]) && s_[n] != '=' && s_[n] != '>' && s_[n] != '/') ++n;
      const std::string_view name = s_.substr(i_, n - i_);
      i_ = n;
      skip_space();
      if (!eat("=")) return std::nullopt;
      skip_space();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) return std::nullopt;
      const size_t end = s_.find(s_[i_], i_ + 1);
      if (end == std::string_view::npos || !f(name, s_.substr(i_ + 1, end - i_ - 1))) return std::nullopt;
      i_ = end + 1;
    }
  }
  // The fast way through the form most writers use, `<vertex x="1" y="2" z="3"/>` or `<triangle
  // v1="0" v2="1" v3="2" />` (`names` holds the three attributes' `name="` in order): the values,
  // and the cursor past the tag; false (the cursor unmoved) for any other form.
  template <class T>
  bool three(std::string_view tag, const std::string_view (&names)[3], T (&out)[3]) {
    size_t i = i_;
    if (s_.compare(i, tag.size(), tag) != 0) return false;
    i += tag.size();
    for (int k = 0; k < 3; ++k) {
      if (i >= s_.size() || s_[i] != ' ') return false;
      ++i;
      if (s_.compare(i, names[k].size(), names[k]) != 0) return false;
      i += names[k].size();
      const char* end = s_.data() + s_.size();
      const auto [p, ec] = std::from_chars(s_.data() + i, end, out[k]);
      if (ec != std::errc() || p == end || *p != '"') return false;
      i = static_cast<size_t>(p - s_.data()) + 1;
    }
    while (i < s_.size() && space(s_[i])) ++i;
    if (s_.compare(i, 2, "/>") != 0) return false;
    i_ = i + 2;
    return true;
  }
  // `<name ...>` (not closed by itself), its attributes ignored.
  bool start(std::string_view name) {
    if (!open(name)) return false;
    const auto closed = attributes([](std::string_view, std::string_view) { return true; });
    return closed && !*closed;
  }

 private:
  std::string_view s_;
  size_t i_;
};

// `<vertex x=".." y=".." z=".."/>` elements up to `</vertices>`, or false.
bool vertices(Scanner& sc, std::vector<float>& out) {
  for (;;) {
    sc.skip_space();
    if (sc.eat("</vertices>")) return true;
    static constexpr std::string_view kXyz[3] = {"x=\"", "y=\"", "z=\""};
    float xyz[3];
    if (sc.three("<vertex", kXyz, xyz)) {
      if (!std::isfinite(xyz[0]) || !std::isfinite(xyz[1]) || !std::isfinite(xyz[2])) return false;
      out.insert(out.end(), xyz, xyz + 3);
      continue;
    }
    if (!sc.open("vertex")) return false;
    int got = 0;
    const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
      if (name.size() != 1 || name[0] < 'x' || name[0] > 'z') return true;
      got |= 1 << (name[0] - 'x');
      return parse(value, xyz[name[0] - 'x']) && std::isfinite(xyz[name[0] - 'x']);
    });
    if (!closed || !*closed || got != 7) return false;
    out.insert(out.end(), xyz, xyz + 3);
  }
}

// `<triangle v1=".." v2=".." v3=".." .../>` elements up to `</triangles>` (properties ignored), or false.
bool triangles(Scanner& sc, std::vector<uint32_t>& out) {
  for (;;) {
    sc.skip_space();
    if (sc.eat("</triangles>")) return true;
    static constexpr std::string_view kV123[3] = {"v1=\"", "v2=\"", "v3=\""};
    uint32_t v[3];
    if (sc.three("<triangle", kV123, v)) {
      out.insert(out.end(), v, v + 3);
      continue;
    }
    if (!sc.open("triangle")) return false;
    int got = 0;
    const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
      if (name.size() != 2 || name[0] != 'v' || name[1] < '1' || name[1] > '3') return true;
      got |= 1 << (name[1] - '1');
      return parse(value, v[name[1] - '1']);
    });
    if (!closed || !*closed || got != 7) return false;
    out.insert(out.end(), v, v + 3);
  }
}

// A plain `<mesh>` at the cursor, read to its end; nothing for any other form, or a mesh lib3mf
// would refuse (a coordinate that is not a finite number, a vertex index out of range).
std::optional<MeshData> mesh(Scanner& sc) {
  MeshData m;
  if (!sc.start("mesh")) return std::nullopt;
  sc.skip_space();
  if (!sc.start("vertices") || !vertices(sc, m.vertices)) return std::nullopt;
  sc.skip_space();
  if (!sc.start("triangles") || !triangles(sc, m.triangles)) return std::nullopt;
  sc.skip_space();
  if (!sc.eat("</mesh>") || m.triangles.empty()) return std::nullopt;
  const size_t nv = m.vertices.size() / 3;
  for (uint32_t v : m.triangles)
    if (v >= nv) return std::nullopt;  // lib3mf says what is wrong
  return m;
}

std::string placeholder(uint32_t id) {
  return fmt::format(
      "<mesh><vertices><vertex x=\"{0}\" y=\"{1}\" z=\"0\"/><vertex x=\"{0}\" y=\"{2}\" z=\"0\"/><vertex x=\"{0}\" "
      "y=\"{1}\" z=\"1\"/></vertices><triangles><triangle v1=\"0\" v2=\"1\" v3=\"2\"/></triangles></mesh>",
      id, kMarkY, kMarkY + 1);
}

}  // namespace

SplitModel split_meshes(std::string_view xml) {
  SplitModel out;
  // A mesh is replaced only where it was read whole, element after element: a comment or CDATA
  // section cannot begin or end inside it (the mesh would not read), so a mesh in a comment is
  // replaced in the comment, which lib3mf skips, and an object of the same id after it is left
  // to lib3mf (ids are taken once).
  size_t copied = 0;  // xml[0, copied) is in out.model
  for (size_t at = xml.find("<object"); at != std::string_view::npos; at = xml.find("<object", at)) {
    Scanner sc(xml, at);
    if (!sc.open("object")) {
      at += 7;
      continue;
    }
    std::optional<uint32_t> id;
    const auto closed = sc.attributes([&](std::string_view name, std::string_view value) {
      uint32_t v = 0;
      if (name == "id" && parse(value, v)) id = v;
      return true;
    });
    if (!closed) break;  // a tag not read to its end: the rest is lib3mf's
    at = sc.pos();
    if (*closed || !id || *id >= kMaxId || out.meshes.count(*id)) continue;
    sc.skip_space();
    const size_t start = sc.pos();
    auto m = mesh(sc);
    if (!m) continue;  // lib3mf reads this one
    out.model.append(xml.substr(copied, start - copied));
    out.model += placeholder(*id);
    copied = at = sc.pos();
    out.meshes.emplace(*id, std::move(*m));
  }
  if (out.meshes.empty()) return SplitModel{};
  out.model.append(xml.substr(copied));
  return out;
}

std::optional<uint32_t> placeholder_id(const float* a, const float* b, const float* c) {
  if (a[1] != kMarkY || a[2] != 0 || b[0] != a[0] || b[1] != kMarkY + 1 || b[2] != 0 || c[0] != a[0] ||
      c[1] != kMarkY || c[2] != 1)
    return std::nullopt;
  if (!(a[0] >= 0 && a[0] < static_cast<float>(kMaxId)) || a[0] != std::floor(a[0])) return std::nullopt;
  return static_cast<uint32_t>(a[0]);
}

}  // namespace tranche::plate::threemf
