#include "geometry/preview/svg_legend.h"

#include <fmt/format.h>

#include <algorithm>

#include "geometry/preview/colours.h"

namespace tranche::preview {

namespace {

std::string xml_escaped(std::string_view s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '&':
        out += "&amp;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out.push_back(c);
    }
  }
  return out;
}

// Characters, not bytes: UTF-8 continuation bytes do not widen the text.
size_t text_length(std::string_view s) {
  return static_cast<size_t>(std::count_if(
      s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xc0) != 0x80; }));
}

}  // namespace

SvgLegend svg_legend(std::span<const LegendEntry> entries, const LegendLayout& L) {
  const double f = L.font, pad = 0.6 * f, row = 1.5 * f, sw = 1.2 * f;  // swatch size
  size_t longest = text_length(L.title);
  for (const LegendEntry& e : entries) longest = std::max(longest, text_length(e.label) + 3);  // + the swatch
  SvgLegend out;
  out.width = 2 * pad + 0.6 * f * static_cast<double>(longest);  // ~0.6 em per character in sans-serif
  out.height = 2 * pad + row * static_cast<double>(entries.size() + 1);
  std::string& s = out.svg;
  s = fmt::format(
      "<g class=\"legend\" transform=\"translate({:.3f} {:.3f})\" font-family=\"sans-serif\" "
      "font-size=\"{:.3f}\">\n",
      L.x, L.y, f);
  s += fmt::format(
      "<rect class=\"legend-frame\" width=\"{:.3f}\" height=\"{:.3f}\" rx=\"{:.3f}\" fill=\"#ffffff\" "
      "fill-opacity=\"0.92\" "
      "stroke=\"#c9ced6\"/>\n",
      out.width, out.height, 0.3 * f);
  s += fmt::format(
      "<text class=\"legend-title\" x=\"{:.3f}\" y=\"{:.3f}\" font-weight=\"bold\" "
      "fill=\"#1f2933\">{}</text>\n",
      pad, pad + 0.9 * f, xml_escaped(L.title));
  for (size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const double top = pad + row * static_cast<double>(i + 1), mid = top + 0.5 * row - 0.1 * f;
    const std::string cls = xml_escaped(e.css_class), col = xml_escaped(e.colour);
    s += fmt::format("<g class=\"legend-entry\">");
    if (e.swatch == Swatch::Fill) {
      s += fmt::format("<rect class=\"{}\" x=\"{:.3f}\" y=\"{:.3f}\" width=\"{:.3f}\" height=\"{:.3f}\"{}/>",
                       cls, pad, mid - sw / 2, sw, sw, col.empty() ? "" : " style=\"fill:" + col + "\"");
    } else {
      // Thicker than the drawing's hairlines, so the colour reads at legend size.
      s += fmt::format(
          "<line class=\"{}\" x1=\"{:.3f}\" y1=\"{:.3f}\" x2=\"{:.3f}\" y2=\"{:.3f}\" "
          "stroke-width=\"{:.3f}\"{}{}/>",
          cls, pad, mid, pad + sw, mid, 0.25 * f,
          col.empty() ? ""
                      : " style=\"stroke:" + col + ";stroke-width:" + fmt::format("{:.3f}", 0.25 * f) + "\"",
          e.swatch == Swatch::Dash ? " stroke-dasharray=\"4 3\"" : "");
    }
    s += fmt::format("<text x=\"{:.3f}\" y=\"{:.3f}\" fill=\"#1f2933\">{}</text></g>\n", pad + sw + 0.5 * f,
                     mid + 0.35 * f, xml_escaped(e.label));
  }
  s += "</g>\n";
  return out;
}

std::vector<LegendEntry> kind_legend_entries() {
  std::vector<LegendEntry> out;
  for (int k = 0; k < kPathKindCount; ++k) {
    const auto kind = static_cast<schema::PathKind>(k);
    out.push_back({fmt::format("kind-{}", schema::enum_value_name(schema::EnumType::PathKind, k)),
                   to_hex(kind_colour(kind)), std::string(kind_label(kind)), Swatch::Line});
  }
  return out;
}

}  // namespace tranche::preview
