// Event traces (--trace-events): each event as one JSON line, so tests and users can
// check a cascade exactly.
#pragma once

#include "runtime/execution_model.hpp"
#include "vrml/field.hpp"

#include <string>

namespace gs::runtime {

/// `value` in VRML97 file syntax (clause 5): "TRUE", "1 0 0", "[ 0.5, 1 ]"; numbers with
/// up to 6 significant digits (SFTime with millisecond precision, "%.3f"); SFNode as its
/// DEF name or type name, "NULL" when null; SFImage as "W H C" followed by the pixels in hex.
std::string fieldValueText(const vrml::FieldValue& value);

/// The name a trace gives a node: its DEF name, else its type name.
std::string traceNodeName(const vrml::Node& node);

/// One event as a JSON object on one line (no newline):
/// {"time":1.500,"node":"T","field":"fraction_changed","value":"0.5"}; the value is
/// fieldValueText() as a JSON string; an exposedField x is named
/// by its eventOut, x_changed.
std::string traceJson(const TraceEvent& event);

}  // namespace gs::runtime
