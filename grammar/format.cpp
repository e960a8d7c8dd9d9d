#include "grammar/format.h"

#include <set>

#include "RulesLexer.h"
#include "grammar/input.h"
#include "grammar/parse.h"
#include "grammar/tokens.h"

namespace tranche::grammar {

using L = RulesLexer;

namespace {

constexpr int kIndent = 2;        // per block
constexpr int kContinuation = 4;  // a statement continued on the next line

// What stands between two tokens: line breaks and comments (`;` and spaces do not matter).
struct Event {
  bool comment = false;
  std::string text;  // the comment, trailing spaces removed
};

struct Tok {
  size_t type = 0;
  std::string text;
  bool sep_before = false;  // a statement separator (newline or `;`) stands before it
  std::vector<Event> gap;   // between the previous token and this one
};

// A gap as the printer needs it.
struct Gap {
  struct Comment {
    std::string text;
    bool blank_before = false;
  };
  std::string trailing;           // a comment on the previous token's line
  std::vector<Comment> comments;  // comments on lines of their own
  bool newline = false;
  bool blank_before_next = false;  // a blank line before the next token
  bool has_comments() const { return !trailing.empty() || !comments.empty(); }
};

Gap summarize(const std::vector<Event>& events) {
  Gap g;
  int newlines = 0;
  for (const Event& e : events) {
    if (!e.comment) {
      ++newlines;
      g.newline = true;
      continue;
    }
    if (!g.newline)
      g.trailing = e.text;
    else
      g.comments.push_back({e.text, newlines >= 2});
    newlines = 0;
  }
  g.blank_before_next = newlines >= 2;
  return g;
}

std::vector<Event> scan_gap(const std::string& src, uint32_t from, uint32_t to) {
  std::vector<Event> out;
  for (uint32_t k = from; k < to; ++k) {
    char c = src[k];
    if (c == '#') {
      uint32_t end = k;
      while (end < to && src[end] != '\n' && src[end] != '\r') ++end;
      std::string text = src.substr(k, end - k);
      while (!text.empty() && (text.back() == ' ' || text.back() == '\t')) text.pop_back();
      out.push_back({true, std::move(text)});
      k = end - 1;
    } else if (c == '\n' || c == '\r') {
      if (c == '\r' && k + 1 < to && src[k + 1] == '\n') ++k;
      out.push_back({});
    }
  }
  return out;
}

uint32_t width_of(std::string_view s) { return ast::char_count(s); }

struct Range {
  size_t begin, end;  // tokens [begin, end)
};

class Printer {
 public:
  Printer(const std::vector<Tok>& t, const std::vector<size_t>& match, const std::vector<bool>& flat_source,
          const std::set<size_t>& broken)
      : t_(t), match_(match), flat_source_(flat_source), broken_(broken) {}

  struct Flat {
    int line;
    size_t open;
    int depth;
  };

  std::string out;
  std::vector<Flat> flats;

  // The statements of the block opened at `open` (or of the file, for open == npos).
  std::vector<Range> statements(size_t begin, size_t end) const {
    std::vector<Range> out_ranges;
    size_t i = begin;
    while (i < end) {
      size_t j = i;
      while (j < end) {
        if (j > i && t_[j].sep_before) break;
        j = t_[j].type == L::LBRACE ? match_[j] + 1 : j + 1;
      }
      out_ranges.push_back({i, j});
      i = j;
    }
    return out_ranges;
  }

  void statement(Range r, int indent, int depth) {
    for (size_t i = r.begin; i < r.end; ++i) {
      if (i > r.begin) gap_in_statement(i, indent);
      if (t_[i].type == L::LBRACE) {
        block(i, indent, depth);
        i = match_[i];
      } else {
        put(t_[i].text);
      }
    }
  }

  // Comments and blank lines before a statement (or before `}` / the end of the file, `last`).
  void leading(const Gap& g, int indent, bool first, bool last) {
    if (!g.trailing.empty()) put(" " + g.trailing);
    for (size_t k = 0; k < g.comments.size(); ++k) {
      newline(indent, g.comments[k].blank_before && !(first && k == 0));
      put(g.comments[k].text);
    }
    if (!last) newline(indent, g.blank_before_next && !(first && g.comments.empty()));
  }

  void newline(int indent, bool blank = false) {
    if (at_start_) {
      at_start_ = false;
    } else {
      while (!out.empty() && out.back() == ' ') out.pop_back();
      if (blank) out += '\n';
      out += '\n';
      line_ += blank ? 2 : 1;
    }
    out.append(static_cast<size_t>(indent), ' ');
  }

  void put(std::string_view s) {
    at_start_ = false;
    out += s;
    for (char c : s) line_ += c == '\n';
  }

 private:
  bool space_between(size_t i) const {
    size_t prev = t_[i - 1].type, next = t_[i].type;
    size_t before = i >= 2 ? t_[i - 2].type : static_cast<size_t>(L::NL);
    if (next == L::RPAREN || next == L::RBRACK || next == L::COMMA || next == L::DOT || next == L::DOTDOT ||
        next == L::COLON)
      return false;
    if (prev == L::LPAREN || prev == L::LBRACK || prev == L::DOT || prev == L::DOTDOT) return false;
    if (prev == L::MINUS && !ends_operand(before)) return false;  // a unary minus
    if ((next == L::LPAREN || next == L::LBRACK) && prev == L::IDENT) return false;  // `min(`, `layers[`
    if ((next == L::PERCENT || next == L::DEGREE) && prev == L::NUMBER) return false;
    if (per_time(i) || per_time(i + 1)) return false;  // `1200 mm/min` stays one (wrong) unit
    return true;
  }

  // Whether tokens i - 2 .. i + 1 are `NUMBER mm / min` (or `/ h`): another slicer's unit, which
  // the checker reports as one (E0106); spaced out it would read as a division.
  bool per_time(size_t i) const {
    if (i < 3 || i >= t_.size() || t_[i - 1].type != L::SLASH) return false;
    const Tok& number = t_[i - 3];
    const Tok& unit = t_[i - 2];
    const Tok& time = t_[i];
    if (i + 1 < t_.size() && t_[i + 1].type == L::LPAREN) return false;  // `mm / min(a, b)`
    return number.type == L::NUMBER && unit.type == L::IDENT && time.type == L::IDENT &&
           (unit.text == "mm" || unit.text == "mm3") && (time.text == "min" || time.text == "h");
  }

  void gap_in_statement(size_t i, int indent) {
    Gap g = summarize(t_[i].gap);
    if (!g.trailing.empty()) put(" " + g.trailing);
    for (const auto& c : g.comments) {
      newline(indent + kContinuation);
      put(c.text);
    }
    bool forced = g.has_comments();
    size_t type = t_[i].type;
    if (type == L::LBRACE && !forced) {
      put(" ");  // `{` ends its header's line
    } else if (type == L::ELSE && t_[i - 1].type == L::RBRACE) {
      if (g.newline)
        newline(indent);
      else
        put(" ");
    } else if (g.newline || forced) {
      newline(type == L::LBRACE ? indent : indent + kContinuation);
    } else if (space_between(i)) {
      put(" ");
    }
  }

  void block(size_t open, int indent, int depth) {
    size_t close = match_[open];
    std::vector<Range> stmts = statements(open + 1, close);
    if (flat_source_[open] && !broken_.count(open)) {
      flats.push_back({line_, open, depth});
      put(stmts.empty() ? "{" : "{ ");
      for (size_t k = 0; k < stmts.size(); ++k) {
        if (k) put("; ");
        statement(stmts[k], indent, depth + 1);
      }
      put(" }");
      return;
    }
    put("{");
    int inner = indent + kIndent;
    for (size_t k = 0; k < stmts.size(); ++k) {
      leading(summarize(t_[stmts[k].begin].gap), inner, k == 0, false);
      statement(stmts[k], inner, depth + 1);
    }
    leading(summarize(t_[close].gap), inner, stmts.empty(), true);
    newline(indent);
    put("}");
  }

  const std::vector<Tok>& t_;
  const std::vector<size_t>& match_;
  const std::vector<bool>& flat_source_;
  const std::set<size_t>& broken_;
  bool at_start_ = true;
  int line_ = 0;
};

// The lines of `text` longer than `width`, by index.
std::vector<int> long_lines(const std::string& text, int width) {
  std::vector<int> out;
  int line = 0;
  size_t start = 0;
  for (size_t k = 0; k <= text.size(); ++k) {
    if (k == text.size() || text[k] == '\n') {
      if (width_of(std::string_view(text).substr(start, k - start)) > static_cast<uint32_t>(width))
        out.push_back(line);
      ++line;
      start = k + 1;
    }
  }
  return out;
}

// The tokens the parser sees, without separators, each with what stands before it; the file's
// start behaves like the start of a line. Ends with the end of file.
std::vector<Tok> significant(const Tokens& tokens, const Input& input, const std::string& src, uint32_t begin) {
  std::vector<Tok> t;
  uint32_t prev_end = begin;
  bool sep = false;
  for (const auto& tok : tokens.list) {
    size_t type = tok->getType();
    if (type == L::NL || type == L::SEMI) {
      sep = true;
      continue;
    }
    bool eof = type == antlr4::Token::EOF;
    uint32_t b = eof ? static_cast<uint32_t>(src.size()) : input.byte(tok->getStartIndex());
    uint32_t e = eof ? b : input.byte(tok->getStopIndex() + 1);
    Tok out;
    out.type = type;
    out.text = src.substr(b, e - b);
    out.sep_before = sep || t.empty();
    if (t.empty()) out.gap.push_back({});
    for (auto& ev : scan_gap(src, prev_end, b)) out.gap.push_back(std::move(ev));
    t.push_back(std::move(out));
    prev_end = e;
    sep = false;
    if (eof) break;
  }
  return t;
}

// match[i]: the `}` of the `{` at i; flat[i]: that block is written on one line, without comments.
bool match_blocks(const std::vector<Tok>& t, std::vector<size_t>& match, std::vector<bool>& flat) {
  match.assign(t.size(), 0);
  flat.assign(t.size(), false);
  std::vector<size_t> open;
  for (size_t i = 0; i + 1 < t.size(); ++i) {
    if (t[i].type == L::LBRACE) open.push_back(i);
    if (t[i].type != L::RBRACE || open.empty()) continue;
    size_t o = open.back();
    open.pop_back();
    match[o] = i;
    bool one_line = true;
    for (size_t k = o + 1; k <= i && one_line; ++k)
      one_line = t[k].gap.empty() && t[k].text.find_first_of("\r\n") == std::string::npos;
    flat[o] = one_line;
  }
  return open.empty();
}

}  // namespace

std::optional<std::string> format_file(const ast::SourceMap& sources, uint32_t file_id, diag::Sink& sink,
                                       const FormatOptions& options) {
  size_t errors = sink.errors();
  parse_file(sources, file_id, sink);
  if (sink.errors() != errors) return std::nullopt;

  const std::string& src = sources.file(file_id).text;
  bool bom = src.rfind("\xEF\xBB\xBF", 0) == 0;
  uint32_t begin = bom ? 3 : 0;
  Input input(sources, file_id, begin, static_cast<uint32_t>(src.size()));
  Tokens tokens = lex(input, sink, ParseOptions{}, /*expression_only=*/false);
  if (tokens.fatal || tokens.errors > 0) return std::nullopt;

  std::vector<Tok> t = significant(tokens, input, src, begin);
  if (t.empty() || t.back().type != antlr4::Token::EOF) return std::nullopt;
  size_t n = t.size() - 1;  // without the end of file
  std::vector<size_t> match;
  std::vector<bool> flat;
  if (!match_blocks(t, match, flat)) return std::nullopt;

  std::set<size_t> broken;
  Printer top(t, match, flat, broken);
  std::vector<Range> items = top.statements(0, n);
  for (size_t k = 0; k < items.size(); ++k) {
    top.leading(summarize(t[items[k].begin].gap), 0, k == 0, false);
    // Each item alone: break its outermost one-line block on a line that is too long, until
    // every line fits or no one-line block is left on the long ones.
    for (;;) {
      Printer item(t, match, flat, broken);
      item.statement(items[k], 0, 0);
      bool changed = false;
      for (int line : long_lines(item.out, options.width)) {
        const Printer::Flat* outer = nullptr;
        for (const auto& f : item.flats)
          if (f.line == line && (!outer || f.depth < outer->depth)) outer = &f;
        if (outer) {
          broken.insert(outer->open);
          changed = true;
          break;
        }
      }
      if (!changed) {
        top.put(item.out);
        break;
      }
    }
  }
  top.leading(summarize(t[n].gap), 0, items.empty(), true);
  std::string out = std::move(top.out);
  while (!out.empty() && (out.back() == ' ' || out.back() == '\n')) out.pop_back();
  if (!out.empty()) out += '\n';

  // The file's own line ending (of its first line break) and byte order mark.
  size_t brk = src.find_first_of("\r\n");
  std::string eol = brk == std::string::npos || src[brk] == '\n' ? "\n" : src.compare(brk, 2, "\r\n") == 0 ? "\r\n" : "\r";
  if (eol != "\n") {
    std::string converted;
    for (size_t k = 0; k < out.size(); ++k) {
      if (out[k] == '\n' && (k == 0 || out[k - 1] != '\r'))
        converted += eol;
      else
        converted += out[k];
    }
    out = std::move(converted);
  }
  return bom ? "\xEF\xBB\xBF" + out : out;
}

std::string format_markdown(std::string_view text, const FormatOptions& options) {
  std::string out, block;
  bool open = false;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    end = end == std::string_view::npos ? text.size() : end + 1;
    std::string_view line = text.substr(start, end - start);
    std::string_view bare = line.substr(0, line.find_last_not_of("\r\n") + 1);
    start = end;
    if (!open) {
      out += line;
      open = bare == "```rules";
      block.clear();
      continue;
    }
    if (bare != "```") {
      block += line;
      continue;
    }
    open = false;
    ast::SourceMap sources;
    uint32_t id = sources.add("block.rules", block);
    diag::Sink sink;
    std::optional<std::string> formatted = format_file(sources, id, sink, options);
    out += formatted && !formatted->empty() ? *formatted : block;
    out += line;
  }
  if (open) out += block;
  return out;
}

}  // namespace tranche::grammar
