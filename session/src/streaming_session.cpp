#include "session/streaming_session.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>
#include <utility>

#include "base/byte_order.hpp"
#include "base/text.hpp"
#include "base/url.hpp"
#include "encodings/parser.hpp"
#include "formats/input_kind.hpp"
#include "gaussian_scene_load.hpp"
#include "net/transfer.hpp"
#include "session/splat_inputs.hpp"
#include "session/world.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"

namespace gs::session {

StreamingSession::StreamingSession(net::LoaderOptions options) : loader_(options) {}

StreamingSession::~StreamingSession() {
  // A tree still building stops at its next check instead of holding the close up (its
  // future's destructor waits for it): about a millisecond, not seconds per million splats.
  for (auto& [url, e] : qnv_) e.cancelTree->store(true);
}

bool StreamingSession::remoteIsGaussian(const std::string& url, bool tileset) {
  std::string error;
  if (!splatSet(url, "", error)) return false;  // the world's node asks again and says why
  for (;;) {
    loader_.pump();
    if (tileset) {
      TilesetStream& t = *tilesets_.at(url);
      t.pump();
      if (const auto& index = t.index()) return index->header.kind == qnv::StreamKind::gaussian;
      if (t.settled()) return false;  // the index failed: the stream says why
    } else {
      const QnvEntry& e = qnv_.at(url);
      if (const auto& header = e.stream->header()) return header->kind == qnv::StreamKind::gaussian;
      if (loader_.settled()) return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

bool StreamingSession::remoteIsCapture(const std::string& url, formats::InputKind kind,
                                       std::string& error) {
  net::FetchRequest request = loader_.requestFor(url, "", error);
  if (request.url.empty()) return false;
  constexpr std::uint64_t kHead = 65536;  // a 3DGS header is about 1.5 KB, a capture's glTF
                                          // JSON a few KB
  request.offset = 0;
  request.length = kHead;
  const std::unique_ptr<net::Transfer> transfer = net::startTransfer(std::move(request));
  std::string head;
  // Whether the head holds what decides: a PLY's header, a GLB's whole JSON chunk.
  const auto enough = [&] {
    if (kind == formats::InputKind::ply) return head.find("end_header") != std::string::npos;
    return head.size() >= 20 && head.starts_with("glTF") &&
           head.size() - 20 >= base::loadLe<std::uint32_t>(head.data() + 12);
  };
  for (;;) {
    const net::TransferStatus status = transfer->status();
    transfer->take(head);
    if (status.finished() && status.state != net::TransferState::done && head.empty()) {
      error = status.error;
      return false;
    }
    if (status.finished() || head.size() >= kHead || enough()) break;
    transfer->wait(0.05);
  }
  transfer->cancel();
  if (kind == formats::InputKind::ply)
    return formats::kindFromContent(head) == formats::InputKind::gaussianSplats;
  return splats::gltfDrawsOnlyGaussians(head);
}

std::shared_ptr<const vrml::Scene> StreamingSession::inputWorld(const std::string& input,
                                                                bool& handled, std::string& error) {
  handled = true;
  if (const std::string index = tilesetIndexOf(input); !index.empty()) {
    // A world of one QNV node naming the index; a local one names it by its file name
    // (the world's url is the index itself, so the name resolves to it).
    const bool remote = base::isHttpUrl(index);
    const std::string name = remote ? index : std::filesystem::path(index).filename().string();
    // A tileset of Gaussians is a capture: turned as its scene file is.
    const bool gaussian = remote ? remoteIsGaussian(index, true)
                                 : isGaussianTilesetIndex(base::localPathOfUrl(index));
    const std::string text = gaussian ? gaussianWorldText(name, true) : splatWorldText(name);
    auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(text, index));
    localScenes_.push_back(scene);
    return scene;
  }
  if (base::isHttpUrl(input)) {
    // Nothing has arrived yet: the name decides (a world when it says nothing).
    formats::InputKind kind = formats::kindFromName(input);
    // A .ply may be a mesh or a capture, a glTF a world or a capture: its head says which.
    if (kind == formats::InputKind::ply || kind == formats::InputKind::gltf) {
      if (remoteIsCapture(input, kind, error)) {
        remoteCaptures_.insert(input);
        kind = formats::InputKind::gaussianSplats;
      } else if (!error.empty()) {
        return nullptr;  // it could not be fetched: why
      }
    }
    if (kind == formats::InputKind::qnv || kind == formats::InputKind::gaussianSplats) {
      // A QNV stream, or a splat scene read whole (StreamingSession::splatSet); a LAS
      // point cloud is z up already, a capture is turned (docs/splats.md, "Axes").
      // A QNV stream of Gaussians is a capture too: its header's kind byte decides.
      const std::string text =
          kind == formats::InputKind::qnv
              ? (remoteIsGaussian(input, false) ? gaussianWorldText(input, true)
                                                : splatWorldText(input))
              : gaussianWorldText(input, !(base::endsWithNoCase(input, ".las") ||
                                           base::endsWithNoCase(input, ".laz")));
      auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(text, input));
      localScenes_.push_back(scene);
      return scene;
    }
    if ((formats::isMesh(kind) && kind != formats::InputKind::gltf) || formats::isVolume(kind)) {
      error = input +
              ": meshes and volumes are read from local files; encode them to .qnv "
              "(ghostspace encode) to stream them";
      return nullptr;
    }
    handled = false;
    return nullptr;
  }
  const std::string path = base::localPathOfUrl(input);
  if (path.empty() || !std::ifstream(path, std::ios::binary)) {
    handled = false;  // the caller says why
    return nullptr;
  }
  if (const std::string why = unsupportedFormat(path); !why.empty()) {
    error = path + ": " + why;
    return nullptr;
  }
  if (!isSplatInput(path)) {
    handled = false;
    return nullptr;
  }
  // Read (and for meshes and volumes, encoded) here; a .qnv world streams the file.
  LoadedWorld w = loadWorld(path);
  if (!w.readable) {
    for (const auto& d : w.scene->diagnostics.items) error = d.format();
    return nullptr;
  }
  localScenes_.push_back(w.scene);
  return w.scene;
}

std::shared_ptr<const vrml::Scene> StreamingSession::open(const std::string& input,
                                                          std::string& error) {
  bool handled = false;
  if (auto scene = inputWorld(input, handled, error); handled) return scene;
  const bool remote = base::isHttpUrl(input);
  const std::string path = remote ? input : base::localPathOfUrl(input);
  if (path.empty()) {
    error = "cannot open '" + input + "': only local files and http(s) URLs can be opened";
    return nullptr;
  }
  if (std::ifstream probe(path, std::ios::binary); !remote && !probe) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return nullptr;
  }
  auto stream = loader_.world(path, "", error);
  if (!stream) return nullptr;
  worlds_.push_back(stream);
  return stream->scene();
}

std::shared_ptr<const render::SplatSet> StreamingSession::splatSet(const std::string& url,
                                                                   const std::string& referrer,
                                                                   std::string& error) {
  if (!base::mayReference(referrer, url, error)) return nullptr;  // before any cache
  if (auto it = qnv_.find(url); it != qnv_.end()) return it->second.set;
  if (auto it = gaussians_.find(url); it != gaussians_.end()) return it->second->set();
  if (auto it = tilesets_.find(url); it != tilesets_.end()) return it->second->set();
  if (const std::string index = tilesetIndexOf(url); !index.empty()) {
    auto& tileset = tilesets_[url];
    tileset = std::make_unique<TilesetStream>(loader_, index, referrer, tilesetOptions_);
    return tileset->set();
  }
  const std::string path = base::localPathOfUrl(url);
  const formats::InputKind kind =
      path.empty() ? formats::InputKind::unknown : formats::classifyFile(path);
  // A remote glTF asked for by a splat node is a Gaussian splatting scene (the glTF
  // importer's GaussianSplats node names its own asset): no glTF is a QNV stream.
  const formats::InputKind named = formats::kindFromName(url);
  if ((path.empty() && (named == formats::InputKind::gaussianSplats ||
                        named == formats::InputKind::gltf || remoteCaptures_.count(url) > 0)) ||
      (!path.empty() && kind != formats::InputKind::qnv && isGaussianSplatFile(path))) {
    // A Gaussian splatting scene: read whole in the background (local or HTTP, under the
    // loader's rules); its set is empty until then, and says why if it fails.
    auto& load = gaussians_[url];
    load = std::make_unique<detail::GaussianSceneLoad>(loader_, url, referrer);
    return load->set();
  }
  if (formats::isMesh(kind) || formats::isVolume(kind)) {
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
  // A Gaussian stream (splats/qnv_gaussians.hpp): each packet's splats at their place in
  // stream order (largest first), as for vectors.
  entry.gaussians = std::make_shared<splats::GaussianCloud>();
  entry.stream->setRecordSink([cloud = entry.gaussians, stream = entry.stream.get(), set](
                                  std::uint64_t first, std::span<const std::uint64_t> records) {
    if (splats::placeGaussianRecords(*stream->header(), first, records, *cloud))
      ++set->revision;  // a gap filled late
  });
  auto result = entry.set;
  qnv_[url] = std::move(entry);
  return result;
}

render::SceneRendererOptions StreamingSession::rendererOptions(render::SceneRendererOptions base) {
  base.traversal.inlineSource = [this](const std::string& url, const std::string& referrer,
                                       std::string& error) -> std::shared_ptr<const vrml::Scene> {
    // An Inline opens every file a session opens (X3D 4.0 clause 9.4.2 lets it load what
    // the browser reads): a capture, a QNV stream or tileset, a mesh or a volume is the
    // world open() makes of it, placed where the Inline is; only what the referrer may
    // reference (a remote world never reads local files).
    if (!base::mayReference(referrer, url, error)) return nullptr;
    if (auto it = inlineInputs_.find(url); it != inlineInputs_.end()) return it->second;
    bool handled = false;
    if (auto scene = inputWorld(url, handled, error); handled) {
      if (scene) inlineInputs_[url] = scene;
      return scene;
    }
    auto stream = loader_.world(url, referrer, error);
    if (!stream) return nullptr;
    if (std::find(worlds_.begin(), worlds_.end(), stream) == worlds_.end())
      worlds_.push_back(stream);
    return stream->scene();
  };
  base.splatLoader = [this](const std::string& url, const std::string& referrer,
                            std::string& error) { return splatSet(url, referrer, error); };
  // Textures, movies and panoramas load in the background while the scene draws without
  // them, under the loader's rules.
  base.fetcher = &loader_;
  return base;
}

bool StreamingSession::pump() {
  for (auto& [url, e] : qnv_) {
    const auto& header = e.stream->header();
    e.stream->want(e.set->wantedVectors * (header ? header->recordsPerElement() : 1u));
  }
  bool changed = loader_.pump();
  for (auto& [url, t] : tilesets_) changed |= t->pump();
  for (auto& [url, e] : qnv_) {
    const auto& header = e.stream->header();
    if (e.haveHeader || !header) continue;
    e.haveHeader = true;
    render::SplatSet& set = *e.set;
    set.style = render::SplatStyle::fromHeader(*header);
    set.expectedVectors = header->vectorCount / header->recordsPerElement();
    if (header->kind == qnv::StreamKind::gaussian) set.gaussians = e.gaussians;
    set.bounds = vrml::Bounds{};
    set.bounds.extend(header->boundsMin);
    set.bounds.extend(header->boundsMax);
    // (The vectors grow geometrically as packets arrive; nothing is reserved from the
    // header's count, which is untrusted.)
    changed = true;
  }
  for (auto& [url, e] : qnv_) changed |= pumpTree(e);
  for (auto& [url, g] : gaussians_) changed |= g->pump();
  return changed;
}

namespace {

/// Whether a stream in `state` has ended: nothing more arrives (net::QnvStream).
bool ended(net::StreamState state) {
  return state == net::StreamState::done || state == net::StreamState::stopped ||
         state == net::StreamState::failed;
}

}  // namespace

bool StreamingSession::wantsTree(const QnvEntry& e) {
  const auto& header = e.stream->header();
  if (!header || header->kind != qnv::StreamKind::gaussian || e.tree.valid()) return false;
  const std::size_t n = e.gaussians->size();
  if (n == 0) return false;
  // A packet that filled a gap after the last build (while resting or ended).
  const bool gapFilled = e.treeSplats > 0 && e.set->revision != e.treeRevision;
  // Ended (whole, stopped or failed: nothing more comes): a tree over every splat.
  if (ended(e.stream->progress().state)) return n != e.treeSplats || gapFilled;
  // Resting at the prefix its views asked for: a first tree, then one each time a view's
  // larger prefix has grown the splats by a quarter (so that a slider dragged up does not
  // build a tree at each step); arriving: one each time the splats have doubled.
  if (e.stream->progress().settled())
    return e.treeSplats == 0 || 4 * n >= 5 * e.treeSplats || gapFilled;
  return n >= std::max<std::size_t>(1024, 2 * e.treeSplats);
}

bool StreamingSession::pumpTree(QnvEntry& e) {
  bool changed = false;
  if (e.tree.valid()) {
    if (e.tree.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
    auto [tree, problem] = e.tree.get();
    e.treeProblem = problem.empty() ? "" : problem + ": far views draw a prefix of the stream";
    if (tree) {
      // (A gap filled while it was built leaves the tree stale: its revision moved on.)
      const bool current = e.set->revision == e.treeRevision;
      e.set->lodTree = std::move(tree);
      ++e.set->revision;
      if (current) e.treeRevision = e.set->revision;
      changed = true;
    }
  }
  if (!wantsTree(e)) return changed;
  e.treeSplats = e.gaussians->size();
  e.treeRevision = e.set->revision;
  // A stream that has ended changes no more (QnvStream::pump does nothing once it is
  // done, stopped or failed): the tree's thread reads its cloud. One that may grow (its
  // record sink appends on this thread) gives it a copy of its prefix.
  std::shared_ptr<const splats::GaussianCloud> cloud =
      ended(e.stream->progress().state)
          ? std::shared_ptr<const splats::GaussianCloud>(e.gaussians)
          : std::make_shared<const splats::GaussianCloud>(*e.gaussians);
  e.tree = std::async(std::launch::async, buildTreeOf, std::move(cloud), e.cancelTree,
                      e.stream->progress().url);
  return changed;
}

bool StreamingSession::settled() const {
  if (!loader_.settled()) return false;
  for (const auto& [url, e] : qnv_)
    // A tree being built, or built and not yet attached, or one to build.
    if (e.tree.valid() || wantsTree(e)) return false;
  for (const auto& [url, t] : tilesets_)
    if (!t->settled()) return false;
  for (const auto& [url, g] : gaussians_)
    if (!g->settled()) return false;
  return true;
}

runtime::UrlLoadState StreamingSession::worldLoadState(const vrml::Scene& scene) const {
  for (const auto& w : worlds_) {
    if (w->scene().get() != &scene) continue;
    switch (w->progress().state) {
      case net::StreamState::done:
        return runtime::UrlLoadState::loaded;
      case net::StreamState::failed:
      case net::StreamState::stopped:
        return runtime::UrlLoadState::failed;
      default:
        return runtime::UrlLoadState::loading;
    }
  }
  return runtime::UrlLoadState::loaded;
}

void StreamingSession::abandonWorld(const vrml::Scene& scene, const std::string& why) {
  for (const auto& w : worlds_)
    if (w->scene().get() == &scene) w->abandon(why);
}

std::vector<const TilesetStream*> StreamingSession::tilesets() const {
  std::vector<const TilesetStream*> out;
  for (const auto& [url, t] : tilesets_) out.push_back(t.get());
  return out;
}

std::vector<net::StreamProgress> StreamingSession::progress() const {
  std::vector<net::StreamProgress> out = loader_.progress();
  for (const auto& [url, t] : tilesets_) out.push_back(t->progress());
  for (const auto& [url, g] : gaussians_) out.push_back(g->progress());
  return out;
}

void StreamingSession::drainMessages(std::vector<std::pair<bool, std::string>>& out) {
  for (auto& [url, t] : tilesets_) t->drainMessages(out);
  for (auto& [url, g] : gaussians_) g->drainMessages(out);
  // A stream that ends short says so in its decoder's warnings, shown below: its end
  // message repeats the last of them and is not shown twice.
  const auto warned = [this](const std::string& message) {
    for (const auto& [url, e] : qnv_) {
      const auto& w = e.stream->warnings();
      if (std::find(w.begin(), w.end(), message) != w.end()) return true;
    }
    return false;
  };
  for (const net::StreamProgress& p : loader_.progress()) {
    if (!p.settled() || p.state == net::StreamState::idle) continue;
    const std::string state = net::toString(p.state);
    if (endShown_[p.url] == state) continue;
    endShown_[p.url] = state;
    if (!p.error.empty() && (p.state == net::StreamState::failed || !warned(p.error)))
      out.push_back({p.state == net::StreamState::failed, p.error});
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
    if (!e.treeProblem.empty()) out.push_back({false, std::exchange(e.treeProblem, {})});
  }
}

}  // namespace gs::session
