// lay_flat (transform.h): the largest flat face on the object's hull, turned down onto the bed.
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "geometry/plate/transform.h"

namespace tranche::plate {
namespace {

constexpr int kCandidates = 64;                  // planes tried, largest face area first
constexpr double kSameNormal = 0.99984769515;    // cos 1°: normals this close are one plane's
constexpr double kNormalBins = 500;              // normal components quantized to 1/500 for grouping

struct Plane {
  Eigen::Vector3d normal_sum = Eigen::Vector3d::Zero();  // area-weighted
  double area = 0;                                      // mm²
  double offset_sum = 0;                                // area-weighted n·p
  Eigen::Vector3d normal() const { return normal_sum.normalized(); }
  double offset() const { return offset_sum / area; }
};

uint64_t key(const Eigen::Vector3d& n, double offset, double offset_bin) {
  auto q = [](double v, double bin) { return static_cast<uint64_t>(static_cast<int64_t>(std::lround(v / bin)) & 0xffff); };
  return q(n.x(), 1 / kNormalBins) | q(n.y(), 1 / kNormalBins) << 16 | q(n.z(), 1 / kNormalBins) << 32 |
         q(offset, offset_bin) << 48;
}

// The centre of mass of a closed mesh (divergence theorem); the vertices' mean for an open one.
Eigen::Vector3d centroid(const std::vector<Eigen::Vector3d>& p, const geo::Mesh& m) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double six_v = 0;
  for (const auto& t : m.triangles) {
    const double v = p[t[0]].dot(p[t[1]].cross(p[t[2]]));
    six_v += v;
    sum += v * (p[t[0]] + p[t[1]] + p[t[2]]);
  }
  if (std::fabs(six_v) > 1e-12) return sum / (4 * six_v);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& q : p) mean += q;
  return mean / static_cast<double>(std::max<size_t>(p.size(), 1));
}

}  // namespace

std::optional<FlatFace> lay_flat(Object& o) {
  const Eigen::Matrix3d linear = o.transform.linear();
  std::vector<Eigen::Vector3d> p;
  p.reserve(o.mesh.vertices.size());
  Eigen::AlignedBox3d box;
  for (const auto& v : o.mesh.vertices) {
    p.push_back(linear * Eigen::Vector3d(v.x, v.y, v.z));
    box.extend(p.back());
  }
  if (p.empty()) return std::nullopt;
  const double tol = 1e-4 * box.diagonal().norm() + 1e-6;  // mm: a face this close to a plane is on it
  const bool mirror = linear.determinant() < 0;
  std::unordered_map<uint64_t, Plane> planes;
  for (const auto& t : o.mesh.triangles) {
    Eigen::Vector3d n = (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]);
    if (mirror) n = -n;
    const double a2 = n.norm();
    if (!(a2 > 1e-12)) continue;
    n /= a2;
    Plane& pl = planes[key(n, n.dot(p[t[0]]), tol)];
    pl.normal_sum += n * a2 / 2;
    pl.area += a2 / 2;
    pl.offset_sum += n.dot(p[t[0]]) * a2 / 2;
  }
  std::vector<Plane> sorted;
  for (auto& [k, pl] : planes) sorted.push_back(pl);
  std::sort(sorted.begin(), sorted.end(), [](const Plane& a, const Plane& b) { return a.area > b.area; });
  std::vector<Plane> cand;  // planes split across quantization bins are merged back
  for (const Plane& pl : sorted) {
    auto same = std::find_if(cand.begin(), cand.end(), [&](const Plane& c) {
      return c.normal().dot(pl.normal()) > kSameNormal && std::fabs(c.offset() - pl.offset()) < 2 * tol;
    });
    if (same != cand.end()) {
      same->normal_sum += pl.normal_sum;
      same->area += pl.area;
      same->offset_sum += pl.offset_sum;
    } else if (static_cast<int>(cand.size()) < kCandidates) {
      cand.push_back(pl);
    }
  }
  const Eigen::Vector3d com = centroid(p, o.mesh);
  std::optional<FlatFace> best;
  for (const Plane& pl : cand) {
    const Eigen::Vector3d n = pl.normal();
    double reach = -1e300;
    for (const auto& q : p) reach = std::max(reach, n.dot(q));
    if (reach - pl.offset() > tol) continue;  // the plane cuts through the object: not a face to stand on
    const Eigen::Vector3d e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    std::vector<Vec2> on;
    for (const auto& q : p)
      if (n.dot(q) >= reach - tol) on.emplace_back(e1.dot(q), e2.dot(q));
    const Convex contact = convex_hull(std::move(on));
    const FlatFace f{n, std::fabs(area(contact)), inside_or_on(contact, Vec2(e1.dot(com), e2.dot(com)), 0)};
    if (!best || (f.stable && !best->stable) ||
        (f.stable == best->stable && f.area_mm2 > best->area_mm2 * (1 + 1e-9)))
      best = f;
  }
  if (!best) return std::nullopt;
  const Eigen::Quaterniond down = Eigen::Quaterniond::FromTwoVectors(best->normal, -Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d c = world_center(o);
  o.transform = Eigen::Translation3d(c) * down * Eigen::Translation3d(-c) * o.transform;
  return best;
}

}  // namespace tranche::plate
