#include "geometry/plan/support_pass.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <numbers>

#include "geometry/plan/island_content.h"
#include "geometry/plan/nest.h"
#include "geometry/support/overhang.h"
#include "geometry/support/raft.h"
#include "geometry/support/tree.h"
#include "geometry/toolpath/clip.h"
#include "geometry/toolpath/edge_grid.h"
#include "geometry/toolpath/flow.h"

namespace tranche::plan {
namespace {

using geo::Rings;
using schema::FieldId;
using schema::PathKind;
using schema::PropId;
using schema::Stage;

// An overhang nowhere wider than this is a short ledge: it prints in the air without sagging much
// (the step of a temperature tower, the apex of a round arch), so the warning leaves it out.
constexpr double kLedgeMm = 2.0;

// What the island stage decided about one island's support.
struct IslandSupport {
  schema::Support style = schema::Support::None;
  double z_gap = 0.2, xy_gap = 0.5;
  int interface_layers = 2;
  bool bed_only = false;
  double brim_mm = 0;
  double reach = 0;  // mm: how far the island leans out over the layer below, unsupported
  Rings overhang;
};

struct LayerSupport {
  std::vector<IslandSupport> islands;
  double brim_width = 0;  // mm, the bead of the brim (layer 0, when an island asks for one)
};

// Layer L's islands decided at their island stage, as the layer loop decides them, and their
// overhangs measured.
Status decide_layer(const setup::PrintSetup& S, const ctx::Cascade& C, int L, LayerSupport& out) {
  Nest nest(S, C);
  toolpath::Neighbours nb(S.layers, L);
  const IslandNeeds needs = IslandNeeds::of(nest);
  const geo::Layer& layer = S.layers[static_cast<size_t>(L)];
  LayerPlan lp = layer_shell(S, L);
  nest.enter_layer(lp, static_cast<int>(layer.islands.size()));
  lp.props = S.print_props;
  if (Status s = nest.decide(Stage::Layer, lp.props); !s) return s;
  const double nozzle = S.print_props[PropId::NozzleDiameter];
  std::map<double, Rings> grown;  // the layer below grown by each reach asked for
  out.islands.resize(layer.islands.size());
  for (size_t i = 0; i < layer.islands.size(); ++i) {
    IslandPlan ip = island_shell(S, L, i);
    measure_island(ip, S.shift, nb, needs);
    nest.enter_island(ip);
    ip.props = lp.props;
    if (Status s = nest.decide(Stage::Island, ip.props); !s) return s;
    const ctx::PropertyValues& P = ip.props;
    IslandSupport& d = out.islands[i];
    d.style = static_cast<schema::Support>(static_cast<int>(P[PropId::Support]));
    d.z_gap = P[PropId::SupportZGap];
    d.xy_gap = P[PropId::SupportXyGap];
    d.interface_layers = static_cast<int>(P[PropId::SupportInterfaceLayers]);
    d.bed_only = P[PropId::SupportOnBedOnly] != 0;
    d.brim_mm = L == 0 ? P[PropId::BrimWidth] : 0;
    if (d.brim_mm > 0 && out.brim_width <= 0) {
      auto w = nest.path_props(P, PathKind::Brim, -1);
      if (!w) return w.error();
      out.brim_width = (*w)[PropId::Width];
    }
    const double angle = P[PropId::SupportAngle];
    // The first layer stands on the bed or on the raft (layers 0 .. raft_layers - 1).
    if (L <= static_cast<int>(S.print_props[PropId::RaftLayers]) || angle >= 90) continue;
    support::OverhangSpec spec;
    spec.reach_mm = lp.height * std::tan(angle * std::numbers::pi / 180);
    spec.nozzle_mm = nozzle;
    spec.max_bridge_mm = P[PropId::SupportMaxBridge];
    d.reach = spec.reach_mm;
    // An island wholly on the layer below has no overhang at any reach (exact segment and point
    // tests, much cheaper than the difference; a part narrowing upwards is most of its layers):
    // the layer below is grown only for the islands that lean out.
    if (spec.reach_mm >= 0 && nb.covers(-1, ip.shape, toolpath::EdgeGrid(ip.shape))) continue;
    auto it = grown.find(spec.reach_mm);
    if (it == grown.end())  // overhangs need no finer arcs than support (25 µm)
      it = grown.emplace(spec.reach_mm, toolpath::offset_coarse(nb.layer(-1), spec.reach_mm)).first;
    d.overhang = support::overhang(ip.shape, it->second, nb.layer(-1), spec);
  }
  return ok_status();
}

// The layer where the top of the support under an overhang of layer L is printed: the highest
// whose top lies z_gap or more below L's bottom; -1 when there is none.
int contact_layer(const setup::PrintSetup& S, int L, double z_gap) {
  const double limit = S.layers[static_cast<size_t>(L)].z_bottom - z_gap + 1e-6;
  int k = L - 1;
  while (k >= 0 && S.layers[static_cast<size_t>(k)].z_top > limit) --k;
  return k;
}

std::string where(const setup::PrintSetup& S, int L) {
  return fmt::format("layer {} (z {:.2f} mm)", L, S.layers[static_cast<size_t>(L)].z_top);
}

// The warning for overhangs printed in the air: the worst layers, once.
// The overhangs printed in the air, once: the worst layer, the total and the next worst ones.
// `advice` ends the message; `code` tags the warning.
Status warn_unsupported(const setup::PrintSetup& S, const std::vector<double>& air, Report& report,
                        const SupportPassOptions& o, const std::string& code, const std::string& advice) {
  constexpr double kWorth = 1.0;  // mm²: less on a layer is a speck no user would support
  std::vector<int> worst;
  double total = 0;
  for (size_t L = 0; L < air.size(); ++L)
    if (air[L] >= kWorth) worst.push_back(static_cast<int>(L)), total += air[L];
  // Less than this in all is a detail no user would put support under (the apex of a round arch).
  constexpr double kWorthSaying = 20.0;  // mm²
  if (worst.empty() || total < kWorthSaying) return ok_status();
  std::sort(worst.begin(), worst.end(), [&](int a, int b) { return air[size_t(a)] > air[size_t(b)]; });
  std::string also;
  for (size_t k = 1; k < std::min<size_t>(3, worst.size()); ++k)
    also += fmt::format("{}{}: {:.0f} mm²", k > 1 ? "; " : "", where(S, worst[k]), air[size_t(worst[k])]);
  const std::string msg =
      worst.size() == 1
          ? fmt::format("{:.0f} mm² of overhang printed in the air; {}", total, advice)
          : fmt::format("{:.0f} mm² of overhang printed in the air here, {:.0f} mm² on {} layers in all (next worst: "
                        "{}); {}",
                        air[size_t(worst[0])], total, worst.size(), also, advice);
  if (o.strict) return Error{where(S, worst[0]), msg + " (--strict makes this an error)"};
  if (o.warn) report.warn(code, where(S, worst[0]), msg);
  return ok_status();
}

}  // namespace

namespace {

// The contacts of every overhang that wants support, by style; the rest is air.
struct Contacts {
  support::ProjectInput normal, tree_iface, tree;  // the columns; the trees' interface; the trees' tips
  std::vector<double> air;                         // per layer, mm² printed in the air
  std::vector<double> near_bed;                    // per layer, mm² in the air with no room for support under it
  bool any_normal = false, any_tree = false;
};

Contacts place_contacts(setup::PrintSetup& S, std::vector<LayerSupport>& decided) {
  const size_t n = S.layers.size();
  Contacts c;
  for (support::ProjectInput* in : {&c.normal, &c.tree_iface, &c.tree}) {
    in->layers = S.layers;
    in->contacts.resize(n);
    in->bottom_gap_layers = 0;  // the largest z gap asked for, in layers
  }
  c.tree_iface.columns = false;
  c.air.assign(n, 0.0);
  c.near_bed.assign(n, 0.0);
  S.overhang_area.assign(n, {});
  for (size_t L = 0; L < n; ++L) {
    S.overhang_area[L].assign(decided[L].islands.size(), 0.f);
    for (size_t i = 0; i < decided[L].islands.size(); ++i) {
      IslandSupport& d = decided[L].islands[i];
      if (d.overhang.empty()) continue;
      const double area = toolpath::area_mm2(d.overhang);
      S.overhang_area[L][i] = static_cast<float>(area);
      const int k = contact_layer(S, static_cast<int>(L), d.z_gap);
      if (k < 0 || d.style == schema::Support::None) {  // no room under it, or not wanted
        // Said when wider than a short ledge; support cannot help an overhang too near the bed.
        (k < 0 ? c.near_bed : c.air)[L] += toolpath::area_mm2(toolpath::offset_open(d.overhang, 0, 0.5 * kLedgeMm));
        continue;
      }
      const int gap = static_cast<int>(L) - 1 - k;
      // Grown by the reach inside the island: the slivers of a slope, a reach apart from layer to
      // layer, then overlap into one band (support/support.h).
      d.overhang = toolpath::intersection(toolpath::offset(d.overhang, d.reach + 0.05), geo::to_rings({S.layers[L].islands[i].shape}));
      if (d.style == schema::Support::Normal) {
        c.normal.bottom_gap_layers = std::max(c.normal.bottom_gap_layers, gap);
        c.normal.contacts[size_t(k)].push_back({std::move(d.overhang), d.interface_layers, d.bed_only, gap == 0});
        c.any_normal = true;
        continue;
      }
      // Tree: the interface under the overhang, the tips right below it.
      const int tips_at = k - d.interface_layers;
      c.tree.bottom_gap_layers = std::max(c.tree.bottom_gap_layers, gap);
      if (tips_at >= 0)  // tips right under the overhang (no gap, no interface) touch it
        c.tree.contacts[size_t(tips_at)].push_back({d.overhang, 0, d.bed_only, gap == 0 && d.interface_layers == 0});
      c.tree_iface.contacts[size_t(k)].push_back({std::move(d.overhang), d.interface_layers, d.bed_only, gap == 0});
      c.any_tree = true;
    }
  }
  return c;
}

// The part grown by each island's xy gap, per layer.
std::vector<Rings> keep_out(const setup::PrintSetup& S, const std::vector<LayerSupport>& decided) {
  std::vector<Rings> out(S.layers.size());
  tbb::parallel_for(size_t{0}, S.layers.size(), [&](size_t L) {
    Rings grown;
    for (size_t i = 0; i < S.layers[L].islands.size(); ++i) {
      Rings g = toolpath::offset_coarse(geo::to_rings({S.layers[L].islands[i].shape}), decided[L].islands[i].xy_gap);
      grown.insert(grown.end(), g.begin(), g.end());
    }
    out[L] = toolpath::simplify(toolpath::union_of(grown), 25000);  // 25 µm: support needs no finer
  });
  return out;
}

// Columns and trees grown from the contacts into S.support.
void grow_support(setup::PrintSetup& S, const std::vector<LayerSupport>& decided, Contacts& c, Report& report,
                  const SupportPassOptions& o) {
  const std::vector<Rings> keep = keep_out(S, decided);
  const Rings bed = support::bed_region(S.bed.circular, S.bed.min_x, S.bed.min_y, S.bed.max_x, S.bed.max_y, S.shift);
  const double w = S.print_props[PropId::NozzleDiameter] * 1.125;
  for (support::ProjectInput* in : {&c.normal, &c.tree_iface, &c.tree}) {
    in->keep_out = keep;
    in->bed = bed;
    in->min_width_mm = in->merge_mm = w;
  }
  double off_bed = 0, blocked = 0;
  S.support.assign(S.layers.size(), {});
  if (c.any_normal) {
    support::ProjectResult r = support::project(c.normal);
    S.support = std::move(r.layers);
    off_bed += r.off_bed_mm2, blocked += r.blocked_mm2;
  }
  if (c.any_tree) {
    support::ProjectResult iface = support::project(c.tree_iface);
    support::TreeResult trees = support::grow_trees(c.tree, support::TreeSpec{});
    blocked += trees.blocked_mm2;
    for (size_t k = 0; k < S.layers.size(); ++k) {
      support::SupportLayer& sl = S.support[k];
      sl.interface = toolpath::union_of(sl.interface, iface.layers[k].interface);
      Rings taken = toolpath::union_of(sl.base, sl.interface);  // normal support and interfaces come first
      sl.tree = toolpath::difference(trees.branches[k], taken);
      sl.area_mm2 = toolpath::area_mm2(sl.base) + toolpath::area_mm2(sl.interface) + toolpath::area_mm2(sl.tree);
    }
  }
  if (o.warn && off_bed > 1)
    report.warn("support-off-bed", "support",
                fmt::format("{:.0f} mm² of support would stand off the bed and was left out", off_bed));
  if (o.warn && blocked > 1)
    report.warn("support-on-part", "support",
                fmt::format("{:.0f} mm² of overhang not supported: support_on_bed_only, and the part lies below it",
                            blocked));
}

// The raft (raft_layers > 0): its layers, empty of the part (pipeline lifted the part onto them),
// print the part's first layer and every support that reaches down to them, grown by
// raft_expansion; the skirt goes round it.
void plan_raft(setup::PrintSetup& S, int raft) {
  const size_t n = S.layers.size(), r = static_cast<size_t>(raft);
  if (raft <= 0 || n <= r) return;
  if (S.support.size() < n) S.support.resize(n);
  Rings foot = toolpath::material(S.layers[r]);
  for (size_t k = 0; k <= r; ++k)
    for (const Rings* rs : {&S.support[k].base, &S.support[k].interface, &S.support[k].tree})
      foot.insert(foot.end(), rs->begin(), rs->end());
  const Rings bed = support::bed_region(S.bed.circular, S.bed.min_x, S.bed.min_y, S.bed.max_x, S.bed.max_y, S.shift);
  const Rings sheet = support::raft_region(foot, S.print_props[PropId::RaftExpansion], bed);
  for (size_t k = 0; k < r; ++k) {
    support::SupportLayer& sl = S.support[k];
    sl = {};
    (support::raft_layer_dense(static_cast<int>(k), raft) ? sl.interface : sl.base) = sheet;
    sl.area_mm2 = toolpath::area_mm2(sheet);
  }
  geo::Ring pts;
  for (const geo::Ring& ring : sheet) pts.insert(pts.end(), ring.begin(), ring.end());
  S.skirt_around = toolpath::convex_hull(std::move(pts));
}

// Layer 0's islands that ask for a brim, and the skirt round the brim and the first layer's support.
void plan_brim(setup::PrintSetup& S, const LayerSupport& first) {
  S.brim.clear();
  if (!S.layers.empty() && first.brim_width > 0) {
    const double w = first.brim_width;
    const double s = toolpath::bead_spacing_mm(w, S.layers[0].height());
    std::vector<support::BrimIsland> asks;
    Rings all;
    for (size_t i = 0; i < S.layers[0].islands.size(); ++i) {
      const geo::Ring& outer = S.layers[0].islands[i].shape.outer;
      all.push_back(outer);
      const double mm = first.islands[i].brim_mm;
      if (mm > 0) asks.push_back({outer, std::max(1, static_cast<int>(std::lround(mm / s)))});
    }
    S.brim = support::brim_paths(asks, all, w, s);
  }
  if (S.skirt_around.empty() || (S.brim.empty() && (S.support.empty() || S.support[0].area_mm2 <= 0))) return;
  geo::Ring pts;
  for (const auto& r : S.skirt_around) pts.insert(pts.end(), r.begin(), r.end());
  for (const auto& b : S.brim) pts.insert(pts.end(), b.pts.begin(), b.pts.end());
  if (!S.support.empty())
    for (const Rings* rs : {&S.support[0].base, &S.support[0].interface, &S.support[0].tree})
      for (const auto& r : *rs) pts.insert(pts.end(), r.begin(), r.end());
  S.skirt_around = toolpath::convex_hull(std::move(pts));
}

}  // namespace

Status plan_support(setup::PrintSetup& S, const ctx::Cascade& C, Report& report, const SupportPassOptions& o) {
  const size_t n = S.layers.size();
  std::vector<LayerSupport> decided(n);
  std::mutex mu;
  Status failed = ok_status();
  int failed_at = INT32_MAX;
  tbb::parallel_for(size_t{0}, n, [&](size_t L) {
    Status s = decide_layer(S, C, static_cast<int>(L), decided[L]);
    if (s) return;
    std::lock_guard lock(mu);
    if (static_cast<int>(L) < failed_at) failed = s, failed_at = static_cast<int>(L);  // the lowest layer's error
  });
  if (!failed) return failed;
  Contacts c = place_contacts(S, decided);
  S.support.clear();
  if (c.any_normal || c.any_tree) grow_support(S, decided, c, report, o);
  if (Status s = warn_unsupported(S, c.air, report, o, "unsupported-overhang",
                                  "set support = normal or tree (--set support=normal) or support it by a rule");
      !s)
    return s;
  // Support may touch what hangs that low: one rule, up to the highest such layer, says so.
  double near_top = 0;
  for (size_t L = 0; L < n; ++L)
    if (c.near_bed[L] >= 1.0) near_top = S.layers[L].z_top;
  if (Status s = warn_unsupported(
          S, c.near_bed, report, o, "overhang-near-bed",
          fmt::format("it is less than support_z_gap above the bed, so no support fits under it: lay the part on "
                      "another face (--lay-flat, --rotate-x), or let support touch it there: rule when "
                      "layer.z_bottom < {:g} mm {{ support_z_gap = 0 mm }} (the stdlib feature "
                      "support-touching-near-bed does it for any gap)",
                      near_top));
      !s)
    return s;
  plan_raft(S, static_cast<int>(S.print_props[PropId::RaftLayers]));
  if (n > 0) plan_brim(S, decided[0]);
  return ok_status();
}

}  // namespace tranche::plan
