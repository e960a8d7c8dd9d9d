// libFuzzer target for bundles and the VM. Three kinds of input:
//   "TRNCHRUL..."  a bundle as is: the reader must refuse it cleanly or return a verified program
//   0x01 F ...     a bundle body (everything after the checksum; F&1: debug flag): the hash, size and
//                  checksum are filled in, so that mutations reach the section parser and the
//                  verifier instead of stopping at the checksum
//   anything else  rule text: compiled, written, read back (must round-trip), then one byte of
//                  the bundle is altered (position and value from the input) and it is read again
// Every program that loads is run: each stage decided, each hook and replacer run, on contexts
// with fields taken from the input. Nothing may crash, hang or exhaust memory.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <optional>
#include <string>

#include "compiler/check.h"
#include "compiler/codegen.h"
#include "compiler/frontend.h"
#include "grammar/parse.h"
#include "runtime/schema/schema.h"
#include "runtime/vm/bundle.h"
#include "runtime/vm/vm.h"

namespace {

using namespace tranche;

void put(std::string& s, size_t at, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) s[at + static_cast<size_t>(i)] = static_cast<char>((v >> (8 * i)) & 0xff);
}

// Fills in a header's schema hash, file size and checksum.
void seal(std::string& b) {
  if (b.size() < 40) return;
  put(b, 16, schema::schema_hash(), 8);
  put(b, 36, b.size(), 4);
  put(b, 24, vm::bundle_checksum(b), 8);
}

struct NullSink final : ctx::LineSink {
  size_t n = 0;
  void line(std::string_view t) override { n += t.size(); }
};

struct NullApi final : ctx::ReplaceApi {
  size_t n = 0;
  void move_to(double, double, const ctx::MoveOptions&) override { ++n; }
  void gcode(std::string_view t) override { n += t.size(); }
  void comment(std::string_view t) override { n += t.size(); }
  Status emit_default() override { return ok_status(); }
  Status offset(double) override { return ok_status(); }
  Status reverse() override { return ok_status(); }
  void retract() override { ++n; }
};

void run(vm::Program program, const uint8_t* data, size_t size) {
  auto rs = vm::RuleSet::create(std::move(program));
  if (!rs) return;
  ctx::Context c;
  c.clear_from(schema::Level::Print);
  for (int f = 0; f < schema::kFieldCount; ++f)
    c.set(static_cast<schema::FieldId>(f), size ? static_cast<double>(data[static_cast<size_t>(f) % size]) - 64 : 0);
  static const ctx::PointMm pts[] = {{0, 0}, {1, 0}, {1, 1}};
  c.set_points(pts);
  static const double values[] = {1, 2, 3};
  ctx::Collection coll(values, 3, [](const void* d, size_t i, schema::FieldId) { return static_cast<const double*>(d)[i]; });
  c.set_pieces(coll);
  c.set_islands(coll);
  auto props = ctx::PropertyValues::schema_defaults();
  c.set_props(&props);
  for (int s = 0; s < schema::kStageCount; ++s) (void)(*rs)->decide(static_cast<schema::Stage>(s), c, props);
  NullSink sink;
  NullApi api;
  for (int l = 0; l < schema::kLevelCount; ++l) {
    auto level = static_cast<schema::Level>(l);
    (void)(*rs)->run(level, ctx::When::Before, c, sink);
    (void)(*rs)->run(level, ctx::When::After, c, sink);
    (void)(*rs)->replace(level, c, api);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string in(reinterpret_cast<const char*>(data), size);
  if (vm::looks_like_bundle(in)) {
    if (auto p = vm::read_bundle(in, "fuzz.bundle")) run(std::move(*p), data, size);
    return 0;
  }
  if (size > 0 && data[0] == 0x01) {
    std::string b(32, '\0');  // magic, version, flags, hash, checksum; then the body
    std::memcpy(b.data(), vm::kBundleMagic, 8);
    put(b, 8, vm::kBundleVersion, 4);
    put(b, 12, size > 1 ? data[1] & 1 : 0, 4);  // with or without the debug section
    b += in.substr(std::min<size_t>(2, in.size()));
    if (b.size() < 40) b.resize(40, '\0');
    seal(b);
    if (auto p = vm::read_bundle(b, "fuzz.bundle")) run(std::move(*p), data, size);
    return 0;
  }
  static int runs = 0;
  if (++runs % 2000 == 0) grammar::clear_parser_caches();
  compiler::FrontendOptions options;
  options.stdlib_dir = "/nonexistent-tranche-stdlib";
  options.read_file = [](const std::filesystem::path&) -> std::optional<std::string> { return std::nullopt; };
  diag::Sink sink;
  ast::Program program;
  compiler::load_source(program, "fuzz.rules", in, options, sink);
  if (!compiler::check(program, sink) || sink.has_errors()) return 0;
  auto p = compiler::generate(program);
  if (!p) return 0;
  std::string bytes = vm::write_bundle(*p);
  auto back = vm::read_bundle(bytes, "fuzz.bundle");
  if (!back) __builtin_trap();  // a compiled program must always load
  if (vm::write_bundle(*back) != bytes) __builtin_trap();
  run(std::move(*back), data, size);
  // One damaged byte, resealed: the reader and verifier must cope.
  if (bytes.size() > 40 && size > 0) {
    size_t at = 40 + (std::hash<std::string_view>{}(in) % (bytes.size() - 40));
    bytes[at] = static_cast<char>(bytes[at] ^ (data[size / 2] | 1));
    seal(bytes);
    if (auto q = vm::read_bundle(bytes, "fuzz.bundle")) run(std::move(*q), data, size);
  }
  return 0;
}
