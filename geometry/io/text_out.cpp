#include "geometry/io/text_out.h"

namespace tranche::geo {

void append_mm(fmt::memory_buffer& out, coord_t units) {
  // Integer arithmetic: a decimal printed this way reads back to the same nanometre.
  uint64_t u = units < 0 ? 0 - static_cast<uint64_t>(units) : static_cast<uint64_t>(units);
  if (units < 0) out.push_back('-');
  fmt::format_to(std::back_inserter(out), "{}", u / 1000000);
  uint32_t frac = static_cast<uint32_t>(u % 1000000);
  if (frac == 0) return;
  char digits[7];
  int n = 6;
  for (int i = 5; i >= 0; --i) {
    digits[i] = static_cast<char>('0' + frac % 10);
    frac /= 10;
  }
  while (digits[n - 1] == '0') --n;
  out.push_back('.');
  out.append(digits, digits + n);
}

void append_json_string(fmt::memory_buffer& out, std::string_view s) {
  out.push_back('"');
  for (unsigned char c : s) {
    if (c == '"' || c == '\\') {
      out.push_back('\\');
      out.push_back(static_cast<char>(c));
    } else if (c < 0x20) {
      fmt::format_to(std::back_inserter(out), "\\u{:04x}", c);
    } else {
      out.push_back(static_cast<char>(c));
    }
  }
  out.push_back('"');
}

void append_xml_escaped(fmt::memory_buffer& out, std::string_view s) {
  for (char c : s) {
    switch (c) {
      case '&':
        out.append(std::string_view("&amp;"));
        break;
      case '<':
        out.append(std::string_view("&lt;"));
        break;
      case '>':
        out.append(std::string_view("&gt;"));
        break;
      case '"':
        out.append(std::string_view("&quot;"));
        break;
      case '\'':
        out.append(std::string_view("&apos;"));
        break;
      default:
        // Control characters are not allowed in XML 1.0.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n' && c != '\r')
          out.push_back('?');
        else
          out.push_back(c);
    }
  }
}

}  // namespace tranche::geo
