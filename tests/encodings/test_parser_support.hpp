// Helpers shared by the parser tests.
#pragma once

#include "encodings/parser.hpp"
#include "test_support.hpp"

#include <string>

namespace gs::test {

/// Parses `body` after a "#VRML V2.0 utf8" header line, as file "test.wrl" (so the
/// body's first line is line 2).
inline vrml::Scene parse(const std::string& body, const vrml::ParseOptions& options = {}) {
  return vrml::parseVrml("#VRML V2.0 utf8\n" + body, "test.wrl", options);
}

/// The message of the first error diagnostic; empty when there is none.
inline std::string firstError(const vrml::Scene& s) {
  for (const vrml::Diagnostic& d : s.diagnostics.items)
    if (d.severity == vrml::Severity::error) return d.message;
  return {};
}

}  // namespace gs::test
