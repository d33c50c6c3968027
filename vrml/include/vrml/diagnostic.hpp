// Diagnostics with place: `file:line:column: error: expected X, got Y`.
#pragma once

#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace gs::vrml {

/// The name of a source text (a path or URL as the user gave it), shared rather than
/// copied: every node and diagnostic of a file names it, so a copy is a reference count
/// (no allocation per node). Reads as the std::string it holds; empty when default-made.
class SourceFile {
 public:
  SourceFile() = default;
  // Implicit, so that `{url, line, column}` makes a SourceLocation from a std::string.
  SourceFile(std::string name)  // NOLINT(google-explicit-constructor)
      : name_(std::make_shared<const std::string>(std::move(name))) {}
  SourceFile(const char* name)  // NOLINT(google-explicit-constructor)
      : SourceFile(std::string(name)) {}
  SourceFile(std::string_view name)  // NOLINT(google-explicit-constructor)
      : SourceFile(std::string(name)) {}
  // Out of line (diagnostic.cpp): inlined into every function that throws a Diagnostic,
  // the shared_ptr's release draws GCC 12's -Wmaybe-uninitialized false positive.
  SourceFile(const SourceFile& other);
  SourceFile(SourceFile&& other) noexcept;
  SourceFile& operator=(const SourceFile& other);
  SourceFile& operator=(SourceFile&& other) noexcept;
  ~SourceFile();

  /// The name ("" when none).
  const std::string& str() const { return name_ ? *name_ : noName(); }
  operator const std::string&() const { return str(); }  // NOLINT(google-explicit-constructor)
  bool empty() const { return str().empty(); }
  bool ends_with(std::string_view tail) const { return str().ends_with(tail); }

  friend bool operator==(const SourceFile& a, const SourceFile& b) {
    return a.name_ == b.name_ || a.str() == b.str();
  }
  friend bool operator==(const SourceFile& a, const std::string& b) { return a.str() == b; }
  friend bool operator==(const SourceFile& a, std::string_view b) { return a.str() == b; }
  friend bool operator==(const SourceFile& a, const char* b) { return a.str() == b; }
  friend std::string operator+(const SourceFile& a, std::string_view b) {
    return a.str() + std::string(b);
  }
  friend std::string operator+(std::string_view a, const SourceFile& b) {
    return std::string(a) + b.str();
  }
  friend std::ostream& operator<<(std::ostream& out, const SourceFile& f) { return out << f.str(); }

 private:
  static const std::string& noName() {
    static const std::string none;
    return none;
  }
  std::shared_ptr<const std::string> name_;
};

/// A place in a source text. Lines and columns count from 1 (column in bytes);
/// 0 means unknown.
struct SourceLocation {
  SourceFile file;  // path or URL as the user gave it
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
