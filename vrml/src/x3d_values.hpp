// Field values as the X3D XML encoding writes them (ISO/IEC 19776-1 clause 5: attribute
// values) turned into the Classic VRML encoding's text (ISO/IEC 19776-2 clause 5), which
// the field-value parser reads. Used for the XML encoding and for the node model's
// defaults (X3DUOM writes them in the XML syntax). Internal to gs_vrml.
#pragma once

#include "vrml/field.hpp"

#include <string>
#include <string_view>

namespace gs::vrml::parsing {

/// The Classic VRML text of the XML attribute value `xml` of a field of type `t`:
/// SFString quoted (with '"' and '\' escaped), SFBool/MFBool `true`/`false` as TRUE/FALSE,
/// MF values in brackets, an empty SFNode as NULL. An MFString written without double
/// quotes (single quotes, or one bare string) is read leniently and `warning` is set to
/// a sentence saying so; otherwise `warning` is left empty. Never throws.
std::string xmlValueToClassic(FieldType t, std::string_view xml, std::string& warning);
/// xmlValueToClassic() appended to `out`.
void appendXmlValueAsClassic(std::string& out, FieldType t, std::string_view xml,
                             std::string& warning);

/// Appends `s` to `out` as a Classic VRML string literal ("..." with '"' and '\' escaped).
void appendQuoted(std::string& out, std::string_view s);

}  // namespace gs::vrml::parsing
