#include "compiler/prover.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace tranche::compiler::prover {

using ast::Expr;
using ast::ExprKind;
using ast::Op;
using ast::RefKind;

namespace {

bool empty(const Cons& c, const Var& v) {
  if (v.kind == VarKind::Set) return c.mask == 0;
  return c.lo > c.hi || (c.lo == c.hi && (c.lo_open || c.hi_open));
}

// Integer variables keep closed integer bounds, so that differences stay exact.
void normalize(Cons& c, const Var& v) {
  if (v.kind != VarKind::Integer) return;
  if (std::isfinite(c.lo)) c.lo = c.lo_open ? std::floor(c.lo) + 1 : std::ceil(c.lo);
  if (std::isfinite(c.hi)) c.hi = c.hi_open ? std::ceil(c.hi) - 1 : std::floor(c.hi);
  c.lo_open = c.hi_open = false;
}

Cons meet(const Cons& a, const Cons& b, const Var& v) {
  Cons c = a;
  if (v.kind == VarKind::Set) {
    c.mask = a.mask & b.mask;
    return c;
  }
  if (b.lo > a.lo || (b.lo == a.lo && b.lo_open)) {
    c.lo = b.lo;
    c.lo_open = b.lo_open;
  }
  if (b.hi < a.hi || (b.hi == a.hi && b.hi_open)) {
    c.hi = b.hi;
    c.hi_open = b.hi_open;
  }
  normalize(c, v);
  return c;
}

const Cons* find(const Box& b, int var) {
  auto it =
      std::lower_bound(b.cons.begin(), b.cons.end(), var, [](const Cons& c, int v) { return c.var < v; });
  return it != b.cons.end() && it->var == var ? &*it : nullptr;
}

void set(Box& b, const Cons& c) {
  auto it =
      std::lower_bound(b.cons.begin(), b.cons.end(), c.var, [](const Cons& x, int v) { return x.var < v; });
  if (it != b.cons.end() && it->var == c.var)
    *it = c;
  else
    b.cons.insert(it, c);
}

std::string collapse_spaces(std::string_view s) {
  std::string out;
  bool space = false;
  for (char c : s) {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      space = !out.empty();
      continue;
    }
    if (space) out += ' ';
    space = false;
    out += c;
  }
  return out;
}

bool reads_inherited(const Expr& e) {
  if (e.ref == RefKind::Inherited) return true;
  for (const auto& a : e.args)
    if (reads_inherited(*a)) return true;
  return false;
}

// The natural domain of a numeric field: indices and counts are >= 0 (a perimeter number is
// -1 for other paths), sizes, areas and times >= 0, ratios in [0, 1]; anything else is open.
std::pair<double, double> field_domain(const schema::FieldInfo& f) {
  if (f.type == schema::Type::Int) return {f.id == schema::FieldId::PathPerimeter ? -1 : 0, INFINITY};
  switch (f.unit) {
    case schema::Unit::Ratio:
      return {0, 1};
    case schema::Unit::Mm2:  // not Mm3: an inside-out mesh has a negative volume
    case schema::Unit::S:
      return {0, INFINITY};
    case schema::Unit::Mm: {
      bool coordinate = f.name.ends_with("center_x") || f.name.ends_with("center_y") || f.name == "piece.x" ||
                        f.name == "piece.y";
      return {coordinate ? -INFINITY : 0, INFINITY};
    }
    default:
      return {-INFINITY, INFINITY};
  }
}

class Normalizer {
 public:
  Normalizer(Space& space, const ast::SourceMap& sources, int rule)
      : space_(space), sources_(sources), rule_(rule) {}
  bool overflow = false;

  Boxes go(const Expr& e, bool neg) {
    if (overflow) return {};
    if (e.constant && e.type.kind == ast::Kind::Bool) return ((*e.constant != 0) != neg) ? all() : Boxes{};
    if (e.kind == ExprKind::Unary && e.op == Op::Not) return go(*e.args[0], !neg);
    if (e.kind == ExprKind::Binary && (e.op == Op::And || e.op == Op::Or)) {
      bool conjunction = (e.op == Op::And) != neg;
      Boxes a = go(*e.args[0], neg), b = go(*e.args[1], neg);
      return conjunction ? conj(a, b) : disj(std::move(a), std::move(b));
    }
    if (e.kind == ExprKind::If && e.type.kind == ast::Kind::Bool) {
      Boxes yes = conj(go(*e.args[0], false), go(*e.args[1], neg));
      Boxes no = conj(go(*e.args[0], true), go(*e.args[2], neg));
      return disj(std::move(yes), std::move(no));
    }
    if (auto boxes = comparison(e, neg)) return *boxes;
    return atom(e, neg);
  }

 private:
  Boxes all() { return {Box{}}; }

  Boxes conj(const Boxes& a, const Boxes& b) {
    Boxes out;
    for (const Box& x : a)
      for (const Box& y : b)
        if (auto z = intersect(x, y, space_)) {
          out.push_back(std::move(*z));
          if (out.size() > kMaxBoxes) {
            overflow = true;
            return {};
          }
        }
    return out;
  }

  Boxes disj(Boxes a, Boxes b) {
    a.insert(a.end(), std::make_move_iterator(b.begin()), std::make_move_iterator(b.end()));
    if (a.size() > kMaxBoxes) overflow = true;
    return a;
  }

  Boxes one(Cons c) {
    const Var& v = space_.var(c.var);
    c = meet(space_.full(c.var), c, v);
    if (empty(c, v)) return {};
    Box b;
    b.cons.push_back(c);
    return {b};
  }

  std::optional<int> var_of(const Expr& e) {
    if (e.ref == RefKind::Field && (e.kind == ExprKind::Member)) return space_.field(e.field);
    if (e.ref == RefKind::Property) return space_.property(e.prop);
    return std::nullopt;
  }

  Boxes numeric(int var, Op op, double c, bool neg) {
    if (neg) {
      static const Op flip[] = {Op::None, Op::None, Op::None, Op::None, Op::None, Op::None, Op::None,
                                Op::None, Op::Ne,   Op::Eq,   Op::Ge,   Op::Gt,   Op::Le,   Op::Lt};
      op = flip[static_cast<size_t>(op)];
    }
    Cons k;
    k.var = var;
    switch (op) {
      case Op::Lt:
        k.hi = c, k.hi_open = true;
        break;
      case Op::Le:
        k.hi = c;
        break;
      case Op::Gt:
        k.lo = c, k.lo_open = true;
        break;
      case Op::Ge:
        k.lo = c;
        break;
      case Op::Eq:
        k.lo = k.hi = c;
        break;
      case Op::Ne: {
        Cons below = k, above = k;
        below.hi = c, below.hi_open = true;
        above.lo = c, above.lo_open = true;
        return disj(one(below), one(above));
      }
      default:
        return {};
    }
    return one(k);
  }

  Boxes set(int var, uint64_t mask, bool neg) {
    Cons k;
    k.var = var;
    k.mask = neg ? (space_.var(var).full & ~mask) : mask;
    return one(k);
  }

  // `field OP constant` (either way round), `field in lo..hi`, `field in (a, b)`, a bare
  // boolean field; nothing for anything else.
  std::optional<Boxes> comparison(const Expr& e, bool neg) {
    if (auto v = var_of(e); v && e.type.kind == ast::Kind::Bool) return set(*v, 2, neg);
    if (e.kind == ExprKind::Binary && e.op >= Op::Eq && e.op <= Op::Ge) {
      const Expr* a = e.args[0].get();
      const Expr* b = e.args[1].get();
      Op op = e.op;
      if (!var_of(*a) && var_of(*b)) {
        std::swap(a, b);
        static const Op mirror[] = {Op::None, Op::None, Op::None, Op::None, Op::None, Op::None, Op::None,
                                    Op::None, Op::Eq,   Op::Ne,   Op::Gt,   Op::Ge,   Op::Lt,   Op::Le};
        op = mirror[static_cast<size_t>(op)];
      }
      auto v = var_of(*a);
      if (!v || !b->constant) return std::nullopt;
      if (space_.var(*v).kind == VarKind::Set) {
        if (op != Op::Eq && op != Op::Ne) return std::nullopt;
        int value = static_cast<int>(*b->constant);
        if (value < 0 || value > 63) return std::nullopt;
        return set(*v, uint64_t{1} << value, neg != (op == Op::Ne));
      }
      return numeric(*v, op, *b->constant, neg);
    }
    if (e.kind == ExprKind::InRange) {
      auto v = var_of(*e.args[0]);
      if (!v || !e.args[1]->constant || !e.args[2]->constant || space_.var(*v).kind == VarKind::Set)
        return std::nullopt;
      Cons k;
      k.var = *v;
      k.lo = *e.args[1]->constant;
      k.hi = *e.args[2]->constant;
      if (!neg) return one(k);
      Cons below, above;
      below.var = above.var = *v;
      below.hi = k.lo, below.hi_open = true;
      above.lo = k.hi, above.lo_open = true;
      return disj(one(below), one(above));
    }
    if (e.kind == ExprKind::InSet) {
      auto v = var_of(*e.args[0]);
      if (!v) return std::nullopt;
      for (size_t i = 1; i < e.args.size(); ++i)
        if (!e.args[i]->constant) return std::nullopt;
      if (space_.var(*v).kind == VarKind::Set) {
        uint64_t mask = 0;
        for (size_t i = 1; i < e.args.size(); ++i) {
          int value = static_cast<int>(*e.args[i]->constant);
          if (value < 0 || value > 63) return std::nullopt;
          mask |= uint64_t{1} << value;
        }
        return set(*v, mask, neg);
      }
      Boxes out = neg ? all() : Boxes{};
      for (size_t i = 1; i < e.args.size(); ++i) {
        Boxes b = numeric(*v, Op::Eq, *e.args[i]->constant, neg);
        out = neg ? conj(out, b) : disj(std::move(out), std::move(b));
      }
      return out;
    }
    return std::nullopt;
  }

  Boxes atom(const Expr& e, bool neg) {
    std::string key = collapse_spaces(sources_.text(e.span));
    if (reads_inherited(e)) key += fmt::format("#rule{}", rule_);
    return set(space_.atom(key), 2, neg);
  }

  Space& space_;
  const ast::SourceMap& sources_;
  int rule_;
};

}  // namespace

int Space::add(const std::string& key, Var v) {
  auto [it, inserted] = ids_.emplace(key, static_cast<int>(vars_.size()));
  if (inserted) vars_.push_back(v);
  return it->second;
}

int Space::field(schema::FieldId f) {
  const auto& info = schema::field(f);
  Var v;
  switch (info.type) {
    case schema::Type::Number:
    case schema::Type::Int: {
      v.kind = info.type == schema::Type::Int ? VarKind::Integer : VarKind::Real;
      auto [lo, hi] = field_domain(info);
      v.lo = lo;
      v.hi = hi;
      break;
    }
    case schema::Type::Bool:
      v.full = 3;
      break;
    case schema::Type::Enum: {
      size_t n = schema::enum_info(info.enum_type).values.size();
      v.full = n >= 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1;
      break;
    }
    case schema::Type::Text:  // compared with quoted text only: each comparison is an atom
      v.kind = VarKind::Integer;
      v.lo = -1;
      v.hi = 65535;
      break;
  }
  return add(fmt::format("field:{}", info.name), v);
}

int Space::property(schema::PropId p) {
  const auto& info = schema::property(p);
  Var v;
  switch (info.type) {
    case schema::Type::Number:
      v.kind = VarKind::Real;
      break;
    case schema::Type::Int:
      v.kind = VarKind::Integer;
      break;
    case schema::Type::Bool:
      v.full = 3;
      break;
    case schema::Type::Enum: {
      size_t n = schema::enum_info(info.enum_type).values.size();
      v.full = n >= 64 ? ~uint64_t{0} : (uint64_t{1} << n) - 1;
      break;
    }
    case schema::Type::Text:  // no property is a name
      v.kind = VarKind::Integer;
      break;
  }
  return add(fmt::format("prop:{}", info.name), v);
}

int Space::atom(const std::string& key) {
  Var v;
  v.full = 3;
  return add(fmt::format("atom:{}", key), v);
}

Cons Space::full(int id) const {
  const Var& v = var(id);
  Cons c;
  c.var = id;
  c.lo = v.lo;
  c.hi = v.hi;
  c.mask = v.full;
  return c;
}

std::optional<Boxes> to_boxes(const ast::Expr& filter, Space& space, const ast::SourceMap& sources, int rule,
                              bool negate) {
  Normalizer n(space, sources, rule);
  Boxes b = n.go(filter, negate);
  if (n.overflow) return std::nullopt;
  return b;
}

std::optional<Box> intersect(const Box& a, const Box& b, const Space& space) {
  Box out;
  out.cons.reserve(a.cons.size() + b.cons.size());
  size_t i = 0, j = 0;
  while (i < a.cons.size() || j < b.cons.size()) {
    if (j == b.cons.size() || (i < a.cons.size() && a.cons[i].var < b.cons[j].var)) {
      out.cons.push_back(a.cons[i++]);
    } else if (i == a.cons.size() || b.cons[j].var < a.cons[i].var) {
      out.cons.push_back(b.cons[j++]);
    } else {
      const Var& v = space.var(a.cons[i].var);
      Cons c = meet(a.cons[i], b.cons[j], v);
      if (empty(c, v)) return std::nullopt;
      out.cons.push_back(c);
      ++i;
      ++j;
    }
  }
  return out;
}

// Whether a ∩ b is non-empty, without building it.
bool overlaps(const Box& a, const Box& b, const Space& space) {
  size_t i = 0, j = 0;
  while (i < a.cons.size() && j < b.cons.size()) {
    if (a.cons[i].var < b.cons[j].var) {
      ++i;
    } else if (b.cons[j].var < a.cons[i].var) {
      ++j;
    } else {
      const Var& v = space.var(a.cons[i].var);
      if (empty(meet(a.cons[i], b.cons[j], v), v)) return false;
      ++i;
      ++j;
    }
  }
  return true;
}

Boxes subtract(const Box& a, const Box& b, const Space& space) {
  if (!overlaps(a, b, space)) return {a};
  Boxes out;
  Box rest = a;
  for (const Cons& cb : b.cons) {
    const Var& v = space.var(cb.var);
    const Cons* found = find(rest, cb.var);
    Cons ca = found ? *found : space.full(cb.var);
    auto emit = [&](Cons piece) {
      normalize(piece, v);
      if (empty(piece, v)) return;
      Box p = rest;
      set(p, piece);
      out.push_back(std::move(p));
    };
    if (v.kind == VarKind::Set) {
      Cons piece = ca;
      piece.mask = ca.mask & ~cb.mask;
      emit(piece);
    } else {
      if (std::isfinite(cb.lo) || cb.lo_open) {
        Cons left = ca;
        Cons cut;
        cut.var = cb.var;
        cut.hi = v.kind == VarKind::Integer ? cb.lo - (cb.lo_open ? 0 : 1) : cb.lo;
        cut.hi_open = v.kind == VarKind::Integer ? false : !cb.lo_open;
        emit(meet(left, cut, v));
      }
      if (std::isfinite(cb.hi) || cb.hi_open) {
        Cons right = ca;
        Cons cut;
        cut.var = cb.var;
        cut.lo = v.kind == VarKind::Integer ? cb.hi + (cb.hi_open ? 0 : 1) : cb.hi;
        cut.lo_open = v.kind == VarKind::Integer ? false : !cb.hi_open;
        emit(meet(right, cut, v));
      }
    }
    set(rest, meet(ca, cb, v));
  }
  return out;
}

std::optional<bool> covered(const Boxes& region, std::span<const Boxes* const> cover, const Space& space,
                            std::vector<size_t>* used, size_t limit) {
  Boxes rest = region;
  for (size_t i = 0; i < cover.size() && !rest.empty(); ++i) {
    bool touched = false;
    for (const Box& b : *cover[i]) {
      Boxes next;
      if (std::none_of(rest.begin(), rest.end(), [&](const Box& r) { return overlaps(r, b, space); }))
        continue;
      for (const Box& r : rest) {
        if (!overlaps(r, b, space)) {
          next.push_back(r);
          continue;
        }
        touched = true;
        Boxes pieces = subtract(r, b, space);
        next.insert(next.end(), std::make_move_iterator(pieces.begin()),
                    std::make_move_iterator(pieces.end()));
        if (next.size() > limit) return std::nullopt;
      }
      rest = std::move(next);
      if (rest.empty()) break;
    }
    if (touched && used) used->push_back(i);
  }
  return rest.empty();
}

}  // namespace tranche::compiler::prover
