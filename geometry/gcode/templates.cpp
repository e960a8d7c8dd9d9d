#include "geometry/gcode/templates.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "runtime/context/overrides.h"

#ifndef TRANCHE_STDLIB_DIR
#define TRANCHE_STDLIB_DIR ""
#endif

namespace tranche::gcode {

namespace fs = std::filesystem;

std::string stdlib_dir() {
  auto ok = [](const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p / "gcode", ec);
  };
  if (const char* env = std::getenv("TRANCHE_STDLIB"); env && *env) return env;
  if (ok(TRANCHE_STDLIB_DIR)) return TRANCHE_STDLIB_DIR;
  std::error_code ec;
  fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const char* rel : {"../stdlib", "../share/tranche/stdlib", "../../stdlib"}) {
      fs::path p = exe.parent_path() / rel;
      if (ok(p)) return p.lexically_normal().string();
    }
  }
  return TRANCHE_STDLIB_DIR;
}

Result<std::string> load_template(const std::string& stdlib, schema::Flavor flavor, std::string_view part,
                                  std::string* file_used) {
  auto name = schema::enum_value_name(schema::EnumType::Flavor, static_cast<int>(flavor));
  fs::path file = fs::path(stdlib) / "gcode" / std::string(name) / (std::string(part) + ".gcode");
  if (file_used) *file_used = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in)
    return Error{file.string(),
                 "cannot read this G-code template; set TRANCHE_STDLIB to the folder holding gcode/"};
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

namespace {
std::string format_value(double v, schema::Type type, schema::EnumType et) {
  if (type == schema::Type::Enum) return std::string(schema::enum_value_name(et, static_cast<int>(v)));
  if (type == schema::Type::Bool) return v != 0 ? "true" : "false";
  return fmt::format("{}", v);
}
}  // namespace

Result<std::string> render_template(std::string_view text, const std::string& file, const ctx::Context& c,
                                    const ctx::PropertyValues& props) {
  std::string out;
  out.reserve(text.size() + 64);
  int line = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    char ch = text[i];
    if (ch == '\n') ++line;
    if (ch == '{' && i + 1 < text.size() && text[i + 1] == '{') {
      out.push_back('{');
      ++i;
      continue;
    }
    if (ch == '}' && i + 1 < text.size() && text[i + 1] == '}') {
      out.push_back('}');
      ++i;
      continue;
    }
    if (ch != '{') {
      out.push_back(ch);
      continue;
    }
    size_t end = text.find('}', i);
    size_t nl = text.find('\n', i);
    if (end == std::string_view::npos || (nl != std::string_view::npos && nl < end))
      return Error{fmt::format("{}:{}", file, line),
                   "'{' without a closing '}' (write {{ for a literal brace)"};
    std::string name(text.substr(i + 1, end - i - 1));
    if (auto p = schema::find_property(name)) {
      const auto& info = schema::property(*p);
      out += format_value(props[*p], info.type, info.enum_type);
    } else if (auto f = schema::find_field(name)) {
      const auto& info = schema::field(*f);
      out += format_value(c.get(*f), info.type, info.enum_type);
    } else {
      std::string msg = fmt::format("unknown name {{{}}} in the template", name);
      auto close = ctx::close_property_names(name, 2);
      if (!close.empty()) msg += fmt::format("; did you mean {{{}}}?", close[0]);
      return Error{fmt::format("{}:{}", file, line), msg};
    }
    i = end;
  }
  if (!out.empty() && out.back() != '\n') out.push_back('\n');
  return out;
}

}  // namespace tranche::gcode
