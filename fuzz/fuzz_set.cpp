// libFuzzer target: the command line's --set values, as `tranche slice` takes them: each line of
// the input is one `--set` argument. The words go through the argument parser (apps/slice_args),
// plain values into the cascade's overrides, the others (expressions, params) through the rule
// compiler, and the print stage is decided from the result. Every step must give a value or an
// Error, never crash or hang. Seeds: fuzz/corpus/set/.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "apps/slice_args.h"
#include "compiler/load_rules.h"
#include "runtime/context/cascade.h"
#include "runtime/context/overrides.h"

namespace {

void fail_if_empty(const tranche::Error& e) {
  if (e.message.empty()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view in(reinterpret_cast<const char*>(data), size);
  std::vector<std::string> args = {"model.stl", "-o", "out.gcode"};
  for (int n = 0; n < 8 && !in.empty(); ++n) {
    const size_t nl = in.find('\n');
    args.push_back("--set");
    args.emplace_back(in.substr(0, nl));
    in.remove_prefix(nl == std::string_view::npos ? in.size() : nl + 1);
  }
  auto parsed = tranche::app::parse_slice_args(args, true);
  if (!parsed) return fail_if_empty(parsed.error()), 0;
  std::vector<std::pair<std::string, std::string>> plain;
  tranche::compiler::RulesInput rules;
  rules.profile = false;
  for (const auto& [k, v] : parsed->slice.sets)
    (tranche::ctx::is_plain_override(k, v) ? plain : rules.expressions).emplace_back(k, v);
  tranche::Report report;
  auto rs = tranche::compiler::load_rules(rules, report);
  if (!rs) return fail_if_empty(rs.error()), 0;
  const tranche::vm::RuleSet* r = rs->get();
  auto cascade = tranche::ctx::Cascade::create(plain, r, r, r);
  if (!cascade) return fail_if_empty(cascade.error()), 0;
  auto props = (*cascade)->print_props(tranche::ctx::Context{});
  if (!props) fail_if_empty(props.error());
  return 0;
}
