// The progressive loading of one session (window or snapshot), docs/progressive-loading.md:
// a net::Loader wired to the renderers. Worlds (.wrl, .wrl.gz) grow node by node, Inline
// worlds load in parallel and grow the same way, QNV streams fill their splat sets
// packet by packet and fetch (by HTTP range requests) only the prefix the views draw.
// Everything runs on the thread that draws; transfers run on their own threads.
#pragma once

#include <atomic>
#include <future>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "formats/input_kind.hpp"
#include "net/loader.hpp"
#include "render/scene_renderer.hpp"
#include "runtime/execution_model.hpp"
#include "session/splat_inputs.hpp"
#include "session/tileset_stream.hpp"
#include "splats/gaussian.hpp"
#include "splats/lod_tree.hpp"
#include "vrml/scene.hpp"

namespace gs::session {

namespace detail {
class GaussianSceneLoad;  // session/src/gaussian_scene_load.hpp
}

class StreamingSession {
 public:
  explicit StreamingSession(net::LoaderOptions options = {});
  ~StreamingSession();
  StreamingSession(const StreamingSession&) = delete;
  StreamingSession& operator=(const StreamingSession&) = delete;

  /// Opens the user's input: a VRML97 world (path or http(s):// URL; streamed), a .qnv
  /// stream or a QNV tileset (its folder or index.qnvt, path or URL; tilesetIndexOf) (a
  /// world of one QuantizedNormalVectors node that streams it), or
  /// a local mesh or volume (read and encoded now, session/splat_inputs.hpp); local inputs
  /// are classified by formats::classifyFile, URLs by their name. The scene
  /// returned grows as pump() runs. Returns null with `error` ("cannot open 'x': ...")
  /// when nothing can be shown at all.
  std::shared_ptr<const vrml::Scene> open(const std::string& input, std::string& error);

  /// `base` with its loaders wired to this session: Inline worlds and QNV urls stream
  /// through the loader (content from the network may reference only http(s) URLs);
  /// textures and EXTERNPROTOs are fetched whole.
  render::SceneRendererOptions rendererOptions(render::SceneRendererOptions base);

  /// Tells each QNV stream the prefix its views asked for (SplatSet::wantedVectors),
  /// then moves what arrived into parsers and decoders. A Gaussian stream gets a
  /// level-of-detail tree (splats/lod_tree.hpp; built on a thread of its own, about 1.5 s
  /// per million splats, and attached at a later pump) over what has arrived, so that far
  /// views draw a cut of merged Gaussians as a capture read whole does: over every splat
  /// once the stream has ended (whole, stopped or failed); when it rests at the prefix its
  /// views asked for, a first tree, then another each time a larger prefix has grown the
  /// splats by a quarter; while it arrives, each time its splats have doubled (from
  /// 1,024), so that the builds of a stream cost a few times its last; again after a gap
  /// filled late. The splats after a tree's prefix are drawn whole, up to each view's
  /// budget, until the next tree (SplatSet::lodTree). Returns true when a scene or a splat
  /// set changed: call SceneRenderer::sceneChanged() on the renderers.
  bool pump();
  /// Whether nothing is arriving, nothing more was asked for, no tree is being built and
  /// none is due by pump()'s rule (an ended stream's tree covers all its splats), and
  /// every Gaussian splatting scene file has been read (or failed) and has its tree.
  bool settled() const;
  /// How far the loading of `scene` got, for X3D LoadSensors watching an Inline
  /// (runtime::ExecutionModel::setUrlObjectState): a world this session streams is loaded
  /// once its stream is done (its whole text parsed), failed when the stream failed or was
  /// stopped (--snapshot-at), loading before; a world it does not stream (read whole) is
  /// loaded.
  runtime::UrlLoadState worldLoadState(const vrml::Scene& scene) const;
  /// A Script replaced world `scene` (Browser.replaceWorld): its stream, if it still
  /// arrives, ends and adds nothing more (net::WorldStream::abandon), saying `why`.
  void abandonWorld(const vrml::Scene& scene, const std::string& why);
  /// Whether `input`, opened by open(), is shown as splats in a world made for it, with
  /// no Viewpoint of its own (to be framed whole): a local one by isSplatInput, a remote
  /// .ply or glTF once its head showed a capture (remoteIsCapture).
  bool opensAsSplats(const std::string& input) const {
    return isSplatInput(input) || remoteCaptures_.count(input) > 0;
  }
  /// Options of the tilesets opened from now on (--tileset-memory).
  void setTilesetOptions(const TilesetOptions& options) { tilesetOptions_ = options; }
  /// Every tileset opened, in URL order (statistics for tests and the progress display).
  std::vector<const TilesetStream*> tilesets() const;
  /// Every stream of the loader (net::Loader::progress), then every tileset
  /// (TilesetStream::progress), then every Gaussian splatting scene file (.ply, .spz,
  /// SOG, ...; StreamKind::splats, local or remote): what the Streams panel and the progress bars
  /// show.
  std::vector<net::StreamProgress> progress() const;
  net::Loader& loader() { return loader_; }
  const net::Loader& loader() const { return loader_; }

  /// Problems to show the user, each once: stream failures and stops (naming the URL),
  /// the parse diagnostics of every world streamed, decoder warnings. Appends the lines
  /// not returned before to `out` (error = true for failures and errors).
  void drainMessages(std::vector<std::pair<bool, std::string>>& out);

 private:
  /// What an input that is no VRML world opens as: a QNV tileset or stream, a Gaussian
  /// splatting scene, a mesh or a volume, each a world of one node showing it (local files
  /// by content, URLs by name). `handled` false when `input` is a world (or a local file
  /// that cannot be read: the caller says why); true with null and `error` when it is no
  /// world and cannot be shown.
  std::shared_ptr<const vrml::Scene> inputWorld(const std::string& input, bool& handled,
                                                std::string& error);
  std::shared_ptr<const render::SplatSet> splatSet(const std::string& url,
                                                   const std::string& referrer, std::string& error);
  /// Whether the remote QNV stream (or, `tileset`, the tileset index) `url` holds
  /// Gaussians: its stream is opened (splatSet, the one the world's node then draws) and
  /// the loader pumped until its header (or index) arrives or it fails (false; its own
  /// messages say why), bounded by the transfer's connect and stall timeouts. Called
  /// before the world naming it is made, so a capture streamed over HTTP is turned as a
  /// local one (docs/splats.md, "Opening a scene"); no byte is fetched twice.
  bool remoteIsGaussian(const std::string& url, bool tileset);
  /// Whether the remote .ply or glTF `url` (`kind` ply or gltf, by its name) is a 3D
  /// Gaussian splatting capture, not a mesh or a glTF world: its first 64 KiB at most are
  /// fetched (one range request, until a PLY's end_header or a GLB's whole JSON chunk
  /// arrives) and classified by content (formats::kindFromContent;
  /// splats::gltfDrawsOnlyGaussians: a glTF of other primitives too is a world, whose
  /// importer draws its splats by a GaussianSplats node). False with `error` (naming the
  /// URL: "http://h/x.ply: HTTP 404 Not Found") when it cannot be fetched.
  bool remoteIsCapture(const std::string& url, formats::InputKind kind, std::string& error);
  /// Remote .ply and glTF URLs found to be captures (remoteIsCapture): splat scenes.
  std::set<std::string> remoteCaptures_;
  net::Loader loader_;
  struct QnvEntry {
    std::shared_ptr<net::QnvStream> stream;
    std::shared_ptr<render::SplatSet> set;
    /// A Gaussian stream's splats as they arrive (set->gaussians once the header says so).
    std::shared_ptr<splats::GaussianCloud> gaussians;
    /// Its level-of-detail tree being built on a thread of its own (over the splats that
    /// had arrived), then set->lodTree; or, when the build failed, why (shown once as a
    /// warning: the stream is then drawn by its prefix). Neither when cancelled.
    std::future<std::pair<std::shared_ptr<const splats::LodTree>, std::string>> tree;
    std::string treeProblem;  // a failed build's warning, not yet drained
    /// Set when the session closes: the build stops (LodTreeOptions::cancel).
    std::shared_ptr<std::atomic<bool>> cancelTree = std::make_shared<std::atomic<bool>>(false);
    /// The splats the last build started over (0 before any), and set->revision then: a
    /// gap filled late after it (the revision moved) makes the tree stale.
    std::size_t treeSplats = 0;
    std::uint64_t treeRevision = 0;
    bool haveHeader = false;
    std::size_t warningsShown = 0;
  };
  std::map<std::string, QnvEntry> qnv_;
  /// pump()'s step for one stream's tree: attaches a tree built (true then: the set
  /// changed), starts a build when wantsTree.
  bool pumpTree(QnvEntry& e);
  /// Whether a Gaussian stream, no tree being built for it, needs one (pump()'s rule).
  static bool wantsTree(const QnvEntry& e);
  /// Gaussian splatting scenes, each read whole in the background, by URL.
  std::map<std::string, std::unique_ptr<detail::GaussianSceneLoad>> gaussians_;
  TilesetOptions tilesetOptions_;
  std::map<std::string, std::unique_ptr<TilesetStream>> tilesets_;  // by index URL
  std::vector<std::shared_ptr<net::WorldStream>> worlds_;           // every world streamed
  std::map<std::string, std::size_t> diagnosticsShown_;             // per world url
  std::map<std::string, std::string> endShown_;                     // url -> state shown
  std::vector<std::shared_ptr<const vrml::Scene>> localScenes_;
  std::map<std::string, std::shared_ptr<const vrml::Scene>> inlineInputs_;  // by URL
};

}  // namespace gs::session
