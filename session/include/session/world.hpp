// Loading a whole world from a local file, timed: `ghostspace info`, `encode` and the
// inputs that are not VRML97 (meshes, volumes, .qnv files). Worlds from http(s) URLs
// stream through StreamingSession instead (session/streaming_session.hpp).
#pragma once

#include "vrml/scene.hpp"

#include <map>
#include <memory>
#include <string>

namespace gs::session {

struct LoadedWorld {
  std::shared_ptr<vrml::Scene> scene;  // never null; diagnostics say what went wrong
  double parseSeconds = 0.0;           // reading + decompressing + parsing, wall clock
  std::size_t bytes = 0;               // size of the file as stored (before gunzip)
  bool readable = false;               // false when the file could not be read at all
};

/// The sentence "unsupported format (.stl): not a VRML97 or X3D world, ..." when the local
/// file `path` is none of the inputs GhostSpace reads (formats::classifyFile finds no kind
/// from its leading bytes or its name: a world without its '#VRML' or '#X3D' header and
/// without a world's extension is not a world either), else "". Only printable ASCII of
/// the extension is quoted.
std::string unsupportedFormat(const std::string& path);

/// Reads and parses the VRML97 world at the local path `path` (gzip or not); a mesh,
/// volume or .qnv file opens as the world splat_inputs.hpp makes for it. Never throws
/// for bad content: problems are in scene->diagnostics. A file of an unsupported format
/// (unsupportedFormat) is not readable: its one diagnostic says so.
LoadedWorld loadWorld(const std::string& path);

/// Distinct nodes reachable from the scene's roots through SFNode/MFNode fields, counted
/// by type name (a USEd node counts once). A PROTO instance counts under its body node's
/// type (what is drawn) and under "Name (PROTO)" (what the world declares).
std::map<std::string, std::size_t> countNodesByType(const vrml::Scene& scene);

}  // namespace gs::session
