// The X3D XML encoding's number lists (ISO/IEC 19776-1 5.3: MF values are their numbers
// separated by white space or commas, without brackets) in their plain forms, read
// straight from an attribute's text: what the Classic VRML lexer reads from their
// translation "[ ... ]", to the bit, or nothing. Used for the plain statements built
// without Classic text (parser_xml_build.cpp), also while an element starts
// (XmlToClassic), so that a long list is not copied first. Internal to gs_encodings.
#pragma once

#include "vrml/field.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace gs::vrml::parsing {

/// Numbers per element of the MF types read here: 1 for MFInt32 and MFFloat, 2 for
/// MFVec2f, 3 for MFVec3f and MFColor; 0 for every other type.
int plainListComponents(FieldType t);

/// Reads `text` (ended by a NUL byte) as decimal integers of up to 9 digits with an
/// optional '-' (Lexer's inline path). False, `out` in any state, on anything else (hex,
/// '+', longer numbers, a comment, any other byte): the Lexer then reads the value.
bool readPlainInts(const char* text, std::vector<std::int32_t>& out);
/// Reads `text` (ended by a NUL byte) as `components` floats per element, flat: decimals
/// of up to 8 digits without exponent as Lexer's inline path, other numbers that start
/// with a digit or '.' (after an optional '-') through fast_float as Lexer::readFloatSlow.
/// False, `out` in any state, on anything else or a last element cut short.
bool readPlainFloats(const char* text, int components, std::vector<float>& out);

/// `out` = the list of type `t` (plainListComponents(t) > 0) from what readPlainInts
/// (MFInt32) or readPlainFloats read.
void assignPlainList(FieldValue& out, FieldType t, const std::vector<std::int32_t>& ints,
                     const std::vector<float>& floats);
/// Appends the Classic VRML text of such a list ("[ 1 2 3 ]"), which the lexer reads back
/// to the same values (std::to_chars' shortest round trip for the floats).
void appendPlainListAsClassic(std::string& out, FieldType t, const std::vector<std::int32_t>& ints,
                              const std::vector<float>& floats);

}  // namespace gs::vrml::parsing
