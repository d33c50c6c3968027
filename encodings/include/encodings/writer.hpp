// Writing a parsed world back out (`ghostspace convert`, docs/x3d.md "Conversion"): the
// VRML97 encoding (ISO/IEC 14772-1:1997 clause 5 and annex A), X3D's Classic VRML encoding
// (ISO/IEC 19776-2), XML encoding (ISO/IEC 19776-1) and JSON encoding (ISO/IEC 19776-5).
// The writers work from the vrml::Scene the parser made: DEF names, PROTO and EXTERNPROTO
// declarations (instances are written as instances, not as their expansion), IS, ROUTEs,
// IMPORT / EXPORT and the X3D header (PROFILE, COMPONENT, META) are kept; field values
// print so that they re-parse to the same bits. What the target encoding cannot express is
// a Diagnostic in WriteResult::diagnostics, never a silent drop.
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/scene.hpp"

#include <optional>
#include <string>
#include <string_view>

namespace gs::vrml {

/// The encodings a Scene can be written in.
enum class Encoding {
  vrml97,   // .wrl: "#VRML V2.0 utf8" (ISO/IEC 14772-1)
  classic,  // .x3dv: X3D Classic VRML encoding (ISO/IEC 19776-2)
  xml,      // .x3d: X3D XML encoding (ISO/IEC 19776-1)
  json,     // .x3dj: X3D JSON encoding (ISO/IEC 19776-5)
};

/// The encoding a file name asks for, by its extension (case-insensitive): ".wrl" vrml97,
/// ".x3dv" classic, ".x3d" xml, ".x3dj" and ".json" json; nothing for any other name
/// (compressed names such as ".x3dz" included: the writers write plain text).
std::optional<Encoding> encodingForPath(std::string_view path);

/// The name of an encoding as the docs and diagnostics spell it ("VRML97", "X3D Classic
/// VRML", "X3D XML", "X3D JSON").
std::string_view encodingName(Encoding e);

struct WriteOptions {
  Encoding encoding = Encoding::classic;
  /// The X3D version written in the header of an X3D encoding when the scene is a VRML97
  /// world (Scene::x3d.version empty); an X3D world keeps its own version.
  std::string x3dVersionForVrml97 = "3.3";
};

/// The text written and what could not be written.
struct WriteResult {
  std::string text;  // UTF-8, ready to be saved as a file of the chosen encoding
  /// Warnings for what the target cannot express (an X3D node or field in a .wrl, a UNIT
  /// statement, a DEF name that two nodes share ...), each with the place in the source
  /// world of what it names where known (file:line:column); never errors.
  Diagnostics diagnostics;
};

/// Writes `scene` in `options.encoding`. Only the fields whose value differs from the
/// field's default are written; floats print with the fewest digits that read back to the
/// same value (std::to_chars), so parse -> write -> parse gives the same scene graph
/// (tests/encodings/test_writer.cpp). PROTO instances are written as instances of their
/// declaration with the interface values they were given; ROUTEs to and from an instance
/// name its interface; ROUTEs, IMPORT / EXPORT and PROTO declarations keep their place
/// among the root nodes (by their source locations). UNIT statements of length and angle
/// are not written: the parser has already converted the values into base units (metres,
/// radians), which is what is written (a diagnostic says so); mass and force UNITs are. For
/// Encoding::vrml97, nodes and fields that VRML97 lacks, X3D-only field types and X3D's header
/// statements are diagnostics and are left out. Never throws for any Scene the parser made
/// (std::bad_alloc aside).
WriteResult writeScene(const Scene& scene, const WriteOptions& options);

}  // namespace gs::vrml
