// A Gaussian splatting scene file (.ply, .spz, SOG, .splat, glTF, LAS; splats/readers.hpp)
// opened in a session, read in the background so that the thread that draws never waits
// for it (docs/splats.md, "Opening a scene"): a local file is read, decoded and sorted by
// importance on a thread of its own; a remote one is fetched by the loader without
// blocking (Loader::takeInBackground, up to LoaderOptions::maxResourceBytes) and then
// decoded the same way. Its level-of-detail tree is then built on another thread, as a
// progressive stream's is. Private to the session.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "net/loader.hpp"
#include "render/splat_renderer.hpp"
#include "splats/gaussian.hpp"
#include "splats/lod_tree.hpp"

namespace gs::session::detail {

class GaussianSceneLoad {
 public:
  /// Starts loading `url` (resolved: a local path, file:// or http(s):// URL) referenced
  /// by `referrer` (empty for the user's own input). `loader` must outlive this.
  GaussianSceneLoad(net::Loader& loader, std::string url, std::string referrer);
  /// Stops a tree build at its next check; a decode still running ends on its own thread.
  ~GaussianSceneLoad();
  GaussianSceneLoad(const GaussianSceneLoad&) = delete;
  GaussianSceneLoad& operator=(const GaussianSceneLoad&) = delete;

  /// The set the scene's nodes draw: empty until the splats arrive (then `gaussians`,
  /// bounds and a new revision), then its tree (`lodTree`); on a failure, `loadError`.
  std::shared_ptr<const render::SplatSet> set() const { return set_; }
  /// Moves the load on (on the thread that draws): takes the fetched bytes, attaches the
  /// decoded splats, starts and attaches the tree. True when the set changed.
  bool pump();
  /// Whether nothing is left to do: the splats and their tree attached, or a failure.
  bool settled() const { return stage_ == Stage::done; }
  /// Warnings to show once (a tree that could not be built); appended to `out`.
  void drainMessages(std::vector<std::pair<bool, std::string>>& out);

 private:
  /// A decode's result: the splats sorted by importance, or why not.
  struct Decoded {
    std::shared_ptr<const splats::GaussianCloud> cloud;
    std::string error;
  };
  using Tree = std::pair<std::shared_ptr<const splats::LodTree>, std::string>;
  enum class Stage { fetching, decoding, tree, done };
  void fail(const std::string& error);

  net::Loader& loader_;
  std::string url_, referrer_;
  std::shared_ptr<render::SplatSet> set_ = std::make_shared<render::SplatSet>();
  Stage stage_ = Stage::fetching;
  std::future<Decoded> decode_;
  std::future<Tree> tree_;
  std::shared_ptr<std::atomic<bool>> cancelTree_ = std::make_shared<std::atomic<bool>>(false);
  std::vector<std::pair<bool, std::string>> messages_;
};

}  // namespace gs::session::detail
