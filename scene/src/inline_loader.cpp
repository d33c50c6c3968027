// SceneTraversal's Inline loader (clause 6.25): each url resolved against the world
// that holds the Inline (base/url.hpp), checked against what that world may reference,
// streamed through TraversalOptions::inlineSource or read whole through its fetcher;
// results and failures cached by URL and by node.
#include "base/url.hpp"
#include "encodings/parser.hpp"
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

namespace gs::scene {

const SceneTraversal::InlineScene* SceneTraversal::inlineScene(const vrml::Node& inlineNode,
                                                               const std::string& baseUrl) {
  const std::vector<std::string>& urls = mfString(inlineNode, "url");
  if (auto it = inlinesByNode_.find(&inlineNode);
      it != inlinesByNode_.end() && inlineUrlsByNode_[&inlineNode] == urls)
    return it->second.get();
  inlineUrlsByNode_[&inlineNode] = urls;
  std::shared_ptr<InlineScene> result;
  std::string failures;
  for (const std::string& reference : urls) {
    if (reference.empty()) continue;
    const std::string url = base::resolveUrl(baseUrl, reference);
    if (auto it = inlinesByUrl_.find(url); it != inlinesByUrl_.end()) {
      if (it->second->scene) {
        result = it->second;
        break;
      }
      failures += (failures.empty() ? "" : "; ") + url + ": failed before";
      continue;
    }
    auto entry = std::make_shared<InlineScene>();
    entry->url = url;
    vrml::Scene loaded;
    std::string reason;
    if (options_.inlineSource) {
      // Progressive: the scene grows in place while it loads (sceneChanged()); the
      // source applies the rules (net::Loader::world: a remote world, a local file).
      entry->scene = options_.inlineSource(url, baseUrl, reason);
      inlinesByUrl_[url] = entry;
      if (entry->scene) {
        inlineScenesLoaded_.push_back(entry->scene);
        result = entry;
        break;
      }
      failures += (failures.empty() ? "" : "; ") + url + ": " + reason;
      continue;
    }
    // Read whole (a traversal without a session: tests, `encode`), under the same rules.
    base::Fetched got =
        base::fetcherOr(options_.fetcher).fetch(url, baseUrl, base::FetchMode::whole);
    if (!got.ready()) {
      inlinesByUrl_[url] = entry;  // remember the failure
      failures += (failures.empty() ? "" : "; ") + got.error;
      continue;
    }
    vrml::ParseOptions parse;
    parse.fetcher = options_.fetcher;
    loaded = vrml::parseVrml(got.bytes, url, parse);
    if (loaded.rootNodes.empty() && loaded.diagnostics.hasErrors()) {
      const auto& items = loaded.diagnostics.items;
      for (const auto& d : items)
        if (d.severity == vrml::Severity::error) {
          reason = d.message;
          break;
        }
    }
    if (reason.empty()) {
      for (const vrml::Diagnostic& d : loaded.diagnostics.items)
        report(d.severity, d.location, d.message);
      if (loaded.url.empty()) loaded.url = url;
      entry->scene = std::make_shared<vrml::Scene>(std::move(loaded));  // Scripts may edit it
      inlineScenesLoaded_.push_back(entry->scene);
      inlinesByUrl_[url] = entry;
      result = entry;
      break;
    }
    inlinesByUrl_[url] = entry;  // remember the failure
    failures += (failures.empty() ? "" : "; ") + url + ": " + reason;
  }
  if (!result) {
    // An Inline without a url draws nothing, quietly: a Script may set it later.
    if (!failures.empty())
      report(vrml::Severity::warning, inlineNode.location,
             "cannot load Inline (" + failures + "): nothing drawn");
    result = std::make_shared<InlineScene>();
  }
  inlinesByNode_[&inlineNode] = result;
  return result.get();
}

std::shared_ptr<const vrml::Scene> SceneTraversal::loadedInline(
    const vrml::Node& inlineNode) const {
  const auto it = inlinesByNode_.find(&inlineNode);
  return it == inlinesByNode_.end() ? nullptr : it->second->scene;
}

std::vector<SceneTraversal::InlineLoad> SceneTraversal::inlineLoads() const {
  std::vector<InlineLoad> out;
  out.reserve(inlinesByNode_.size());
  for (const auto& [node, entry] : inlinesByNode_) out.push_back({node, entry->scene});
  return out;
}

}  // namespace gs::scene
