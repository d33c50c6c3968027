// The X3D JSON encoding (ISO/IEC 19776-5, ".x3dj") read through nlohmann-json. The JSON
// encoding mirrors the XML one element for element ("@field" keys are attributes,
// "-field" keys hold the nodes of a field, "#sourceCode" is a Script's text), so the
// parsed document is written out as XML text and read by XmlToClassic: the Classic VRML
// text, containerField grouping, PROTO and Script field types are then exactly those of
// the XML encoding. Each element starts a line of that XML, and each XML line is mapped
// onto the JSON line and column where the element's object starts (found by scanning the
// JSON's bytes for '{' outside strings, in document order): diagnostics are moved from
// Classic lines to XML lines (XmlToClassic) and then to the JSON. Whole documents only (no
// streaming). Internal to gs_encodings.
#pragma once

#include "lexer.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>

namespace gs::vrml::parsing {

/// Whether `text` (after gunzip) is JSON: its first byte that is neither white space nor
/// part of a UTF-8 byte order mark is '{'. `decided` is false when `text` holds no such
/// byte yet (more may come).
bool looksLikeJson(std::string_view text, bool& decided);

/// The translator of one whole JSON document.
class JsonToClassic {
 public:
  /// Appends the Classic VRML text to `out` (which nobody else may change while this
  /// lives). `url` names the JSON in diagnostics; input nested deeper than about three
  /// JSON levels per node for `maxNesting` nodes is refused before it is parsed.
  JsonToClassic(std::string& out, std::string url, int maxNesting);
  ~JsonToClassic();
  JsonToClassic(const JsonToClassic&) = delete;
  JsonToClassic& operator=(const JsonToClassic&) = delete;

  /// Translates the whole document `json`. What `scene` holds now is not mapped later;
  /// the translation's structural errors and warnings (at JSON locations, naming the JSON
  /// path) are added to it. Returns false when translation failed for good (JSON syntax
  /// error, nesting limit, no "X3D" object): fatalError() says why. Never throws but
  /// std::bad_alloc.
  bool translate(std::string_view json, Scene& scene);

  /// Whether the header line ("#X3D V4.0 utf8") has been written.
  bool wroteHeader() const;
  /// Whether translation failed for good.
  bool failed() const;
  /// The error that stopped it (at the JSON's file:line:column), when failed().
  const Diagnostic& fatalError() const;

  /// The JSON line and column (1-based) of the object whose translation byte `offset` of
  /// the Classic text belongs to; {0, 0} when none.
  std::pair<int, int> jsonLocationAt(std::size_t offset);
  /// jsonLocationAt() for the parser of the translation (Parser's `origin`), as
  /// XmlToClassic::origin() for XML; lives as long as this translator.
  TextOrigin& origin();

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace gs::vrml::parsing
