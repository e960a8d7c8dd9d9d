#include "geometry/mesh/primitives.h"

#include <cassert>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

namespace tranche::geo {
namespace {

constexpr double kPi = std::numbers::pi;

Vec3 sub(const Vec3& a, const Vec3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3& a, const Vec3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

// Collects vertices and triangles; each face is given with a hint of its outward direction and
// flipped when needed, so every generator gets the winding right by construction.
class Builder {
 public:
  // With `weld`, vertices equal after snapping to a 1e-9 mm grid share one id (generators that
  // compute the same point from two cells); without it every call makes a new vertex.
  explicit Builder(bool weld) : weld_(weld) {}

  uint32_t vertex(double x, double y, double z) {
    if (!weld_) return push(x, y, z);
    Key k{std::llround(x * 1e9), std::llround(y * 1e9), std::llround(z * 1e9)};
    auto [it, inserted] = ids_.try_emplace(k, 0);
    if (inserted) it->second = push(k.x / 1e9, k.y / 1e9, k.z / 1e9);
    return it->second;
  }

  void tri(uint32_t a, uint32_t b, uint32_t c, const Vec3& outward) {
    const auto& v = mesh_.vertices;
    Vec3 n = cross(sub(v[b], v[a]), sub(v[c], v[a]));
    if (dot(n, outward) < 0) std::swap(b, c);
    mesh_.triangles.push_back({a, b, c});
  }

  // a, b, c, d in order around a planar (or nearly planar) quad.
  void quad(uint32_t a, uint32_t b, uint32_t c, uint32_t d, const Vec3& outward) {
    tri(a, b, c, outward);
    tri(a, c, d, outward);
  }

  void reserve(size_t vertices, size_t triangles) {
    mesh_.vertices.reserve(vertices);
    mesh_.triangles.reserve(triangles);
  }

  const Vec3& at(uint32_t id) const { return mesh_.vertices[id]; }
  Mesh take(std::string name) {
    mesh_.name = std::move(name);
    return std::move(mesh_);
  }

 private:
  struct Key {
    int64_t x, y, z;
    bool operator==(const Key&) const = default;
  };
  struct KeyHash {
    size_t operator()(const Key& k) const {
      uint64_t h = static_cast<uint64_t>(k.x) * 0x9E3779B97F4A7C15ull;
      h ^= static_cast<uint64_t>(k.y) + 0x7F4A7C159E3779B9ull + (h << 6) + (h >> 2);
      h ^= static_cast<uint64_t>(k.z) + 0x94D049BB133111EBull + (h << 6) + (h >> 2);
      return static_cast<size_t>(h);
    }
  };

  uint32_t push(double x, double y, double z) {
    mesh_.vertices.push_back({x, y, z});
    return static_cast<uint32_t>(mesh_.vertices.size() - 1);
  }

  bool weld_;
  Mesh mesh_;
  std::unordered_map<Key, uint32_t, KeyHash> ids_;
};

// Angle of the i-th vertex of a regular n-gon, starting on +x.
double angle(int i, int n) { return 2 * kPi * i / n; }

}  // namespace

Mesh box(const Vec3& size, const Vec3& origin) {
  Builder b(false);
  uint32_t v[8];
  for (int i = 0; i < 8; ++i)
    v[i] = b.vertex(origin.x + (i & 1 ? size.x : 0), origin.y + (i & 2 ? size.y : 0),
                    origin.z + (i & 4 ? size.z : 0));
  b.quad(v[0], v[1], v[3], v[2], {0, 0, -1});
  b.quad(v[4], v[5], v[7], v[6], {0, 0, 1});
  b.quad(v[0], v[1], v[5], v[4], {0, -1, 0});
  b.quad(v[2], v[3], v[7], v[6], {0, 1, 0});
  b.quad(v[0], v[2], v[6], v[4], {-1, 0, 0});
  b.quad(v[1], v[3], v[7], v[5], {1, 0, 0});
  return b.take("box");
}

Mesh cone(double r_bottom, double r_top, double h, int segments) {
  assert(segments >= 3);
  Builder b(false);
  const int n = segments;
  uint32_t c0 = b.vertex(0, 0, 0);
  uint32_t c1 = b.vertex(0, 0, h);
  std::vector<uint32_t> lo(n), hi(n);
  for (int i = 0; i < n; ++i) {
    double a = angle(i, n);
    lo[i] = b.vertex(r_bottom * std::cos(a), r_bottom * std::sin(a), 0);
    hi[i] = r_top > 0 ? b.vertex(r_top * std::cos(a), r_top * std::sin(a), h) : c1;
  }
  for (int i = 0; i < n; ++i) {
    int j = (i + 1) % n;
    double a = angle(i, n) + kPi / n;
    Vec3 radial{std::cos(a), std::sin(a), 0};
    b.tri(c0, lo[i], lo[j], {0, 0, -1});
    if (r_top > 0) {
      b.tri(c1, hi[i], hi[j], {0, 0, 1});
      b.quad(lo[i], lo[j], hi[j], hi[i], radial);
    } else {
      b.tri(lo[i], lo[j], c1, radial);
    }
  }
  return b.take("cone");
}

Mesh cylinder(double r, double h, int segments) {
  Mesh m = cone(r, r, h, segments);
  m.name = "cylinder";
  return m;
}

Mesh sphere(double r, int segments, int rings) {
  assert(segments >= 3 && rings >= 2);
  Builder b(false);
  b.reserve(static_cast<size_t>(segments) * (rings - 1) + 2, 2ull * segments * (rings - 1));
  uint32_t south = b.vertex(0, 0, -r);
  std::vector<uint32_t> grid;  // (rings − 1) parallels × segments, from south to north
  for (int k = 1; k < rings; ++k) {
    double phi = -kPi / 2 + kPi * k / rings;
    for (int i = 0; i < segments; ++i) {
      double a = angle(i, segments);
      grid.push_back(
          b.vertex(r * std::cos(phi) * std::cos(a), r * std::cos(phi) * std::sin(a), r * std::sin(phi)));
    }
  }
  uint32_t north = b.vertex(0, 0, r);
  auto at = [&](int k, int i) { return grid[static_cast<size_t>(k) * segments + (i % segments)]; };
  auto outward = [&](uint32_t a, uint32_t c) {
    const Vec3& p = b.at(a);
    const Vec3& q = b.at(c);
    return Vec3{p.x + q.x, p.y + q.y, p.z + q.z};  // from the centre through the face
  };
  for (int i = 0; i < segments; ++i) {
    b.tri(south, at(0, i), at(0, i + 1), outward(at(0, i), at(0, i + 1)));
    b.tri(north, at(rings - 2, i), at(rings - 2, i + 1), outward(at(rings - 2, i), at(rings - 2, i + 1)));
    for (int k = 0; k + 1 < rings - 1; ++k)
      b.quad(at(k, i), at(k, i + 1), at(k + 1, i + 1), at(k + 1, i), outward(at(k, i), at(k + 1, i + 1)));
  }
  return b.take("sphere");
}

Mesh torus(double R, double r, int segments_major, int segments_minor) {
  assert(segments_major >= 3 && segments_minor >= 3 && r < R);
  const int m = segments_major, n = segments_minor;
  Builder b(false);
  b.reserve(static_cast<size_t>(m) * n, 2ull * m * n);
  std::vector<double> cu(m), su(m), cv(n), sv(n);
  for (int i = 0; i < m; ++i) cu[i] = std::cos(angle(i, m)), su[i] = std::sin(angle(i, m));
  for (int j = 0; j < n; ++j) cv[j] = std::cos(angle(j, n)), sv[j] = std::sin(angle(j, n));
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      double rho = R + r * cv[j];
      b.vertex(rho * cu[i], rho * su[i], r * sv[j]);
    }
  auto id = [&](int i, int j) { return static_cast<uint32_t>((i % m) * n + (j % n)); };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      // Outward: from the tube's centre line towards the face's middle.
      double a = angle(i, m) + kPi / m, c = angle(j, n) + kPi / n;
      Vec3 out{std::cos(c) * std::cos(a), std::cos(c) * std::sin(a), std::sin(c)};
      b.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1), out);
    }
  return b.take("torus");
}

Mesh plate_with_holes(double size_x, double size_y, double thickness, int cols, int rows, double hole_r,
                      int segments, const std::vector<bool>& hole_mask) {
  assert(segments >= 4 && segments % 4 == 0 && cols >= 1 && rows >= 1);
  assert(hole_mask.empty() || hole_mask.size() == static_cast<size_t>(cols) * rows);
  Builder b(true);
  const double cw = size_x / cols, ch = size_y / rows;
  const double zs[2] = {0, thickness};
  const Vec3 down{0, 0, -1}, up{0, 0, 1};
  for (int row = 0; row < rows; ++row)
    for (int col = 0; col < cols; ++col) {
      const double cx = (col + 0.5) * cw, cy = (row + 0.5) * ch;
      const bool hole = hole_mask.empty() || hole_mask[static_cast<size_t>(row) * cols + col];
      // Points on the cell's border at the hole's vertex angles (starting on a corner) so that
      // neighbouring cells produce the same points along their shared side and weld.
      std::vector<uint32_t> border[2], rim[2];
      for (int k = 0; k < 2; ++k)
        for (int i = 0; i < segments; ++i) {
          double a = kPi / 4 + angle(i, segments), c = std::cos(a), s = std::sin(a);
          double t = 1 / std::max(std::abs(c), std::abs(s));
          border[k].push_back(b.vertex(cx + 0.5 * cw * c * t, cy + 0.5 * ch * s * t, zs[k]));
          if (hole) rim[k].push_back(b.vertex(cx + hole_r * c, cy + hole_r * s, zs[k]));
        }
      uint32_t centre[2] = {0, 0};
      if (!hole) centre[0] = b.vertex(cx, cy, zs[0]), centre[1] = b.vertex(cx, cy, zs[1]);
      for (int i = 0; i < segments; ++i) {
        int j = (i + 1) % segments;
        for (int k = 0; k < 2; ++k) {
          const Vec3& out = k ? up : down;
          if (hole) {
            b.quad(rim[k][i], border[k][i], border[k][j], rim[k][j], out);
          } else {
            b.tri(centre[k], border[k][i], border[k][j], out);
          }
        }
        if (hole) {
          double a = kPi / 4 + angle(i, segments) + kPi / segments;
          b.quad(rim[0][i], rim[0][j], rim[1][j], rim[1][i], {-std::cos(a), -std::sin(a), 0});
        }
        // The plate's outer wall, where this border piece lies on the plate's edge.
        const Vec3& p = b.at(border[0][i]);
        const Vec3& q = b.at(border[0][j]);
        Vec3 out{0, 0, 0};
        if (p.x == 0 && q.x == 0) out = {-1, 0, 0};
        if (p.y == 0 && q.y == 0) out = {0, -1, 0};
        if (std::abs(p.x - size_x) < 1e-9 && std::abs(q.x - size_x) < 1e-9) out = {1, 0, 0};
        if (std::abs(p.y - size_y) < 1e-9 && std::abs(q.y - size_y) < 1e-9) out = {0, 1, 0};
        if (out.x != 0 || out.y != 0) b.quad(border[0][i], border[0][j], border[1][j], border[1][i], out);
      }
    }
  return b.take("plate");
}

void append(Mesh& into, const Mesh& part) {
  const auto base = static_cast<uint32_t>(into.vertices.size());
  into.vertices.insert(into.vertices.end(), part.vertices.begin(), part.vertices.end());
  into.triangles.reserve(into.triangles.size() + part.triangles.size());
  for (const auto& t : part.triangles) into.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
}

Mesh translated(Mesh mesh, const Vec3& offset) {
  mesh.transform(1.0, offset);
  return mesh;
}

namespace {

// A semicircular arch in the xz plane: the half annulus between radii r_in and r_out (mm) around
// (cx, z0), swept along y from y0 to y1; its feet stand at z0.
Mesh arch(double cx, double z0, double r_in, double r_out, double y0, double y1, int segments) {
  Builder b(false);
  std::vector<uint32_t> in[2], out[2];
  const double ys[2] = {y0, y1};
  for (int k = 0; k < 2; ++k)
    for (int i = 0; i <= segments; ++i) {
      double a = kPi * i / segments;
      in[k].push_back(b.vertex(cx + r_in * std::cos(a), ys[k], z0 + r_in * std::sin(a)));
      out[k].push_back(b.vertex(cx + r_out * std::cos(a), ys[k], z0 + r_out * std::sin(a)));
    }
  for (int i = 0; i < segments; ++i) {
    double a = kPi * (i + 0.5) / segments;
    Vec3 radial{std::cos(a), 0, std::sin(a)};
    b.quad(out[0][i], out[0][i + 1], out[1][i + 1], out[1][i], radial);
    b.quad(in[0][i], in[0][i + 1], in[1][i + 1], in[1][i], {-radial.x, 0, -radial.z});
    b.quad(in[0][i], out[0][i], out[0][i + 1], in[0][i + 1], {0, -1, 0});
    b.quad(in[1][i], out[1][i], out[1][i + 1], in[1][i + 1], {0, 1, 0});
  }
  b.quad(in[0][0], out[0][0], out[1][0], in[1][0], {0, 0, -1});
  b.quad(in[0][segments], out[0][segments], out[1][segments], in[1][segments], {0, 0, -1});
  return b.take("arch");
}

}  // namespace

Mesh demo_model() {
  // Holes along the back row and the left column leave room for the boss and the arch.
  std::vector<bool> mask(16);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) mask[row * 4 + col] = row == 3 || col == 0;
  Mesh m = plate_with_holes(40, 40, 3, 4, 4, 2.5, 12, mask);
  // The boss starts inside the plate: overlapping shells that slicing must union.
  append(m, translated(cylinder(4, 11, 32), {25, 25, 2}));
  append(m, arch(22.5, 3, 8, 12, 5, 11, 20));
  m.name = "tranche demo";
  return m;
}

}  // namespace tranche::geo
