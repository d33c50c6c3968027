// Moving locations from the Classic VRML text a translated encoding (XML, JSON) produced
// back onto the file the user wrote: what the parser added to a Scene since the last call
// (diagnostics, nodes, routes, IMPORT/EXPORT statements) names lines of the translation;
// `locate` gives the original line and column of a Classic line. Internal to gs_vrml.
#pragma once

#include "vrml/scene.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace gs::vrml::parsing {

class LocationMapper {
 public:
  /// Where a Classic line (1-based) came from: {line, column} in the original file, or
  /// {0, 0} when unknown (the location is then left as it is).
  using Locate = std::function<std::pair<int, int>(int classicLine)>;

  /// What `scene` holds now is not to be mapped (it was there before the translation).
  void skipTo(const Scene& scene);
  /// The diagnostics `scene` holds now are at original locations already (the
  /// translator's own warnings): map() leaves them.
  void skipDiagnostics(const Scene& scene) { done_.diagnostics = scene.diagnostics.items.size(); }
  /// Maps the locations `url` names in what was added to `scene` since the last call:
  /// diagnostics, nodes reachable from new roots, hidden nodes and routes (each node
  /// once), routes, IMPORT and EXPORT statements. Each list only grows while parsing; a
  /// shorter one was replaced (rejected input) and is mapped from its start.
  void map(Scene& scene, const std::string& url, const Locate& locate);

 private:
  struct Done {
    std::size_t diagnostics = 0, roots = 0, hidden = 0, routes = 0, imports = 0, exports = 0;
  } done_;
  // The nodes already mapped: an open-addressing hash set (null: free slot).
  bool insertMapped(const Node* n);
  std::vector<const Node*> mapped_;
  std::size_t mappedCount_ = 0;
};

}  // namespace gs::vrml::parsing
