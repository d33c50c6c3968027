// The VRML97 reader: classic UTF-8 encoding (ISO/IEC 14772-1:1997 clause 5 and annex A
// grammar), gzip read transparently; also X3D's Classic VRML encoding (ISO/IEC 19776-2)
// and X3D's XML encoding (ISO/IEC 19776-1, read through expat and translated into the
// Classic encoding; external entities are never loaded). Safe for untrusted input: every error is a
// Diagnostic with file:line:column, nesting and allocation are bounded.
#pragma once

#include "base/fetch.hpp"
#include "vrml/scene.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <string_view>

namespace gs::vrml {

/// Limits that keep hostile input from exhausting the machine.
struct ParseLimits {
  int maxNesting = 256;                    // nested nodes / PROTO instances
  std::size_t maxInputBytes = 1ull << 31;  // after gzip decompression, bytes
  int maxExternProtoDepth = 8;             // EXTERNPROTO files loading others
  std::size_t maxNodes = 4'000'000;        // nodes created, PROTO expansions included
};

struct ParseOptions {
  ParseLimits limits;
  /// Reads EXTERNPROTO files and a glTF asset's external buffers and images
  /// (FetchMode::whole, the parsed file's URL as referrer); not owned, and must outlive
  /// the parse. Null: local files and data: URLs only (base::LocalFetcher).
  base::Fetcher* fetcher = nullptr;
  /// StreamingParser only: EXTERNPROTO files of the streamed file are asked for in the
  /// background (base::FetchMode::background), and a statement that needs one still on
  /// its way waits, as a statement cut short does, and is retried at a later feed() (the
  /// instances appear when their definition arrives; StreamingParser::
  /// waitingForExternProto()). At finish() a file still on its way fails the EXTERNPROTO
  /// (a warning). False: read whole (FetchMode::whole) during the parse.
  bool externProtosInBackground = false;
  /// Called with each completed top-level node as soon as it is parsed (for progressive
  /// display); may be empty.
  std::function<void(const NodePtr&)> onRootNode;
};

/// Parses a VRML97 or X3D text (or gzip of one) held in memory: text whose first byte
/// after white space and a UTF-8 BOM is '<' is X3D XML (Scene::x3d.encoding "XML"), whose
/// diagnostics and node locations give the XML's line and column. `url` names it in
/// diagnostics and is the base for relative URLs. Never throws for bad content: a fatal syntax
/// error ends the parse with an error Diagnostic and the nodes read before it are kept; recoverable
/// problems (unknown node or field, unresolved EXTERNPROTO) are diagnosed and skipped. A "#VRML
/// V1.0 ascii" header gives the error "VRML 1.0 is not supported".
///
/// PROTO instances are expanded (see Node and proto.hpp); ROUTEs to their interfaces are
/// flattened (see Route). A Script field that USEs the Script itself, or a Script it is
/// nested in (allowed by clause 6.40, a cycle anywhere else), holds a non-owning NodePtr
/// (use_count() == 0) so that the cycle does not leak; it is valid while that Script lives.
/// Nodes nested deeper than ParseLimits::maxNesting, more than ParseLimits::maxNodes
/// nodes, or input larger than ParseLimits::maxInputBytes end the parse with an error.
Scene parseVrml(std::string_view bytes, const std::string& url, const ParseOptions& options = {});

/// Reads `path` (gzip or not) and parses it as parseVrml does. A file that cannot be
/// read gives a Scene with one error diagnostic naming the path and the reason.
Scene loadVrmlFile(const std::string& path, const ParseOptions& options = {});

/// Decompresses `bytes` when they start with the gzip magic (1f 8b), else returns them.
/// Throws ParseError ("file: corrupt gzip data: ...") on a damaged stream and when the
/// result would exceed `maxBytes`.
std::string gunzipIfCompressed(std::string_view bytes, const std::string& url,
                               std::size_t maxBytes);

}  // namespace gs::vrml
