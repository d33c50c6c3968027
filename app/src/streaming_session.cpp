#include "app/streaming_session.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>

#include "app/commands.hpp"
#include "app/mesh_input.hpp"
#include "app/splat_inputs.hpp"
#include "app/volume_input.hpp"
#include "app/world.hpp"
#include "render/traversal.hpp"
#include "vrml/parser.hpp"

namespace gs::app {

namespace {

/// The path part of a URL, without query or fragment (for the file extension).
std::string urlPath(const std::string& url) {
  return url.substr(0, url.find_first_of("?#"));
}

bool endsWithNoCase(const std::string& s, const std::string& suffix) {
  if (s.size() < suffix.size()) return false;
  return std::equal(suffix.rbegin(), suffix.rend(), s.rbegin(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) ==
           std::tolower(static_cast<unsigned char>(b));
  });
}

}  // namespace

bool isUrlInput(const std::string& input) {
  return net::isHttpUrl(input);
}

StreamingSession::StreamingSession(net::LoaderOptions options) : loader_(options) {}

StreamingSession::~StreamingSession() = default;

std::shared_ptr<const vrml::Scene> StreamingSession::open(const std::string& input,
                                                          std::string& error) {
  const bool remote = isUrlInput(input);
  const std::string path = remote ? urlPath(input) : render::localPathOfUrl(input);
  if (remote && endsWithNoCase(path, ".qnv")) {
    auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(splatWorldText(input), input));
    localScenes_.push_back(scene);
    return scene;
  }
  if (remote) {
    if (isMeshFile(path) || isVolumeFile(path)) {
      error = input +
              ": meshes and volumes are read from local files; encode them to .qnv "
              "(ghostspace encode) to stream them";
      return nullptr;
    }
    auto stream = loader_.world(input, "", error);
    if (!stream) return nullptr;
    worlds_.push_back(stream);
    return stream->scene();
  }
  if (path.empty()) {
    error = "cannot open '" + input + "': only local files and http(s) URLs can be opened";
    return nullptr;
  }
  if (std::ifstream probe(path, std::ios::binary); !probe) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return nullptr;
  }
  if (isMeshFile(path) || isVolumeFile(path) || isQnvFile(path)) {
    // Read (and for meshes and volumes, encoded) here; a .qnv world streams the file.
    LoadedWorld w = loadWorld(path);
    if (!w.readable) {
      for (const auto& d : w.scene->diagnostics.items) error = d.format();
      return nullptr;
    }
    localScenes_.push_back(w.scene);
    return w.scene;
  }
  auto stream = loader_.world(path, "", error);
  if (!stream) return nullptr;
  worlds_.push_back(stream);
  return stream->scene();
}

std::shared_ptr<const render::SplatSet> StreamingSession::splatSet(const std::string& url,
                                                                   const std::string& referrer,
                                                                   std::string& error) {
  if (!net::mayReference(referrer, url, error)) return nullptr;  // before any cache
  if (auto it = qnv_.find(url); it != qnv_.end()) return it->second.set;
  const std::string path = render::localPathOfUrl(url);
  if (!path.empty() && (isMeshFile(path) || isVolumeFile(path))) {
    return splatLoader()(url, referrer, error);  // encoded whole, here and now
  }
  QnvEntry entry;
  entry.set = std::make_shared<render::SplatSet>();
  render::SplatSet* set = entry.set.get();
  // Each packet's vectors go to their place in stream order (largest first); a lost
  // packet leaves zero-magnitude, transparent vectors.
  auto sink = [set](std::uint64_t first, std::span<const qnv::DecodedVector> v) {
    const std::size_t end = static_cast<std::size_t>(first) + v.size();
    if (first < set->vectors.size()) ++set->revision;  // a gap filled late
    if (set->vectors.size() < end)
      set->vectors.resize(end, qnv::DecodedVector{{}, 0.0f, {0, 0, 1}, 0});
    std::copy(v.begin(), v.end(), set->vectors.begin() + static_cast<std::ptrdiff_t>(first));
  };
  entry.stream = loader_.qnv(url, referrer, std::move(sink), error);
  if (!entry.stream) return nullptr;
  auto result = entry.set;
  qnv_[url] = std::move(entry);
  return result;
}

render::SceneRendererOptions StreamingSession::rendererOptions(render::SceneRendererOptions base) {
  base.traversal.inlineSource = [this](const std::string& url, const std::string& referrer,
                                       std::string& error) -> std::shared_ptr<const vrml::Scene> {
    auto stream = loader_.world(url, referrer, error);
    if (!stream) return nullptr;
    if (std::find(worlds_.begin(), worlds_.end(), stream) == worlds_.end())
      worlds_.push_back(stream);
    return stream->scene();
  };
  base.splatLoader = [this](const std::string& url, const std::string& referrer,
                            std::string& error) { return splatSet(url, referrer, error); };
  base.loader = [this](const std::string& url, std::string& bytes, std::string& error) {
    // Textures load in the background while the scene draws untextured; the renderer
    // has already refused local files for remote worlds.
    if (loader_.fetchInBackground(url, "", bytes, error)) return true;
    if (error.empty()) error = render::kLoadPending;
    return false;
  };
  return base;
}

bool StreamingSession::pump() {
  for (auto& [url, e] : qnv_) e.stream->want(e.set->wantedVectors);
  bool changed = loader_.pump();
  for (auto& [url, e] : qnv_) {
    const auto& header = e.stream->header();
    if (e.haveHeader || !header) continue;
    e.haveHeader = true;
    render::SplatSet& set = *e.set;
    set.style = render::SplatStyle::fromHeader(*header);
    set.expectedVectors = header->vectorCount;
    set.bounds = vrml::Bounds{};
    set.bounds.extend(header->boundsMin);
    set.bounds.extend(header->boundsMax);
    // (The vectors grow geometrically as packets arrive; nothing is reserved from the
    // header's count, which is untrusted.)
    changed = true;
  }
  return changed;
}

void StreamingSession::drainMessages(std::vector<std::pair<bool, std::string>>& out) {
  for (const net::StreamProgress& p : loader_.progress()) {
    if (!p.settled() || p.state == net::StreamState::idle) continue;
    const std::string state = net::toString(p.state);
    if (endShown_[p.url] == state) continue;
    endShown_[p.url] = state;
    if (!p.error.empty()) out.push_back({p.state == net::StreamState::failed, p.error});
  }
  std::vector<const vrml::Scene*> scenes;
  for (const auto& s : localScenes_) scenes.push_back(s.get());
  for (const auto& w : worlds_) scenes.push_back(w->scene().get());
  for (const vrml::Scene* world : scenes) {
    const vrml::Scene& scene = *world;
    std::size_t& shown = diagnosticsShown_[scene.url];
    for (; shown < scene.diagnostics.items.size(); ++shown) {
      const auto& d = scene.diagnostics.items[shown];
      out.push_back({d.severity == vrml::Severity::error, d.format()});
    }
  }
  for (auto& [url, e] : qnv_) {
    const auto& warnings = e.stream->warnings();
    for (; e.warningsShown < warnings.size(); ++e.warningsShown)
      out.push_back({false, warnings[e.warningsShown]});
  }
}

}  // namespace gs::app
