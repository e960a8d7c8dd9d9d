// ASCII STL: `solid NAME`, then facets (`facet normal x y z`, `outer loop`, three `vertex x y z`,
// `endloop`, `endfacet`), then `endsolid NAME`; several solids in one file are merged. Keywords
// are case-insensitive; any whitespace (tabs, CR, LF) separates tokens.
#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <optional>

#include "geometry/mesh/stl_parse.h"
#include "geometry/mesh/weld.h"

namespace tranche::geo::stl {
namespace {

constexpr std::string_view kDamaged = "; the file is damaged here — repair or re-export the model";

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

bool is_keyword(std::string_view tok, std::string_view kw) {
  if (tok.size() != kw.size()) return false;
  for (size_t i = 0; i < kw.size(); ++i) {
    if ((tok[i] | 0x20) != kw[i]) return false;
  }
  return true;
}

// A token as it appears in a message: quoted, at most 24 characters, non-printables escaped.
std::string shown(std::string_view tok) {
  std::string s = "'";
  for (size_t i = 0; i < tok.size() && i < 24; ++i) {
    const auto c = static_cast<unsigned char>(tok[i]);
    if (c < 0x20 || c > 0x7e) {
      s += fmt::format("\\x{:02x}", c);
    } else {
      s += static_cast<char>(c);
    }
  }
  if (tok.size() > 24) s += "...";
  return s + "'";
}

struct Token {
  std::string_view text;  // empty at end of input
  uint64_t line = 0;
  bool end() const { return text.empty(); }
};

class Lexer {
 public:
  explicit Lexer(std::string_view s) : p_(s.data()), end_(s.data() + s.size()) {}

  Token next() {
    while (p_ < end_ && is_space(*p_)) {
      // LF, CRLF and lone CR (old Mac files) each end one line.
      if (*p_ == '\n' || (*p_ == '\r' && (p_ + 1 == end_ || p_[1] != '\n'))) ++line_;
      ++p_;
    }
    if (p_ == end_) return Token{{}, last_line_};  // at the end, point at the last token's line
    const char* b = p_;
    while (p_ < end_ && !is_space(*p_)) ++p_;
    last_line_ = line_;
    return Token{std::string_view(b, static_cast<size_t>(p_ - b)), line_};
  }
  Token peek() const {
    Lexer copy = *this;
    return copy.next();
  }
  uint64_t line() const { return line_; }

 private:
  const char* p_;
  const char* end_;
  uint64_t line_ = 1;
  uint64_t last_line_ = 1;
};

enum class Num { kOk, kBad, kRange };

Num parse_float(std::string_view tok, float& out) {
  if (tok.size() > 1 && tok[0] == '+') tok.remove_prefix(1);  // from_chars rejects '+'
  const char* e = tok.data() + tok.size();
  auto [ptr, ec] = std::from_chars(tok.data(), e, out);
  if (ptr != e || ec == std::errc::invalid_argument) return Num::kBad;
  if (ec == std::errc::result_out_of_range) {
    double d = 0;
    auto [ptr2, ec2] = std::from_chars(tok.data(), e, d);
    if (ptr2 != e || ec2 != std::errc() || std::fabs(d) >= 1) return Num::kRange;
    out = static_cast<float>(d);  // underflow: rounds to zero or a subnormal
  }
  return Num::kOk;
}

class Parser {
 public:
  Parser(std::string_view bytes, const std::string& file, Report& report)
      : lex_(bytes), file_(file), report_(report) {
    raw_.facets.reserve(bytes.size() / 256);  // a typical exporter writes ~250 bytes per facet
    raw_.lines.reserve(bytes.size() / 256);
  }

  Result<RawStl> run() {
    Token t = lex_.next();  // the caller checked that the file starts with `solid`
    const uint64_t solid_line = t.line;
    raw_.name = rest_of_line(t.line);
    std::string solid_name = raw_.name;
    for (;;) {
      t = lex_.next();
      if (t.end()) {
        return fail(t.line, fmt::format("the file ends without 'endsolid' (solid at line {}, {} facets "
                                        "read); it is probably truncated — re-export the model",
                                        solid_line, raw_.facets.size()));
      }
      if (is_keyword(t.text, "facet")) {
        if (auto err = facet(t.line)) return std::move(*err);
        continue;
      }
      if (!is_keyword(t.text, "endsolid")) {
        return fail(t.line,
                    fmt::format("expected 'facet' or 'endsolid', found {}{}", shown(t.text), kDamaged));
      }
      const std::string end_name = rest_of_line(t.line);
      if (!end_name.empty() && end_name != solid_name) {
        report_.warn("stl-name", at_line(file_, t.line),
                     fmt::format("'endsolid {}' does not match 'solid {}' (line {}); the name is ignored",
                                 end_name, solid_name, solid_line));
      }
      t = lex_.next();
      if (t.end()) break;
      if (!is_keyword(t.text, "solid")) {
        report_.warn("stl-trailing", at_line(file_, t.line),
                     fmt::format("text after 'endsolid' is ignored (starts with {})", shown(t.text)));
        break;
      }
      solid_name = rest_of_line(t.line);
    }
    if (raw_.facets.empty()) {
      return Error{file_,
                   fmt::format("the file has no facets ({}); export the model again with its "
                               "geometry selected",
                               raw_.name.empty() ? "an empty solid" : "solid '" + raw_.name + "' is empty")};
    }
    summarise_normals();
    return std::move(raw_);
  }

 private:
  Error fail(uint64_t line, std::string message) const {
    return Error{at_line(file_, line), std::move(message)};
  }

  // The solid's name: the following words on the same line, up to a keyword that starts the body
  // (minified files put everything on one line).
  std::string rest_of_line(uint64_t line) {
    std::string name;
    for (Token t = lex_.peek(); !t.end() && t.line == line; t = lex_.peek()) {
      if (is_keyword(t.text, "facet") || is_keyword(t.text, "endsolid") || is_keyword(t.text, "solid")) break;
      if (!name.empty()) name += ' ';
      name.append(t.text);
      lex_.next();
    }
    return name;
  }

  std::optional<Error> expect(std::string_view kw, std::string_view after) {
    const Token t = lex_.next();
    if (is_keyword(t.text, kw)) return std::nullopt;
    if (t.end()) {
      return fail(t.line, fmt::format("the file ends where '{}' should follow {}; it is probably truncated — "
                                      "re-export the model",
                                      kw, after));
    }
    return fail(t.line,
                fmt::format("expected '{}' after {}, found {}{}", kw, after, shown(t.text), kDamaged));
  }

  // Reads three numbers into out; `what` names them in messages ("vertex", "normal").
  std::optional<Error> numbers(float* out, std::string_view what, bool finite) {
    static constexpr const char* kAxis[] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      const Token t = lex_.next();
      if (t.end()) {
        return fail(t.line, fmt::format("the file ends inside a {} (its {} coordinate is missing); it is "
                                        "probably truncated — re-export the model",
                                        what, kAxis[k]));
      }
      switch (parse_float(t.text, out[k])) {
        case Num::kOk:
          break;
        case Num::kBad:
          return fail(t.line, fmt::format("expected a number for the {} {} coordinate, found {}{}", what,
                                          kAxis[k], shown(t.text), kDamaged));
        case Num::kRange:
          return fail(t.line, fmt::format("{} {} coordinate {} is out of range for a 32-bit float (about "
                                          "±3.4e38); check the model's units",
                                          what, kAxis[k], shown(t.text)));
      }
      if (finite && !std::isfinite(out[k])) {
        return fail(t.line, fmt::format("{} {} coordinate {} is not a finite number; the file is corrupt — "
                                        "repair or re-export the model",
                                        what, kAxis[k], shown(t.text)));
      }
    }
    return std::nullopt;
  }

  std::optional<Error> facet(uint64_t line) {
    Facet f{};
    // "facet normal x y z"; some exporters write "facet normal" with no numbers, or just "facet".
    if (is_keyword(lex_.peek().text, "normal")) lex_.next();
    if (is_keyword(lex_.peek().text, "outer")) {
      if (missing_normal_++ == 0) first_missing_normal_ = line;
    } else {
      if (auto err = numbers(f.normal, "normal", false)) return err;
      if (!std::isfinite(f.normal[0]) || !std::isfinite(f.normal[1]) || !std::isfinite(f.normal[2])) {
        if (nan_normal_++ == 0) first_nan_normal_ = line;
        f.normal[0] = f.normal[1] = f.normal[2] = 0;
      }
    }
    if (auto err = expect("outer", "'facet normal'")) return err;
    if (auto err = expect("loop", "'outer'")) return err;
    const uint64_t loop_line = lex_.line();
    int corners = 0;
    for (;;) {
      const Token t = lex_.next();
      if (is_keyword(t.text, "vertex")) {
        float scratch[3];
        if (auto err = numbers(corners < 3 ? f.v + 3 * corners : scratch, "vertex", true)) return err;
        ++corners;
        continue;
      }
      if (is_keyword(t.text, "endloop")) break;
      if (t.end()) {
        return fail(t.line, fmt::format("the file ends inside the facet at line {} ('outer loop' without "
                                        "'endloop'); it is probably truncated — re-export the model",
                                        line));
      }
      if (is_keyword(t.text, "endfacet") || is_keyword(t.text, "facet") || is_keyword(t.text, "endsolid")) {
        return fail(t.line, fmt::format("'outer loop' at line {} has no 'endloop' (found {})", loop_line,
                                        shown(t.text)));
      }
      return fail(t.line, fmt::format("expected 'vertex' or 'endloop', found {}{}", shown(t.text), kDamaged));
    }
    if (corners != 3) {
      return fail(line, fmt::format("facet has {} {}, an STL facet needs exactly 3; export the model with "
                                    "triangulated faces",
                                    corners, corners == 1 ? "vertex" : "vertices"));
    }
    if (auto err = expect("endfacet", "'endloop'")) return err;
    if (raw_.facets.size() >= Welder::kMaxTriangles) {
      return fail(line, fmt::format("more than {} facets; simplify the model", Welder::kMaxTriangles));
    }
    raw_.facets.push_back(f);
    raw_.lines.push_back(static_cast<uint32_t>(std::min<uint64_t>(line, UINT32_MAX)));
    return std::nullopt;
  }

  void summarise_normals() {
    if (missing_normal_ > 0) {
      report_.warn("stl-normal", at_line(file_, first_missing_normal_),
                   fmt::format("{} facet{} without normal values (first here); normals are computed from the "
                               "vertex order",
                               missing_normal_, missing_normal_ == 1 ? "" : "s"));
    }
    if (nan_normal_ > 0) {
      report_.warn("stl-normal", at_line(file_, first_nan_normal_),
                   fmt::format("{} facet{} with a normal that is not a finite number (first here); normals "
                               "are computed from the vertex order",
                               nan_normal_, nan_normal_ == 1 ? "" : "s"));
    }
  }

  Lexer lex_;
  const std::string& file_;
  Report& report_;
  RawStl raw_;
  uint64_t missing_normal_ = 0, first_missing_normal_ = 0;
  uint64_t nan_normal_ = 0, first_nan_normal_ = 0;
};

}  // namespace

Result<RawStl> parse_ascii(std::string_view bytes, const std::string& file, Report& report) {
  if (bytes.starts_with("\xEF\xBB\xBF")) bytes.remove_prefix(3);  // UTF-8 byte order mark
  return Parser(bytes, file, report).run();
}

}  // namespace tranche::geo::stl
