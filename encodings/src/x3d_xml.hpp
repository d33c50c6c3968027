// The X3D XML encoding (ISO/IEC 19776-1) read through expat and translated into the
// Classic VRML encoding (ISO/IEC 19776-2), which the parser reads: DEF/USE, PROTO
// expansion, ROUTE checks, IS and Scripts then work as for a .x3dv file. Each top-level
// element of <Scene> is buffered as a small tree and written out as one statement when
// its end tag arrives, so a world still grows statement by statement while it loads.
// Every element's translation starts on a line of its own, and the XML line and column
// of its start tag are recorded for its first byte: origin() gives the parser those
// locations, so every node, route and diagnostic it makes names the XML. With a builder
// (setBuilder: parseVrml's reader and StreamingParser), a plain statement is offered to it
// first and built straight from its elements, with no Classic text (parser_xml_build.cpp).
// Internal to gs_encodings.
#pragma once

#include "lexer.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

class XmlStatementBuilder;  // x3d_xml_tree.hpp

/// Whether `text` (after gunzip) is XML: its first byte that is neither white space nor
/// part of a UTF-8 byte order mark is '<'. `decided` is false when `text` holds no such
/// byte yet (more may come).
bool looksLikeXml(std::string_view text, bool& decided);

/// Byte offsets of a translation -> the original file's line and column: one entry per
/// translated element, at the first byte of its translation (offsets increasing). Every
/// byte up to the next entry belongs to that element.
class OffsetLocations final : public TextOrigin {
 public:
  struct Entry {
    std::size_t offset;  // in the translation, bytes
    int line;            // in the original, 1-based
    int column;          // in the original, 1-based
  };
  /// Adds an entry at `e.offset` (not before the last one's; an entry at the same offset
  /// replaces it: that element wrote nothing).
  void add(const Entry& e) {
    if (!entries_.empty() && entries_.back().offset == e.offset)
      entries_.back() = e;
    else
      entries_.push_back(e);
  }
  const std::vector<Entry>& entries() const { return entries_; }
  /// The entry at or before `offset`: O(1) when asked in increasing order, O(log n)
  /// otherwise; {0, 0} before the first entry.
  std::pair<int, int> at(std::size_t offset) override;

 private:
  std::vector<Entry> entries_;
  std::size_t cursor_ = 0;  // the entry of the last offset asked
};

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

  /// Offers each top-level node statement of <Scene> to `builder` (null: none) before
  /// translating it, while the Classic text written so far cannot run into what follows
  /// it (no raw attribute text in it that could open a string, comment or bracket, no
  /// SFImage, whose parse looks ahead). `builder` must outlive the translation.
  void setBuilder(XmlStatementBuilder* builder);

  /// Whether the header line ("#X3D V3.3 utf8") has been written.
  bool wroteHeader() const;
  /// Whether translation stopped for good.
  bool failed() const;
  /// The error that stopped it (at the XML's file:line:column), when failed().
  const Diagnostic& fatalError() const;

  /// The XML line and column (1-based) of the start tag of the element whose translation
  /// byte `offset` of the Classic text belongs to; {0, 0} when none. Offsets asked in
  /// increasing order cost O(1) each, others O(log elements).
  std::pair<int, int> xmlLocationAt(std::size_t offset);
  /// xmlLocationAt() for the parser of the translation (Parser's `origin`); lives as long
  /// as this translator.
  TextOrigin& origin();
  /// Appends the warnings found while translating so far (lenient MFString values,
  /// ignored content; at XML locations) to the scene's diagnostics: at index `at` of
  /// its list (after the others when that is past its end).
  void addWarnings(Scene& scene, std::size_t at = static_cast<std::size_t>(-1));

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace gs::vrml::parsing
