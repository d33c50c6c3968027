// The X3D XML encoding (ISO/IEC 19776-1) read through expat and translated into the
// Classic VRML encoding (ISO/IEC 19776-2), which the parser reads: DEF/USE, PROTO
// expansion, ROUTE checks, IS and Scripts then work as for a .x3dv file. Each top-level
// element of <Scene> is buffered as a small tree and written out as one statement when
// its end tag arrives, so a world still grows statement by statement while it loads.
// Every element's translation starts on a line of its own, and the XML line and column
// of its start tag are recorded for that line: mapDiagnostics() moves the parser's
// diagnostics back onto the XML. Internal to gs_vrml.
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

/// Whether `text` (after gunzip) is XML: its first byte that is neither white space nor
/// part of a UTF-8 byte order mark is '<'. `decided` is false when `text` holds no such
/// byte yet (more may come).
bool looksLikeXml(std::string_view text, bool& decided);

/// The translator, over expat's push parser (external entities are never loaded).
class XmlToClassic {
 public:
  /// Appends the Classic VRML text to `out` (which nobody else may change while this
  /// lives). `url` names the XML in diagnostics; elements nested deeper than
  /// `maxNesting` (plus the few levels of X3D, Scene, ProtoDeclare and ProtoBody) end the
  /// translation with an error.
  XmlToClassic(std::string& out, std::string url, int maxNesting);
  ~XmlToClassic();
  XmlToClassic(const XmlToClassic&) = delete;
  XmlToClassic& operator=(const XmlToClassic&) = delete;

  /// Adds the next bytes of the XML (any split). Returns false once translation stopped
  /// for good (XML syntax error, nesting limit): fatalError() says why; the statements
  /// written before stay. `last`: no more bytes will come (finish() in the same call,
  /// which spares expat a pass over the bytes for its line and column counts).
  bool feed(std::string_view bytes, bool last = false);
  /// No more bytes will come (an unclosed document is a syntax error). Same result.
  bool finish();

  /// Whether the header line ("#X3D V3.3 utf8") has been written.
  bool wroteHeader() const;
  /// Whether translation stopped for good.
  bool failed() const;
  /// The error that stopped it (at the XML's file:line:column), when failed().
  const Diagnostic& fatalError() const;

  /// The XML line and column (1-based) of the start tag of the element whose translation
  /// Classic line `classicLine` (1-based) belongs to; {0, 0} when none.
  std::pair<int, int> xmlLocation(int classicLine) const;

  /// What `scene` holds now is not to be mapped by mapScene() (call before parsing).
  void skipTo(const Scene& scene);
  /// Moves the locations of what the parser added to `scene` since the last call (or
  /// skipTo) from Classic lines to the XML's line and column, where they name this XML's
  /// url: diagnostics, the nodes reachable from new root and hidden nodes (each node
  /// once), ROUTEs, IMPORTs and EXPORTs.
  void mapScene(Scene& scene);
  /// mapScene(), then appends the warnings found while translating so far (lenient
  /// MFString values, ignored content; at XML locations) to the scene's diagnostics.
  void addWarnings(Scene& scene);

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace gs::vrml::parsing
