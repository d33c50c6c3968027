// Helpers of the X3D Script tests (test_script_x3d*.cpp): small worlds run by the execution
// model with the ECMAScript host, their diagnostics, and the Script S's outputs.
#pragma once

#include "runtime_fixture.hpp"
#include "script_test_support.hpp"

#include <string>

namespace gs::test {

/// Execution options that run Scripts with ECMAScript under relaxedLimits().
inline runtime::ExecutionOptions x3dScripts() {
  runtime::ExecutionOptions o;
  o.scripts = runtime::ecmascriptFactory();
  o.scriptLimits = relaxedLimits();
  return o;
}

/// The execution model's and the parser's diagnostics of `w`, one per line.
inline std::string modelDiagnostics(const RunningWorld& w) {
  std::string s;
  for (const auto& d : w.model->diagnostics().items) s += d.format() + "\n";
  for (const auto& d : w.scene->diagnostics.items) s += d.format() + "\n";
  return s;
}

/// The value of field `field` of the node DEFed S (the Script whose outputs a test reads).
inline const vrml::FieldValue& outOf(const RunningWorld& w, const std::string& field) {
  const vrml::FieldValue* v = w.node("S").field(field);
  REQUIRE(v != nullptr);
  return *v;
}

}  // namespace gs::test
