// Filter evaluation: the rule VM against the same rules hand-written in C++ and written in Lua 5.4,
// over one stream of contexts walked like the slicer walks them (layers ⊃ islands ⊃ paths ⊃
// pieces, each level's fields set when the loop enters it). Every piece decides `speed` and
// `flow` (and the three must agree on every value). Prints one table; times are the best of runs.
//   vm_bench [PIECES] [RUNS]
#include <fmt/format.h>
extern "C" {
#include <lauxlib.h>
#include <lua.h>
#include <lualib.h>
}

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "compiler/codegen.h"
#include "compiler/frontend.h"
#include "compiler/check.h"
#include "runtime/vm/vm.h"

using namespace tranche;
using schema::FieldId;
using schema::Level;
using schema::PathKind;
using schema::PropId;
using schema::Stage;

namespace {

// The rules, as a user writes them.
const char* kRules = R"(
rule "base" { speed = 60 mm/s; flow = 100% }
rule "outer walls" when path.kind == outer_perimeter { speed = 40 mm/s }
rule "inner walls" when path.kind == inner_perimeter { speed = 55 mm/s }
rule "skins" when path.kind in (top_solid, bottom_solid) { speed = 45 mm/s }
rule "bridges" when path.kind == bridge { speed = 25 mm/s; flow = 80% }
rule "first layers" when layer.index < 2 { speed = 20 mm/s; flow = 105% }
rule "tiny islands" when island.area < 4 mm2 { speed = 15 mm/s }
rule "small outer walls" when island.area < 25 mm2 and path.kind == outer_perimeter { speed = 25 mm/s }
rule "overhangs" when piece.overhang > 30% { speed = 15 mm/s }
rule "short infill moves" when piece.length < 0.5 mm and path.kind == infill { speed = 30 mm/s }
rule "band" when layer.z_bottom in 10 mm .. 20 mm { flow = 98% }
rule "unsupported" when island.supported < 50% and path.kind != skirt { speed = 20 mm/s }
rule "deep perimeters" when path.perimeter > 2 { speed = 50 mm/s }
rule "big solid" when cell.solid and island.area > 100 mm2 { speed = 80 mm/s }
rule "every tenth layer" when layer.index mod 10 == 0 and layer.index > 0 { flow = 102% }
rule "long walls" when path.length > 100 mm and path.kind == inner_perimeter { speed = 65 mm/s }
)";

// The same rules by hand: the last matching rule wins, written as a C++ programmer would.
struct Decided {
  double speed, flow;
};
inline Decided by_hand(const ctx::Context& c) {
  const double kind = c.get(FieldId::PathKind), layer = c.get(FieldId::LayerIndex),
               area = c.get(FieldId::IslandArea);
  auto is = [&](PathKind k) { return kind == static_cast<double>(k); };
  double speed = 60, flow = 1;
  if (is(PathKind::OuterPerimeter)) speed = 40;
  if (is(PathKind::InnerPerimeter)) speed = 55;
  if (is(PathKind::TopSolid) || is(PathKind::BottomSolid)) speed = 45;
  if (is(PathKind::Bridge)) speed = 25, flow = 0.8;
  if (layer < 2) speed = 20, flow = 1.05;
  if (area < 4) speed = 15;
  if (area < 25 && is(PathKind::OuterPerimeter)) speed = 25;
  if (c.get(FieldId::PieceOverhang) > 0.3) speed = 15;
  if (c.get(FieldId::PieceLength) < 0.5 && is(PathKind::Infill)) speed = 30;
  double zb = c.get(FieldId::LayerZBottom);
  if (zb >= 10 && zb <= 20) flow = 0.98;
  if (c.get(FieldId::IslandSupported) < 0.5 && !is(PathKind::Skirt)) speed = 20;
  if (c.get(FieldId::PathPerimeter) > 2) speed = 50;
  if (c.get(FieldId::CellSolid) != 0 && area > 100) speed = 80;
  if (std::fmod(layer, 10) == 0 && layer > 0) flow = 1.02;
  if (c.get(FieldId::PathLength) > 100 && is(PathKind::InnerPerimeter)) speed = 65;
  return {speed, flow};
}

// The same rules in Lua: what a slicer embedding Lua would run per piece.
const char* kLua = R"(
local OUTER, INNER, INFILL, TOP, BOTTOM, BRIDGE, SKIRT = 0, 1, 2, 4, 5, 6, 7
function decide(c)
  local speed, flow = 60, 1.0
  local kind = c.kind
  if kind == OUTER then speed = 40 end
  if kind == INNER then speed = 55 end
  if kind == TOP or kind == BOTTOM then speed = 45 end
  if kind == BRIDGE then speed = 25; flow = 0.8 end
  if c.layer < 2 then speed = 20; flow = 1.05 end
  if c.area < 4 then speed = 15 end
  if c.area < 25 and kind == OUTER then speed = 25 end
  if c.overhang > 0.3 then speed = 15 end
  if c.plen < 0.5 and kind == INFILL then speed = 30 end
  if c.zb >= 10 and c.zb <= 20 then flow = 0.98 end
  if c.supported < 0.5 and kind ~= SKIRT then speed = 20 end
  if c.perimeter > 2 then speed = 50 end
  if c.solid and c.area > 100 then speed = 80 end
  if c.layer % 10 == 0 and c.layer > 0 then flow = 1.02 end
  if c.length > 100 and kind == INNER then speed = 65 end
  return speed, flow
end
)";

// A synthetic print: its layers, islands, paths and pieces, with the fields the rules read.
struct PieceF { double length, overhang; };
struct PathF { int kind, perimeter; double length; bool solid; std::vector<PieceF> pieces; };
struct IslandF { double area, supported; std::vector<PathF> paths; };
struct LayerF { int index; double z_bottom; std::vector<IslandF> islands; };

std::vector<LayerF> make_print(size_t pieces) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<LayerF> layers;
  size_t n = 0;
  for (int l = 0; n < pieces; ++l) {
    LayerF layer{l, 0.2 * l, {}};
    int islands = 1 + static_cast<int>(u(rng) * 6);
    for (int i = 0; i < islands && n < pieces; ++i) {
      IslandF isl{std::pow(10, u(rng) * 3 - 0.5), u(rng) < 0.1 ? u(rng) : 1.0, {}};
      int paths = 5 + static_cast<int>(u(rng) * 40);
      for (int p = 0; p < paths && n < pieces; ++p) {
        static const int kinds[] = {0, 1, 1, 2, 2, 2, 3, 4, 5, 6};
        int kind = kinds[static_cast<int>(u(rng) * 10)];
        PathF path{kind, kind <= 1 ? static_cast<int>(u(rng) * 4) : -1, u(rng) * 200, kind >= 3, {}};
        int count = 4 + static_cast<int>(u(rng) * 30);
        for (int k = 0; k < count && n < pieces; ++k, ++n)
          path.pieces.push_back({u(rng) * 3, u(rng) < 0.05 ? u(rng) : 0.0});
        isl.paths.push_back(std::move(path));
      }
      layer.islands.push_back(std::move(isl));
    }
    layers.push_back(std::move(layer));
  }
  return layers;
}

// Walks the print like the slicer: `enter(level)` at each element, `piece()` for each piece.
template <class Enter, class Piece>
void walk(const std::vector<LayerF>& print, ctx::Context& c, Enter&& enter, Piece&& piece) {
  for (const auto& l : print) {
    c.clear_from(Level::Layer);
    c.set(FieldId::LayerIndex, l.index);
    c.set(FieldId::LayerZBottom, l.z_bottom);
    enter(Level::Layer);
    for (const auto& isl : l.islands) {
      c.clear_from(Level::Island);
      c.set(FieldId::IslandArea, isl.area);
      c.set(FieldId::IslandSupported, isl.supported);
      enter(Level::Island);
      for (const auto& p : isl.paths) {
        c.clear_from(Level::Cell);
        c.set(FieldId::CellSolid, p.solid ? 1 : 0);
        c.set(FieldId::PathKind, p.kind);
        c.set(FieldId::PathPerimeter, p.perimeter);
        c.set(FieldId::PathLength, p.length);
        enter(Level::Path);
        for (const auto& pc : p.pieces) {
          c.clear_from(Level::Piece);
          c.set(FieldId::PieceLength, pc.length);
          c.set(FieldId::PieceOverhang, pc.overhang);
          enter(Level::Piece);
          piece();
        }
      }
    }
  }
}

double now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  size_t pieces = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 2'000'000;
  int runs = argc > 2 ? std::atoi(argv[2]) : 5;
  auto print = make_print(pieces);

  // The VM.
  compiler::FrontendOptions fo;
  fo.read_file = [](const std::filesystem::path&) -> std::optional<std::string> { return std::nullopt; };
  diag::Sink sink;
  ast::Program program;
  compiler::load_source(program, "bench.rules", kRules, fo, sink);
  if (!compiler::check(program, sink) || sink.has_errors()) {
    std::fprintf(stderr, "vm_bench: the rules do not check\n");
    return 1;
  }
  auto code = compiler::generate(program);
  auto rs = vm::RuleSet::create(std::move(*code));
  if (!rs) {
    std::fprintf(stderr, "vm_bench: %s\n", rs.error().to_string().c_str());
    return 1;
  }

  // Lua: one table per run, its fields updated when the loop enters a level.
  lua_State* L = luaL_newstate();
  luaL_openlibs(L);
  if (luaL_dostring(L, kLua) != LUA_OK) {
    std::fprintf(stderr, "vm_bench: lua: %s\n", lua_tostring(L, -1));
    return 1;
  }

  std::vector<Decided> want, got_vm, got_lua;
  want.reserve(pieces), got_vm.reserve(pieces), got_lua.reserve(pieces);
  double t_walk = 1e9, t_cpp = 1e9, t_vm = 1e9, t_lua = 1e9;
  for (int r = 0; r < runs; ++r) {
    ctx::Context c;
    // The walk alone (what every variant pays to set the context).
    double t0 = now();
    size_t count = 0;
    walk(print, c, [](Level) {}, [&] { ++count; });
    t_walk = std::min(t_walk, now() - t0);

    want.clear();
    t0 = now();
    walk(print, c, [](Level) {}, [&] { want.push_back(by_hand(c)); });
    t_cpp = std::min(t_cpp, now() - t0);

    got_vm.clear();
    auto props = ctx::PropertyValues::schema_defaults();
    const double speed0 = props[PropId::Speed], flow0 = props[PropId::Flow];
    c.set_props(&props);
    t0 = now();
    walk(print, c, [](Level) {}, [&] {
      props[PropId::Speed] = speed0;  // the values below the rules
      props[PropId::Flow] = flow0;
      (void)(*rs)->decide(Stage::Piece, c, props);
      got_vm.push_back({props[PropId::Speed], props[PropId::Flow]});
    });
    t_vm = std::min(t_vm, now() - t0);

    got_lua.clear();
    lua_newtable(L);
    int table = lua_gettop(L);
    lua_getglobal(L, "decide");
    int fn = lua_gettop(L);
    auto setn = [&](const char* k, double v) {
      lua_pushnumber(L, v);
      lua_setfield(L, table, k);
    };
    t0 = now();
    walk(print, c,
         [&](Level level) {
           switch (level) {
             case Level::Layer:
               setn("layer", c.get(FieldId::LayerIndex));
               setn("zb", c.get(FieldId::LayerZBottom));
               break;
             case Level::Island:
               setn("area", c.get(FieldId::IslandArea));
               setn("supported", c.get(FieldId::IslandSupported));
               break;
             case Level::Path:
               lua_pushboolean(L, c.get(FieldId::CellSolid) != 0);
               lua_setfield(L, table, "solid");
               setn("kind", c.get(FieldId::PathKind));
               setn("perimeter", c.get(FieldId::PathPerimeter));
               setn("length", c.get(FieldId::PathLength));
               break;
             case Level::Piece:
               setn("plen", c.get(FieldId::PieceLength));
               setn("overhang", c.get(FieldId::PieceOverhang));
               break;
             default:
               break;
           }
         },
         [&] {
           lua_pushvalue(L, fn);
           lua_pushvalue(L, table);
           lua_call(L, 1, 2);
           got_lua.push_back({lua_tonumber(L, -2), lua_tonumber(L, -1)});
           lua_pop(L, 2);
         });
    t_lua = std::min(t_lua, now() - t0);
    lua_settop(L, 0);
  }
  if (std::getenv("VM_BENCH_PROFILE")) {  // only the VM, many times (for perf)
    ctx::Context c;
    auto props = ctx::PropertyValues::schema_defaults();
    c.set_props(&props);
    for (int r = 0; r < 20; ++r)
      walk(print, c, [](Level) {}, [&] { (void)(*rs)->decide(Stage::Piece, c, props); });
  }
  size_t bad = 0;
  for (size_t i = 0; i < want.size(); ++i) {
    auto same = [](Decided a, Decided b) { return std::abs(a.speed - b.speed) < 1e-9 && std::abs(a.flow - b.flow) < 1e-9; };
    if (!same(want[i], got_vm[i]) || !same(want[i], got_lua[i])) ++bad;
  }
  lua_close(L);
  auto ns = [&](double t) { return (t - t_walk) / static_cast<double>(want.size()) * 1e9; };
  std::printf("filters: 16 rules deciding speed and flow, %zu pieces in %zu layers (best of %d runs)\n",
              want.size(), print.size(), runs);
  std::printf("%-26s %12s %14s\n", "", "ns / piece", "vs hand C++");
  std::printf("%-26s %12.1f %14s\n", "hand-written C++", ns(t_cpp), "1.00");
  std::printf("%-26s %12.1f %14.2f\n", "rule VM", ns(t_vm), ns(t_vm) / ns(t_cpp));
  std::printf("%-26s %12.1f %14.2f\n", "Lua 5.4", ns(t_lua), ns(t_lua) / ns(t_cpp));
  std::printf("VM / C++ = %.2f (target <= 2), Lua / VM = %.2f (target > 1); context walk alone: %.1f ns / piece\n",
              ns(t_vm) / ns(t_cpp), ns(t_lua) / ns(t_vm), t_walk / static_cast<double>(want.size()) * 1e9);
  if (bad) {
    std::printf("MISMATCH: %zu pieces decided differently\n", bad);
    return 1;
  }
  return 0;
}
