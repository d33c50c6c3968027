// Loading a world for the application: from a path (later: a URL), timed.
#pragma once

#include "vrml/scene.hpp"

#include <map>
#include <memory>
#include <string>

namespace gs::app {

struct LoadedWorld {
  std::shared_ptr<vrml::Scene> scene;  // never null; diagnostics say what went wrong
  double parseSeconds = 0.0;           // reading + decompressing + parsing, wall clock
  std::size_t bytes = 0;               // size of the file as stored (before gunzip)
  bool readable = false;               // false when the file could not be read at all
};

/// Reads and parses the VRML97 world at `path` (gzip or not). Never throws for bad
/// content: problems are in scene->diagnostics.
LoadedWorld loadWorld(const std::string& path);

/// Distinct nodes reachable from the scene's roots through SFNode/MFNode fields, counted
/// by type name (a USEd node counts once).
std::map<std::string, std::size_t> countNodesByType(const vrml::Scene& scene);

}  // namespace gs::app
