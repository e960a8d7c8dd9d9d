#include "grammar/parse.h"

#include <fmt/format.h>

#include <new>

#include "RulesLexer.h"
#include "RulesParser.h"
#include "grammar/build_ast.h"
#include "grammar/errors.h"
#include "grammar/tokens.h"

namespace tranche::grammar {

namespace {

size_t g_ll_fallbacks = 0;

// Parses with SLL prediction first (fast, enough for every valid file) and again with full LL
// and error reporting only when SLL fails. `build` runs on an error-free tree while the parser
// (which owns the tree) is alive; returns false on syntax errors.
template <class Entry, class Build>
bool parse_tokens(Input& input, Tokens& tokens, diag::Sink& sink, const ParseOptions& options, Entry entry,
                  Build build) {
  std::vector<ast::Span> unclosed = tokens.unclosed;
  int budget = std::max(1, options.max_errors - tokens.errors);
  antlr4::ListTokenSource source(std::move(tokens.list));
  antlr4::CommonTokenStream stream(&source);
  RulesParser parser(&stream);
  parser.removeErrorListeners();
  auto* sim = parser.getInterpreter<antlr4::atn::ParserATNSimulator>();
  sim->setPredictionMode(antlr4::atn::PredictionMode::SLL);
  parser.setErrorHandler(std::make_shared<antlr4::BailErrorStrategy>());
  decltype(entry(parser)) tree = nullptr;
  try {
    tree = entry(parser);
  } catch (const antlr4::ParseCancellationException&) {
    ++g_ll_fallbacks;
    auto strategy = std::make_shared<ReportingStrategy>(input, sink, std::move(unclosed), budget);
    parser.reset();
    parser.setErrorHandler(strategy);
    sim->setPredictionMode(antlr4::atn::PredictionMode::LL);
    tree = entry(parser);
    if (strategy->reported() != 0) return false;  // else SLL was only unsure: LL parsed it cleanly
  }
  return build(tree);
}

bool report_encoding(const Input& input, diag::Sink& sink) {
  if (input.ok()) return true;
  const ast::SourceMap& sources = input.sources();
  uint32_t at = input.bad_offset();
  unsigned byte = static_cast<unsigned char>(sources.file(input.file()).text[at]);
  sink.error("E0001", sources.span(input.file(), at, at + 1), "file is not valid UTF-8",
             fmt::format("invalid byte 0x{:02X}", byte))
      .help("save the file as UTF-8");
  return false;
}

ast::Span start_span(const ast::SourceMap& sources, uint32_t file, uint32_t at) {
  return sources.span(file, at, at);
}

}  // namespace

ast::File parse_file(const ast::SourceMap& sources, uint32_t file_id, diag::Sink& sink,
                     const ParseOptions& options) {
  ast::File out;
  out.id = file_id;
  const std::string& text = sources.file(file_id).text;
  uint32_t begin = text.rfind("\xEF\xBB\xBF", 0) == 0 ? 3 : 0;
  try {
    Input input(sources, file_id, begin, static_cast<uint32_t>(text.size()));
    if (!report_encoding(input, sink)) return out;
    size_t errors_before = sink.errors();
    Tokens tokens = lex(input, sink, options, /*expression_only=*/false);
    // After a lexical error the parser would only report its consequences.
    if (tokens.fatal || tokens.errors > 0) return out;
    parse_tokens(
        input, tokens, sink, options, [](RulesParser& p) { return p.file(); },
        [&](RulesParser::FileContext* tree) {
          if (sink.errors() > errors_before) return false;
          AstBuilder builder(input, sink, options);
          ast::File file = builder.file(tree);
          if (builder.failed()) return false;
          out = std::move(file);
          return true;
        });
    return out;
  } catch (const TooManyErrors&) {
    return out;
  } catch (const std::bad_alloc&) {
    throw;  // not a syntax error: the tools say the memory ran out (base/memory.h)
  } catch (const std::exception& e) {
    // The ANTLR runtime throws on states it cannot handle; never let that escape.
    sink.error("E0004", start_span(sources, file_id, begin), fmt::format("the parser failed: {}", e.what()),
               "while reading this file");
    return out;
  }
}

ast::ExprPtr parse_expression(const ast::SourceMap& sources, uint32_t file_id, uint32_t begin, uint32_t end,
                              diag::Sink& sink, const ParseOptions& options) {
  try {
    Input input(sources, file_id, begin, end);
    if (!report_encoding(input, sink)) return nullptr;
    size_t errors_before = sink.errors();
    Tokens tokens = lex(input, sink, options, /*expression_only=*/true);
    if (tokens.fatal || tokens.errors > 0) return nullptr;
    ast::ExprPtr result;
    parse_tokens(
        input, tokens, sink, options, [](RulesParser& p) { return p.exprOnly(); },
        [&](RulesParser::ExprOnlyContext* tree) {
          if (sink.errors() > errors_before) return false;
          AstBuilder builder(input, sink, options);
          ast::ExprPtr e = builder.expression(tree->expr());
          if (builder.failed()) return false;
          result = std::move(e);
          return result != nullptr;
        });
    return result;
  } catch (const TooManyErrors&) {
    return nullptr;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    sink.error("E0004", start_span(sources, file_id, begin), fmt::format("the parser failed: {}", e.what()),
               "while reading this expression");
    return nullptr;
  }
}

size_t ll_fallbacks() { return g_ll_fallbacks; }

void clear_parser_caches() {
  antlr4::ANTLRInputStream in("");
  RulesLexer lexer(&in);
  antlr4::CommonTokenStream tokens(&lexer);
  RulesParser parser(&tokens);
  parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->clearDFA();
  parser.getInterpreter<antlr4::atn::ParserATNSimulator>()->getSharedContextCache().clear();
  lexer.getInterpreter<antlr4::atn::LexerATNSimulator>()->clearDFA();
}

}  // namespace tranche::grammar
