// Completion from the text before the cursor: what may be written there.
#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <set>

#include "lsp/features.h"
#include "lsp/schema_text.h"

namespace tranche::lsp {

namespace fs = std::filesystem;

namespace {

// LSP CompletionItemKind values.
enum Kind { kFunction = 3, kField = 5, kVariable = 6, kModule = 9, kProperty = 10, kUnit = 11, kEnumMember = 20,
            kKeyword = 14, kFile = 17, kConstant = 21, kEvent = 23 };

constexpr const char* kLevels[] = {"print", "layer", "island", "cell", "path", "piece"};
constexpr const char* kKeywords[] = {"rule", "when", "on", "use", "param", "append", "before", "after", "replace",
                                     "gcode", "comment", "let", "if", "then", "else", "for", "in", "move", "to",
                                     "travel", "extrude", "with", "default", "offset", "reverse", "retract",
                                     "and", "or", "not", "mod", "true", "false"};
constexpr const char* kUnits[] = {"mm", "mm2", "mm3", "mm/s", "mm/s2", "mm3/s", "deg", "°", "s", "°C", "%"};

struct Items {
  json list = json::array();
  json range;  // the edit range: the word being typed
  void add(std::string label, int kind, std::string detail = {}, std::string doc = {}, std::string sort = {}) {
    json item = {{"label", label}, {"kind", kind}, {"textEdit", {{"range", range}, {"newText", label}}}};
    if (!detail.empty()) item["detail"] = detail;
    if (!doc.empty()) item["documentation"] = {{"kind", "markdown"}, {"value", doc}};
    if (!sort.empty()) item["sortText"] = sort + label;
    list.push_back(std::move(item));
  }
};

// The enum a field or property name has, if any.
schema::EnumType enum_of(const std::string& name) {
  if (auto f = schema::find_field(name)) return schema::field(*f).enum_type;
  if (auto p = schema::find_property(name)) return schema::property(*p).enum_type;
  return schema::EnumType::None;
}

void add_fields(Items& items, const std::string& level, bool other_layer) {
  static const std::set<std::string> readable = {"index", "z_bottom", "z", "height", "area", "islands"};
  for (const auto& f : schema::fields()) {
    std::string name(f.name);
    if (!name.starts_with(level + ".")) continue;
    std::string member = name.substr(level.size() + 1);
    if (other_layer && !readable.count(member)) continue;
    items.add(member, kField, type_text(f.type, f.unit, f.enum_type), std::string(f.doc));
  }
}

void add_use_paths(Items& items, const std::string& typed, const Document& doc,
                   const compiler::FrontendOptions& options) {
  std::vector<std::pair<fs::path, std::string>> roots;  // directory, prefix shown
  if (typed.starts_with("./") || typed.starts_with("../")) {
    fs::path base = fs::path(doc.path).parent_path();
    std::string dir = typed.substr(0, typed.rfind('/') + 1);
    roots.emplace_back(base / dir, dir);
  } else if (fs::path stdlib = compiler::stdlib_dir(options); !stdlib.empty()) {
    roots.emplace_back(stdlib, "");
  }
  std::error_code ec;
  for (const auto& [dir, prefix] : roots) {
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
      if (it.depth() > 3 || !it->is_regular_file(ec) || it->path().extension() != ".rules") continue;
      fs::path rel = it->path().lexically_relative(dir);
      rel.replace_extension();
      if (fs::equivalent(it->path(), doc.path, ec)) continue;
      items.add(prefix + rel.generic_string(), kFile, it->path().string());
    }
  }
}

// The collection a `for NAME in ...` before the cursor loops over ("" if NAME is not one).
std::string loop_collection(const std::string& text, const std::string& name) {
  std::regex loop_re("for\\s+" + name + "\\s+in\\s+(path\\.points|path\\.pieces|layer\\.islands)");
  std::string found;
  for (std::sregex_iterator it(text.begin(), text.end(), loop_re), end; it != end; ++it) found = (*it)[1];
  return found;
}

// The unit of the field or property compared just before the number being typed, if any.
std::string compared_unit(const std::string& before) {
  static const std::regex cmp_re(R"(([\w.]+)\s*(?:[<>]=?|==|!=|\bin)\s*-?[\d.]+\s*[a-zA-Z°%/23]*$)");
  std::smatch m;
  if (!std::regex_search(before, m, cmp_re)) return {};
  if (auto f = schema::find_field(m[1].str())) {
    const auto& info = schema::field(*f);
    return info.unit == schema::Unit::Ratio ? "%" : std::string(schema::unit_name(info.unit));
  }
  if (auto p = schema::find_property(m[1].str())) {
    const auto& info = schema::property(*p);
    return info.unit == schema::Unit::Ratio ? "%" : std::string(schema::unit_name(info.unit));
  }
  return {};
}

// Units, the one of the property being set (or of the field compared) first.
void add_units(Items& items, const std::string& before) {
  std::string want;
  std::smatch a;
  // The property of the statement being typed: at the start of the line, or after the `{` or
  // `;` of a one-line rule (`rule "u" { speed = 20 `).
  static const std::regex target_re(R"((?:^|[{;])\s*(\w+)\s*=[^=;{}]*$)");
  if (std::regex_search(before, a, target_re)) {
    if (auto prop = schema::find_property(a[1].str())) {
      const auto& info = schema::property(*prop);
      want = info.unit == schema::Unit::Ratio ? "%" : std::string(schema::unit_name(info.unit));
    }
  }
  if (want.empty()) want = compared_unit(before);
  for (const char* u : kUnits) items.add(u, kUnit, "unit", {}, want == u ? "0" : "1");
}

void add_names(Items& items, const Document& doc) {
  for (const auto& p : schema::properties())
    items.add(std::string(p.name), kProperty, type_text(p.type, p.unit, p.enum_type), property_text(p));
  // Params: the program's (with their values), and those the text defines (while it does not parse).
  std::set<std::string> seen;
  if (doc.analysis.program)
    for (const ast::Param* p : doc.analysis.program->params)
      if (seen.insert(p->name).second)
        items.add(p->name, kConstant, "param", p->constant ? "= `" + value_text(*p->constant, p->type) + "`" : "");
  static const std::regex param_re(R"((?:^|\n)[ \t]*param[ \t]+(\w+))");
  for (std::sregex_iterator it(doc.text.begin(), doc.text.end(), param_re), end; it != end; ++it)
    if (seen.insert((*it)[1]).second) items.add((*it)[1], kConstant, "param");
  for (const auto& f : functions()) items.add(std::string(f.name), kFunction, std::string(f.signature), std::string(f.doc));
  for (const char* l : kLevels) items.add(l, kModule, "level");
  for (const char* l : {"below", "above", "layers"}) items.add(l, kModule, "another layer");
  for (const char* k : kKeywords) items.add(k, kKeyword);
}

}  // namespace

json completion(const Document& doc, const json& position, const compiler::FrontendOptions& options) {
  uint32_t at = doc.offset(position);
  Position p = doc.index->position(at);
  uint32_t line_start = doc.index->offset(Position{p.line, 0});
  std::string before = doc.text.substr(line_start, at - line_start);
  std::smatch m;
  Items items;
  // The word being typed (letters, digits, `_`, and unit symbols) is what an item replaces.
  auto word_from = [&](size_t length) {
    Position s = doc.index->position(at - static_cast<uint32_t>(length));
    items.range = {{"start", {{"line", s.line}, {"character", s.character}}},
                   {"end", {{"line", p.line}, {"character", p.character}}}};
  };
  static const std::regex use_re(R"re(^\s*use\s+"([^"]*)$)re");
  static const std::regex event_re(R"(^\s*on\s+(\w+)\.(\w*)$)");
  static const std::regex member_re(R"((?:^|[^\w.\]])(\w+)\.(\w*)$)");
  static const std::regex other_re(R"(layers\s*\[[^\]]*\]\.(\w*)$)");
  static const std::regex compare_re(R"(([\w.]+)\s*(?:==|!=)\s*(\w*)$)");
  static const std::regex in_set_re(R"(([\w.]+)\s+in\s*\(([^)]*?)(\w*)$)");
  static const std::regex assign_re(R"((\w+)\s*=\s*(\w*)$)");
  static const std::regex number_re(R"((?:^|[^\w.])\.?\d[\d.]*(?:[eE][-+]?\d+)?\s*([a-zA-Z°%/23]*)$)");
  static const std::regex hook_re(R"((?:^|[^\w])(before|after|replace)\s+(\w*)$)");
  static const std::regex on_re(R"(^\s*on\s+(\w*)$)");
  if (std::regex_search(before, m, use_re)) {
    word_from(m[1].length());
    add_use_paths(items, m[1], doc, options);
  } else if (std::regex_search(before, m, event_re)) {
    word_from(m[2].length());
    items.add("start", kEvent, "before the " + std::string(m[1]));
    items.add("end", kEvent, "after the " + std::string(m[1]));
  } else if (std::regex_search(before, m, other_re)) {
    word_from(m[1].length());
    add_fields(items, "layer", true);
  } else if (std::regex_search(before, m, member_re) &&
             (std::find(std::begin(kLevels), std::end(kLevels), m[1].str()) != std::end(kLevels) ||
              m[1] == "below" || m[1] == "above")) {
    word_from(m[2].length());
    bool other = m[1] == "below" || m[1] == "above";
    add_fields(items, other ? "layer" : m[1].str(), other);
  } else if (std::regex_search(before, m, member_re) && !loop_collection(doc.text.substr(0, at), m[1]).empty()) {
    // `p.` of `for p in path.points`: the fields of a point, a piece or an island.
    word_from(m[2].length());
    std::string coll = loop_collection(doc.text.substr(0, at), m[1]);
    if (coll == "path.points")
      for (const char* f : {"x", "y", "index"}) items.add(f, kField, "of a point");
    else
      add_fields(items, coll == "path.pieces" ? "piece" : "island", false);
  } else if ((std::regex_search(before, m, compare_re) || std::regex_search(before, m, assign_re)) &&
             enum_of(m[1]) != schema::EnumType::None) {
    word_from(m[2].length());
    const auto& info = schema::enum_info(enum_of(m[1]));
    for (auto v : info.values) items.add(std::string(v), kEnumMember, std::string(info.name));
  } else if (std::regex_search(before, m, in_set_re) && enum_of(m[1]) != schema::EnumType::None) {
    word_from(m[3].length());
    const auto& info = schema::enum_info(enum_of(m[1]));
    for (auto v : info.values) items.add(std::string(v), kEnumMember, std::string(info.name));
  } else if (std::regex_search(before, m, number_re)) {
    word_from(m[1].length());
    add_units(items, before);
  } else if (std::regex_search(before, m, hook_re)) {
    word_from(m[2].length());
    bool replace = m[1] == "replace";
    for (const char* l : {"print", "layer", "island", "cell", "path"})
      if (!replace || std::string_view(l) == "path" || std::string_view(l) == "island")
        items.add(l, kModule, replace ? "replace this level's G-code" : "hook on this level");
  } else if (std::regex_search(before, m, on_re)) {
    word_from(m[1].length());
    for (const char* l : {"print", "layer", "island", "cell", "path"})
      for (const char* e : {"start", "end"}) items.add(fmt::format("{}.{}", l, e), kEvent);
  } else {
    static const std::regex word_re(R"((\w*)$)");
    std::regex_search(before, m, word_re);
    word_from(m[1].length());
    add_names(items, doc);
  }
  return {{"isIncomplete", false}, {"items", items.list}};
}

}  // namespace tranche::lsp
