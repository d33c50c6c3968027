// Field values as the X3D XML encoding writes them (ISO/IEC 19776-1 clause 5: attribute
// values) turned into the Classic VRML encoding's text (ISO/IEC 19776-2 clause 5), which
// the field-value parser reads. Used for the XML encoding and for the node model's
// defaults (X3DUOM writes them in the XML syntax). Internal to gs_encodings.
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

/// A DEF/PROTO name as Classic VRML can write it (clause 5.2.3 of ISO/IEC 19776-2: no
/// spaces, quotes, '#', ',', '.', brackets or backslash; not starting with a digit or
/// sign): XML IDs such as "Cube.001" are written "Cube_001". Appended to `out`.
void appendXmlIdent(std::string& out, std::string_view s);
std::string xmlIdent(std::string_view s);

/// The Classic text of a field type's default value (for a <field> without value).
std::string classicDefaultText(FieldType t);

/// Whether a field of access type `access` (X3D or VRML97 name) takes a value.
bool accessTakesValue(std::string_view access);

/// Whether XML attribute `n` is no field (ISO/IEC 19776-1 5.1): DEF, USE, containerField,
/// namespaced names (xmlns, "xsd:..."), and HTML's class, id and style (which a node may
/// still have a field of).
bool xmlIgnoredAttribute(std::string_view n);

/// Whether `text` starts with a URL scheme ("ecmascript:", "data:", "http:").
bool hasUrlScheme(std::string_view text);

/// Appends `s` to `out` as a Classic VRML string literal ("..." with '"' and '\' escaped).
void appendQuoted(std::string& out, std::string_view s);

}  // namespace gs::vrml::parsing
