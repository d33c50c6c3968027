#include "vrml/diagnostic.hpp"

#include <algorithm>

namespace gs::vrml {

SourceFile::SourceFile(const SourceFile& other) = default;
SourceFile::SourceFile(SourceFile&& other) noexcept = default;
SourceFile& SourceFile::operator=(const SourceFile& other) = default;
SourceFile& SourceFile::operator=(SourceFile&& other) noexcept = default;
SourceFile::~SourceFile() = default;

std::string Diagnostic::format() const {
  std::string s = location.file.empty() ? std::string("<input>") : location.file.str();
  if (location.line > 0) {
    s += ':' + std::to_string(location.line);
    if (location.column > 0) s += ':' + std::to_string(location.column);
  }
  s += severity == Severity::error ? ": error: " : ": warning: ";
  s += message;
  return s;
}

void Diagnostics::warning(SourceLocation loc, std::string message) {
  items.push_back({Severity::warning, std::move(loc), std::move(message)});
}

void Diagnostics::error(SourceLocation loc, std::string message) {
  items.push_back({Severity::error, std::move(loc), std::move(message)});
}

bool Diagnostics::hasErrors() const {
  return errorCount() > 0;
}

std::size_t Diagnostics::errorCount() const {
  return static_cast<std::size_t>(
      std::count_if(items.begin(), items.end(),
                    [](const Diagnostic& d) { return d.severity == Severity::error; }));
}

std::size_t Diagnostics::warningCount() const {
  return items.size() - errorCount();
}

}  // namespace gs::vrml
