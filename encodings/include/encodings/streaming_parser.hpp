// The VRML97 reader for bytes that arrive over time (Nagasawa, "Beyond VRML", section
// 1.2: a world written outlines first is shown while it loads). Each completed top-level
// statement (node, PROTO, EXTERNPROTO, ROUTE) joins the scene as soon as its last byte
// has arrived, so the scene grows in file order; the result after finish() is the Scene
// that parseVrml() gives for the whole text. X3D's XML encoding (ISO/IEC 19776-1: the
// first byte after white space and BOM is '<') is read too: it is translated into Classic
// VRML text as it comes, each top-level element of <Scene> joining the scene once its end
// tag has arrived, with diagnostics and node locations at the XML's line and column.
#pragma once

#include "encodings/parser.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace gs::vrml {

class StreamingParser {
 public:
  /// `url` names the text in diagnostics and is the base of relative URLs, as for
  /// parseVrml(). `options` (limits, EXTERNPROTO loader, onRootNode) as parseVrml().
  explicit StreamingParser(std::string url, ParseOptions options = {});
  ~StreamingParser();
  StreamingParser(const StreamingParser&) = delete;
  StreamingParser& operator=(const StreamingParser&) = delete;

  /// Changes the URL that names the text and is the base of its relative URLs (an HTTP
  /// redirect moved it). Only before the first feed(); returns false (nothing changed)
  /// after.
  bool rebase(std::string url);

  /// Adds the next bytes of the file (any split, gzip compressed or not: the first two
  /// bytes decide) and parses every top-level statement now complete. Cost: amortized
  /// linear in the input; a statement cut by the end of the bytes so far is retried only
  /// once the unparsed text has grown by half. Returns the number of root nodes added.
  /// Never throws for bad content (diagnostics as parseVrml; a corrupt gzip stream or a
  /// fatal syntax error ends parsing and later bytes are ignored; an X3D XML document whose
  /// version is refused builds nothing, but its later bytes are still read for the XML
  /// warnings and syntax error parseVrml also reports, so done() stays false).
  std::size_t feed(std::string_view bytes);

  /// No more bytes will come: parses what is left. A last statement cut short is
  /// reported as parseVrml() reports the same truncated text ("unexpected end of
  /// file ..."). Returns the number of root nodes added.
  std::size_t finish();

  /// The scene parsed so far. Valid until the next feed() or finish().
  const Scene& scene() const;
  /// Moves the scene out (after finish()).
  Scene takeScene();

  /// Text bytes (after gunzip) received / consumed by complete statements (for XML: of
  /// its Classic VRML translation, which holds only the statements not built straight
  /// from their elements).
  std::size_t textBytes() const;
  std::size_t parsedBytes() const;
  /// Whether parsing stopped for good (finish() called, or a fatal error).
  bool done() const;
  /// With ParseOptions::externProtosInBackground: whether the next statement waits for
  /// an EXTERNPROTO file still on its way. feed() (even of no bytes) retries it; call
  /// finish() only once this is false, or the EXTERNPROTO fails with "still on its way".
  bool waitingForExternProto() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gs::vrml
