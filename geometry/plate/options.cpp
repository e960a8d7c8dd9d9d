#include "geometry/plate/options.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>

namespace tranche::plate {
namespace {

// "SEL=REST" -> (SEL, REST); no '=' -> ("", value).
std::pair<std::string, std::string> split_selector(const std::string& value) {
  const size_t eq = value.rfind('=');
  if (eq == std::string::npos) return {"", value};
  return {value.substr(0, eq), value.substr(eq + 1)};
}

// Comma-separated finite numbers.
bool numbers(const std::string& text, std::vector<double>& out) {
  out.clear();
  size_t at = 0;
  while (true) {
    const size_t comma = text.find(',', at);
    const std::string part = text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    double v = 0;
    const char* b = part.data();
    const char* e = part.data() + part.size();
    while (b < e && *b == ' ') ++b;
    if (b < e && *b == '+') ++b;
    const auto [end, ec] = std::from_chars(b, e, v);
    if (ec != std::errc() || end != e || !std::isfinite(v)) return false;
    out.push_back(v);
    if (comma == std::string::npos) return true;
    at = comma + 1;
  }
}

Error usage(const std::string& message) { return Error{"", message}; }

}  // namespace

Result<PerObject<Eigen::Vector3d>> parse_scale(const std::string& value) {
  auto [sel, rest] = split_selector(value);
  std::vector<double> v;
  const bool percent = !rest.empty() && rest.back() == '%';
  if (percent) rest.pop_back();
  if (!numbers(rest, v) || (v.size() != 1 && v.size() != 3))
    return usage(fmt::format("--scale needs a factor (2, 50%) or x,y,z factors (1,1,2), optionally for one object "
                             "(lid=2), not '{}'",
                             value));
  for (double& f : v) {
    if (percent) f /= 100;
    if (!(f > 0) || f > 1e4) return usage(fmt::format("--scale factors must be positive, not '{}'", value));
  }
  const Eigen::Vector3d f = v.size() == 1 ? Eigen::Vector3d::Constant(v[0]) : Eigen::Vector3d(v[0], v[1], v[2]);
  return PerObject<Eigen::Vector3d>{sel, f};
}

Result<PerObject<double>> parse_angle(const std::string& option, const std::string& value) {
  auto [sel, rest] = split_selector(value);
  std::vector<double> v;
  if (!numbers(rest, v) || v.size() != 1)
    return usage(fmt::format("{} needs an angle in degrees (90, -45.5), optionally for one object (lid=90), not '{}'",
                             option, value));
  return PerObject<double>{sel, v[0]};
}

Result<PerObject<Vec2>> parse_xy(const std::string& option, const std::string& value) {
  auto [sel, rest] = split_selector(value);
  std::vector<double> v;
  if (!numbers(rest, v) || v.size() != 2)
    return usage(fmt::format("{} needs X,Y in mm (100,80), optionally for one object (lid=100,80), not '{}'", option,
                             value));
  return PerObject<Vec2>{sel, Vec2(v[0], v[1])};
}

Result<PerObject<int>> parse_copies(const std::string& value) {
  auto [sel, rest] = split_selector(value);
  std::vector<double> v;
  if (!numbers(rest, v) || v.size() != 1 || v[0] != std::floor(v[0]) || v[0] < 1 || v[0] > 1000)
    return usage(fmt::format("--copies needs a whole number from 1 to 1000, optionally for one object (lid=3), not "
                             "'{}'",
                             value));
  return PerObject<int>{sel, static_cast<int>(v[0])};
}

Result<double> parse_spacing(const std::string& value) {
  std::vector<double> v;
  if (!numbers(value, v) || v.size() != 1 || v[0] < 0 || v[0] > 1000)
    return usage(fmt::format("--spacing needs a distance in mm (0 or more), not '{}'", value));
  return v[0];
}

}  // namespace tranche::plate
