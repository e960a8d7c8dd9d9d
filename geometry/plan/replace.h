// The replacer API (`replace island { ... }`, `replace path { ... }`): what a replacer's
// statements do to the element being replaced. Moves and text become the element's ops; `default`
// emits the element's normal output; `offset` and `reverse` alter it, after which it is measured
// and decided again (a new generation of its level), so the rest of the replacer and every later
// stage read the altered element.
#pragma once

#include "geometry/plan/nest.h"
#include "geometry/plan/plan.h"
#include "runtime/context/hooks.h"

namespace tranche::plan {

// What an island replacer needs from the layer task.
class IslandHost {
 public:
  virtual ~IslandHost() = default;
  virtual Nest& nest() = 0;
  // Measures and decides the island again (its shape changed).
  virtual Status redecide_island(IslandPlan& ip) = 0;
  // Builds the island's paths and cells from its shape and props.
  virtual Status build_island(IslandPlan& ip) = 0;
};

class IslandReplace final : public ctx::ReplaceApi {
 public:
  IslandReplace(IslandHost& host, IslandPlan& ip) : host_(host), ip_(ip) {}
  void move_to(double x, double y, const ctx::MoveOptions& o) override;
  void gcode(std::string_view line) override { ip_.ops.push_back(Op::line(line)); }
  void comment(std::string_view text) override;
  Status emit_default() override;
  Status offset(double mm) override;
  Status reverse() override { return Error{"replace island", "reverse applies to paths, not islands"}; }
  void retract() override { ip_.ops.push_back(Op::of(Op::Kind::Retract)); }
  // The first error of a move (move_to cannot return one).
  Status status = ok_status();

 private:
  IslandHost& host_;
  IslandPlan& ip_;
  bool built_ = false;
};

class PathReplace final : public ctx::ReplaceApi {
 public:
  PathReplace(Nest& nest, PathPlan& p) : nest_(nest), p_(p) {}
  void move_to(double x, double y, const ctx::MoveOptions& o) override;
  void gcode(std::string_view line) override { p_.ops.push_back(Op::line(line)); }
  void comment(std::string_view text) override;
  Status emit_default() override {
    p_.ops.push_back(Op::of(Op::Kind::Default));
    return ok_status();
  }
  Status offset(double mm) override;
  Status reverse() override;
  void retract() override { p_.ops.push_back(Op::of(Op::Kind::Retract)); }

 private:
  // The path's shape changed: the rest of the replacer reads the new one.
  void altered();
  Nest& nest_;
  PathPlan& p_;
};

// Bed millimetres to model units.
geo::Point to_model(const Nest& nest, double x_mm, double y_mm);

}  // namespace tranche::plan
