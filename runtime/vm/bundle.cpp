#include "runtime/vm/bundle.h"

#include <fmt/format.h>

#include <cstring>
#include <vector>

#include "base/fnv.h"
#include "runtime/vm/verify.h"

namespace tranche::vm {

namespace {

enum Section : uint32_t { kStrings = 1, kConsts, kCode, kChunks, kRules, kSlots, kOrder, kDebug };
constexpr uint32_t kSectionCount = 8;

class Writer {
 public:
  void u8(uint8_t v) { s_.push_back(static_cast<char>(v)); }
  void u16(uint16_t v) { raw(v); }
  void u32(uint32_t v) { raw(v); }
  void u64(uint64_t v) { raw(v); }
  void f64(double v) {
    uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    u64(b);
  }
  void str(const std::string& v) {
    u32(static_cast<uint32_t>(v.size()));
    s_ += v;
  }
  void strings(const std::vector<std::string>& v) {
    u32(static_cast<uint32_t>(v.size()));
    for (const auto& x : v) str(x);
  }
  void u32s(const std::vector<uint32_t>& v) {
    u32(static_cast<uint32_t>(v.size()));
    for (uint32_t x : v) u32(x);
  }
  void align() {
    while (s_.size() % 8) s_.push_back('\0');
  }
  std::string& bytes() { return s_; }

 private:
  template <class T>
  void raw(T v) {
    for (size_t i = 0; i < sizeof(T); ++i) s_.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
  }
  std::string s_;
};

void candidates(Writer& w, const Candidates& cands) {
  w.u32(static_cast<uint32_t>(cands.size()));
  for (const auto& c : cands) {
    w.u32(c.rule);
    w.u32(c.chunk);
    w.u8(c.append ? 1 : 0);
    w.u8(0), w.u8(0), w.u8(0);
  }
}

std::string section(uint32_t id, const Program& p) {
  Writer w;
  switch (id) {
    case kStrings:
      w.strings(p.strings);
      break;
    case kConsts:
      w.u32(static_cast<uint32_t>(p.consts.size()));
      for (double v : p.consts) w.f64(v);
      break;
    case kCode:
      w.u32(static_cast<uint32_t>(p.code.size()));
      for (const auto& in : p.code) w.u64(in.pack());
      break;
    case kChunks:
      w.u32(static_cast<uint32_t>(p.chunks.size()));
      for (const auto& c : p.chunks) {
        w.u32(c.start);
        w.u32(c.size);
        w.u16(c.regs);
        w.u8(static_cast<uint8_t>(c.kind));
        w.u8(0);
      }
      break;
    case kRules:
      w.u32(static_cast<uint32_t>(p.conjuncts.size()));
      for (const auto& c : p.conjuncts) {
        w.u32(c.chunk);
        w.u8(static_cast<uint8_t>(c.level));
        w.u8(0), w.u8(0), w.u8(0);
      }
      w.u32(static_cast<uint32_t>(p.rules.size()));
      for (const auto& r : p.rules) {
        w.u32(r.first);
        w.u32(r.count);
      }
      break;
    case kSlots:
      for (const auto& c : p.props) candidates(w, c);
      for (const auto& level : p.hooks)
        for (const auto& c : level) candidates(w, c);
      for (const auto& c : p.replace) candidates(w, c);
      break;
    case kOrder:
      w.u32(static_cast<uint32_t>(p.property_order.size()));
      for (auto q : p.property_order) w.u16(static_cast<uint16_t>(q));
      break;
    case kDebug: {
      const Debug& d = p.debug;
      w.strings(d.files);
      w.u32(static_cast<uint32_t>(d.locs.size()));
      for (const auto& l : d.locs) w.u32(l.file), w.u32(l.line), w.u32(l.col);
      w.u32s(d.instr_loc);
      w.strings(d.rule_names);
      w.u32s(d.rule_loc);
      w.strings(d.conj_text);
      w.u32s(d.conj_loc);
      break;
    }
    default:
      break;
  }
  return std::move(w.bytes());
}

class Reader {
 public:
  Reader(std::string_view b, std::string what) : b_(b), what_(std::move(what)) {}
  bool ok() const { return ok_; }
  const std::string& what() const { return what_; }
  size_t left() const { return b_.size() - pos_; }
  bool done() const { return pos_ == b_.size(); }

  uint8_t u8() { return static_cast<uint8_t>(raw(1)); }
  uint16_t u16() { return static_cast<uint16_t>(raw(2)); }
  uint32_t u32() { return static_cast<uint32_t>(raw(4)); }
  uint64_t u64() { return raw(8); }
  double f64() {
    uint64_t v = u64();
    double d;
    std::memcpy(&d, &v, sizeof d);
    return d;
  }
  // A count of items of at least `min_bytes` each, checked against what is left.
  uint32_t count(size_t min_bytes) {
    uint32_t n = u32();
    if (ok_ && static_cast<uint64_t>(n) * min_bytes > left()) fail("a count larger than the data");
    return ok_ ? n : 0;
  }
  std::string str() {
    uint32_t n = count(1);
    if (!ok_) return {};
    std::string s(b_.substr(pos_, n));
    pos_ += n;
    return s;
  }
  std::vector<std::string> strings() {
    uint32_t n = count(4);
    std::vector<std::string> v;
    v.reserve(n);
    for (uint32_t i = 0; i < n && ok_; ++i) v.push_back(str());
    return v;
  }
  std::vector<uint32_t> u32s() {
    uint32_t n = count(4);
    std::vector<uint32_t> v(n);
    for (uint32_t i = 0; i < n && ok_; ++i) v[i] = u32();
    return v;
  }
  void fail(const char* why) {
    if (ok_) error_ = why;
    ok_ = false;
  }
  const std::string& error() const { return error_; }

 private:
  uint64_t raw(size_t n) {
    if (!ok_ || left() < n) {
      fail("truncated");
      return 0;
    }
    uint64_t v = 0;
    for (size_t i = 0; i < n; ++i) v |= uint64_t(static_cast<unsigned char>(b_[pos_ + i])) << (8 * i);
    pos_ += n;
    return v;
  }
  std::string_view b_;
  size_t pos_ = 0;
  bool ok_ = true;
  std::string what_, error_;
};

Candidates read_candidates(Reader& r) {
  uint32_t n = r.count(12);
  Candidates c(n);
  for (uint32_t i = 0; i < n && r.ok(); ++i) {
    c[i].rule = r.u32();
    c[i].chunk = r.u32();
    uint8_t a = r.u8();
    if (a > 1) r.fail("a flag that is neither 0 nor 1");
    c[i].append = a == 1;
    if (r.u8() != 0 || r.u8() != 0 || r.u8() != 0) r.fail("non-zero padding");
  }
  return c;
}

}  // namespace

uint64_t bundle_checksum(std::string_view bundle) { return bundle.size() < 32 ? 0 : fnv1a64(bundle.substr(32)); }

bool looks_like_bundle(std::string_view bytes) {
  return bytes.size() >= sizeof kBundleMagic && std::memcmp(bytes.data(), kBundleMagic, sizeof kBundleMagic) == 0;
}

std::string write_bundle(const Program& p, bool with_debug) {
  bool debug = with_debug && !p.debug.empty();
  uint32_t n = debug ? kSectionCount : kSectionCount - 1;
  std::vector<std::string> bodies;
  for (uint32_t id = 1; id <= n; ++id) bodies.push_back(section(id, p));
  Writer w;
  for (char c : kBundleMagic) w.u8(static_cast<uint8_t>(c));
  w.u32(kBundleVersion);
  w.u32(debug ? 1 : 0);
  w.u64(schema::schema_hash());
  w.u64(0);  // checksum, patched below
  w.u32(n);
  w.u32(0);  // file size, patched below
  size_t offset = 40 + 16 * size_t(n);
  offset = (offset + 7) / 8 * 8;
  for (uint32_t i = 0; i < n; ++i) {
    w.u32(i + 1);
    w.u32(0);
    w.u32(static_cast<uint32_t>(offset));
    w.u32(static_cast<uint32_t>(bodies[i].size()));
    offset = (offset + bodies[i].size() + 7) / 8 * 8;
  }
  w.align();
  for (const auto& b : bodies) {
    w.bytes() += b;
    w.align();
  }
  std::string& s = w.bytes();
  uint32_t size = static_cast<uint32_t>(s.size());
  for (int i = 0; i < 4; ++i) s[36 + i] = static_cast<char>((size >> (8 * i)) & 0xff);
  uint64_t sum = bundle_checksum(s);
  for (int i = 0; i < 8; ++i) s[24 + i] = static_cast<char>((sum >> (8 * i)) & 0xff);
  return std::move(s);
}

namespace {

// The rules section: the conjuncts, then the rules.
void read_rules(Reader& r, Program& p) {
  uint32_t k = r.count(8);
  p.conjuncts.resize(k);
  for (uint32_t i = 0; i < k && r.ok(); ++i) {
    p.conjuncts[i].chunk = r.u32();
    uint8_t level = r.u8();
    if (level >= schema::kLevelCount) r.fail("unknown level");
    p.conjuncts[i].level = static_cast<schema::Level>(level);
    if (r.u8() != 0 || r.u8() != 0 || r.u8() != 0) r.fail("non-zero padding");
  }
  uint32_t m = r.count(8);
  p.rules.resize(m);
  for (uint32_t i = 0; i < m && r.ok(); ++i) {
    p.rules[i].first = r.u32();
    p.rules[i].count = r.u32();
  }
}

// The debug section.
void read_debug(Reader& r, Debug& d) {
  d.files = r.strings();
  uint32_t k = r.count(12);
  d.locs.resize(k);
  for (uint32_t i = 0; i < k && r.ok(); ++i) d.locs[i] = {r.u32(), r.u32(), r.u32()};
  d.instr_loc = r.u32s();
  d.rule_names = r.strings();
  d.rule_loc = r.u32s();
  d.conj_text = r.strings();
  d.conj_loc = r.u32s();
}

// The program from its sections (`sec[id]`; the debug section only when `debug`).
Result<Program> read_sections(const std::vector<std::string_view>& sec, bool debug, const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Error{name, fmt::format("{}; rebuild it with `rulec build`", why)};
  };
  Program p;
  auto parse = [&](uint32_t id, auto&& body) -> Status {
    Reader r(sec[id], "");
    body(r);
    if (r.ok() && !r.done()) r.fail("trailing bytes");
    if (!r.ok()) return bad(fmt::format("section {}: {}", id, r.error()));
    return ok_status();
  };
  Status s = parse(kStrings, [&](Reader& r) { p.strings = r.strings(); });
  if (s) s = parse(kConsts, [&](Reader& r) {
    uint32_t k = r.count(8);
    p.consts.resize(k);
    for (uint32_t i = 0; i < k && r.ok(); ++i) p.consts[i] = r.f64();
  });
  if (s) s = parse(kCode, [&](Reader& r) {
    uint32_t k = r.count(8);
    p.code.resize(k);
    for (uint32_t i = 0; i < k && r.ok(); ++i) p.code[i] = Instr::unpack(r.u64());
  });
  if (s) s = parse(kChunks, [&](Reader& r) {
    uint32_t k = r.count(12);
    p.chunks.resize(k);
    for (uint32_t i = 0; i < k && r.ok(); ++i) {
      auto& c = p.chunks[i];
      c.start = r.u32();
      c.size = r.u32();
      c.regs = r.u16();
      uint8_t kind = r.u8();
      if (kind > static_cast<uint8_t>(ChunkKind::Replace)) r.fail("unknown chunk kind");
      c.kind = static_cast<ChunkKind>(kind);
      if (r.u8() != 0) r.fail("non-zero padding");
    }
  });
  if (s) s = parse(kRules, [&](Reader& r) { read_rules(r, p); });
  if (s) s = parse(kSlots, [&](Reader& r) {
    for (auto& c : p.props) c = read_candidates(r);
    for (auto& level : p.hooks)
      for (auto& c : level) c = read_candidates(r);
    for (auto& c : p.replace) c = read_candidates(r);
  });
  if (s) s = parse(kOrder, [&](Reader& r) {
    uint32_t k = r.count(2);
    for (uint32_t i = 0; i < k && r.ok(); ++i) {
      uint16_t id = r.u16();
      if (id >= schema::kPropCount) r.fail("unknown property");
      p.property_order.push_back(static_cast<schema::PropId>(id));
    }
  });
  if (s && debug) s = parse(kDebug, [&](Reader& r) { read_debug(r, p.debug); });
  if (!s) return s.error();
  if (debug && p.debug.empty()) return bad("the debug section is empty");
  if (Status v = verify(p); !v) return Error{name, fmt::format("this bundle is invalid ({}); rebuild it with `rulec build`", v.error().message)};
  return p;
}

}  // namespace

Result<Program> read_bundle(std::string_view bytes, const std::string& name) {
  auto bad = [&](const std::string& why) {
    return Error{name, fmt::format("{}; rebuild it with `rulec build`", why)};
  };
  if (bytes.size() > kMaxBundleBytes) return bad("this bundle is larger than 256 MiB");
  if (!looks_like_bundle(bytes)) return Error{name, "not a rule bundle (it does not start with TRNCHRUL)"};
  Reader h(bytes, "header");
  for (size_t i = 0; i < sizeof kBundleMagic; ++i) h.u8();
  uint32_t version = h.u32();
  uint32_t flags = h.u32();
  uint64_t hash = h.u64();
  uint64_t sum = h.u64();
  uint32_t n = h.u32();
  uint32_t size = h.u32();
  if (!h.ok()) return bad("the bundle is truncated");
  if (version < kBundleVersion)
    return bad(fmt::format("this bundle has format version {}, from an older tranche (this one reads version {})",
                           version, kBundleVersion));
  if (version != kBundleVersion)
    return bad(fmt::format("bundle format version {} is not the one this tranche reads ({})", version, kBundleVersion));
  if (hash != schema::schema_hash())
    return bad("this bundle was compiled for another version of the context (fields and properties)");
  if (size != bytes.size()) return bad(fmt::format("the bundle should be {} bytes but is {} (truncated?)", size, bytes.size()));
  if (bundle_checksum(bytes) != sum) return bad("the bundle's checksum does not match (the file is damaged)");
  if (flags > 1) return bad("unknown flags in the header");
  bool debug = flags & 1;
  if (n != (debug ? kSectionCount : kSectionCount - 1)) return bad("unexpected number of sections");
  std::vector<std::string_view> sec(kSectionCount + 1);
  for (uint32_t i = 0; i < n; ++i) {
    uint32_t id = h.u32();
    uint32_t zero = h.u32();
    uint32_t off = h.u32();
    uint32_t len = h.u32();
    if (!h.ok()) return bad("the section table is truncated");
    if (id != i + 1 || zero != 0 || off % 8 != 0 || uint64_t(off) + len > bytes.size() || off < 40 + 16 * uint64_t(n))
      return bad(fmt::format("section {} is malformed", i + 1));
    sec[id] = bytes.substr(off, len);
  }

  return read_sections(sec, debug, name);
}

}  // namespace tranche::vm
