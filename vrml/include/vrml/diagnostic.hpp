// Diagnostics with place: `file:line:column: error: expected X, got Y`.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace gs::vrml {

/// A place in a source text. Lines and columns count from 1 (column in bytes);
/// 0 means unknown.
struct SourceLocation {
  std::string file;  // path or URL as the user gave it
  int line = 0;
  int column = 0;
};

enum class Severity { warning, error };

/// One message about an input. Errors mean part of the input was skipped or the input
/// was rejected; warnings mean it was read with a recoverable oddity.
struct Diagnostic {
  Severity severity = Severity::error;
  SourceLocation location;
  std::string message;

  /// "file:line:column: error: message" (line and column omitted when 0).
  std::string format() const;
};

/// Collected diagnostics of one load.
struct Diagnostics {
  std::vector<Diagnostic> items;
  void warning(SourceLocation loc, std::string message);
  void error(SourceLocation loc, std::string message);
  bool hasErrors() const;
  std::size_t errorCount() const;
  std::size_t warningCount() const;
};

/// Thrown by the lexer and parser for a fatal error (bad header, syntax error the parser
/// cannot recover from, resource limit). `what()` is the formatted diagnostic.
class ParseError : public std::runtime_error {
 public:
  explicit ParseError(Diagnostic d) : std::runtime_error(d.format()), diagnostic(std::move(d)) {}
  Diagnostic diagnostic;
};

}  // namespace gs::vrml
