#include "geometry/io/svg_stack.h"

#include <cmath>
#include <string_view>

#include "geometry/io/svg_path.h"

namespace tranche::geo::svg {

namespace {

// The prefix bound to the tranche namespace on the root ("tranche" when written by us), or "".
std::string stack_prefix(pugi::xml_node root) {
  for (pugi::xml_attribute a : root.attributes()) {
    std::string_view name = a.name();
    if (name.rfind("xmlns:", 0) == 0 && std::string_view(a.value()) == kStackNamespace)
      return std::string(name.substr(6));
  }
  return "";
}

}  // namespace

bool has_class(pugi::xml_node n, std::string_view cls) {
  std::string_view list = n.attribute("class").value();
  size_t p = 0;
  while (p < list.size()) {
    while (p < list.size() && std::isspace(static_cast<unsigned char>(list[p]))) ++p;
    size_t e = p;
    while (e < list.size() && !std::isspace(static_cast<unsigned char>(list[e]))) ++e;
    if (list.substr(p, e - p) == cls) return true;
    p = e;
  }
  return false;
}

Result<Stack> read_stack(pugi::xml_node root, const SourceMap& src, Report& report) {
  Stack stack;
  std::string prefix = stack_prefix(root);
  if (prefix.empty()) return stack;  // a flat drawing
  auto attr = [&](pugi::xml_node n, const char* local) {
    return n.attribute((prefix + ":" + local).c_str());
  };
  pugi::xml_attribute format = attr(root, "format");
  if (!format) return stack;  // the namespace alone (e.g. an editor kept it) does not make a stack
  if (std::string_view(format.value()) != kStackFormat)
    return Error{src.at(root), "unknown tranche format \"" + std::string(format.value()) +
                                   "\" (this reader knows \"" + kStackFormat + "\")"};
  auto version = parse_number(attr(root, "version").value());
  if (!version || *version != std::floor(*version) || *version < 1)
    return Error{src.at(root), "the layer stack has no valid " + prefix + ":version"};
  if (*version > kStackVersion)
    return Error{src.at(root), "layer stack version " + std::string(attr(root, "version").value()) +
                                   " is newer than this reader (version " + std::to_string(kStackVersion) +
                                   "): update tranche"};
  if (pugi::xml_attribute units = attr(root, "units"); units && std::string_view(units.value()) != "mm")
    return Error{src.at(root), "layer stack units \"" + std::string(units.value()) + "\" are not mm"};
  stack.is_stack = true;

  // Layer groups: <g> elements with a z range, at any depth (an editor may wrap them), not nested.
  std::vector<pugi::xml_node> todo;
  for (pugi::xml_node c = root.last_child(); c; c = c.previous_sibling()) todo.push_back(c);
  while (!todo.empty()) {
    pugi::xml_node n = todo.back();
    todo.pop_back();
    if (n.type() != pugi::node_element) continue;
    std::string_view name = n.name();
    bool group = name == "g" || name == "svg:g";
    if (group && (attr(n, "z-top") || attr(n, "z-bottom"))) {
      auto zb = parse_number(attr(n, "z-bottom").value());
      auto zt = parse_number(attr(n, "z-top").value());
      if (!zb || !zt)
        return Error{src.at(n),
                     "layer group without a readable " + prefix + ":z-bottom and " + prefix + ":z-top (mm)"};
      if (!(*zb >= 0 && *zt > *zb && *zt < 1e5))
        return Error{src.at(n), "layer group with z from " + std::string(attr(n, "z-bottom").value()) +
                                    " to " + attr(n, "z-top").value() +
                                    " mm: it must run upwards from z >= 0"};
      if (!stack.layers.empty()) {
        const StackLayer& prev = stack.layers.back();
        if (*zb < prev.z_top - 1e-9)
          return Error{src.at(n), "layer groups overlap or are out of order: this one starts at z " +
                                      std::string(attr(n, "z-bottom").value()) +
                                      " mm, below the top of the one before"};
        if (*zb > prev.z_top + 1e-9)
          report.warn("svg-stack-gap", src.at(n),
                      "no layer between z " + std::to_string(prev.z_top) + " and " + std::to_string(*zb) +
                          " mm: that part of the print is empty");
      }
      stack.layers.push_back({n, *zb, *zt});
      continue;
    }
    if (group)
      for (pugi::xml_node c = n.last_child(); c; c = c.previous_sibling()) todo.push_back(c);
  }
  if (stack.layers.empty()) return Error{src.at(root), "the layer stack has no layer groups"};
  if (auto declared = parse_number(attr(root, "layers").value());
      declared && *declared != static_cast<double>(stack.layers.size()))
    report.warn("svg-stack-count", src.at(root),
                "the stack declares " + std::string(attr(root, "layers").value()) + " layers but holds " +
                    std::to_string(stack.layers.size()) + " layer groups");
  return stack;
}

}  // namespace tranche::geo::svg
