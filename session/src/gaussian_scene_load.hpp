// A Gaussian splatting scene file (.ply, .spz, SOG, .splat, glTF, LAS; splats/readers.hpp)
// opened in a session, read in the background so that the thread that draws never waits
// for it, and drawn while it arrives (docs/splats.md, "Opening a scene"):
// - a local file is read a batch at a time on a thread of its own
//   (splats::openGaussianBatches: binary and compressed PLY, .splat, SPZ, SOG, glTF), each batch
//   drawn as it comes; the other formats (LAS, ascii PLY) are read whole there;
// - a remote one is fetched by its own transfer under the loader's rules and limits
//   (Loader::requestFor, up to LoaderOptions::maxResourceBytes); a binary .ply or a
//   .splat is decoded row by row as its bytes arrive (splats::openGaussianRows) and drawn
//   as it grows, a compressed .ply's vertex records too (without SH, the whole file read
//   again once it arrived), an SPZ v4 file's zstd streams and a GLB or .gltf capture's
//   accessors (in its BIN chunk or its buffer files) side by side by range requests, an
//   SOG meta.json's WebP images side by side, each decoded a band of rows at a time, each
//   splat decoded once all its records came
//   (gaussian_columns_fetch.hpp), an SPZ v2/v3 file's gzip data inflated as they come,
//   each splat decoded once its last attribute came (splats::openGaussianStream), the
//   other formats once whole;
// then the whole scene is sorted by importance on a thread of its own, replaces the splats
// drawn, and gets its level-of-detail tree on another thread, as a progressive stream's.
// Private to the session.
#pragma once

#include <atomic>
#include <future>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gaussian_columns_fetch.hpp"
#include "net/loader.hpp"
#include "render/splat_renderer.hpp"
#include "splats/gaussian.hpp"
#include "splats/lod_tree.hpp"
#include "splats/readers.hpp"

namespace gs::session::detail {

class GaussianSceneLoad {
 public:
  /// Starts loading `url` (resolved: a local path, file:// or http(s):// URL) referenced
  /// by `referrer` (empty for the user's own input). `loader` must outlive this.
  GaussianSceneLoad(net::Loader& loader, std::string url, std::string referrer);
  /// Stops the transfer, the reading thread (at its next batch) and a tree build (at its
  /// next check); a whole-file decode or a sort still running ends on its own thread.
  ~GaussianSceneLoad();
  GaussianSceneLoad(const GaussianSceneLoad&) = delete;
  GaussianSceneLoad& operator=(const GaussianSceneLoad&) = delete;

  /// The set the scene's nodes draw: empty until splats arrive; then the splats so far in
  /// file order (`expectedVectors` the scene's count when known); then the whole scene
  /// sorted by importance, then its tree (`lodTree`); on a failure, `loadError` (the
  /// splats that had arrived stay drawn).
  std::shared_ptr<const render::SplatSet> set() const { return set_; }
  /// Moves the load on (on the thread that draws): takes what arrived, attaches it, starts
  /// and attaches the sort and the tree. True when the set changed.
  bool pump();
  /// Whether nothing is left to do: the sorted splats and their tree attached, or a failure.
  bool settled() const { return stage_ == Stage::done; }
  /// Warnings to show once (a tree that could not be built); appended to `out`.
  void drainMessages(std::vector<std::pair<bool, std::string>>& out);
  /// How far it got, for the Streams panel and the progress bars (kind splats): `vectors`
  /// the splats drawn of `expectedVectors` (once the file's head said how many), `bytes`
  /// and `expectedBytes` of a remote file's transfer (a local file's are not counted:
  /// 0 and -1), `stage` "sorting" or "building tree" once every splat is in; `state`
  /// failed with `error` the node's (SplatSet::loadError), stopped when --snapshot-at cut
  /// it (drawn with what arrived), done when settled().
  net::StreamProgress progress() const;

  /// What a reading thread hands over (shared with it: it may outlive the load).
  struct Pipe;

 private:
  /// The whole scene sorted by importance, or why not.
  struct Sorted {
    std::shared_ptr<const splats::GaussianCloud> cloud;
    std::string error;
  };
  using Tree = std::pair<std::shared_ptr<const splats::LodTree>, std::string>;
  enum class Stage { arriving, sorting, tree, done };
  void fail(const std::string& error);
  /// Appends `batch` to the splats drawn while arriving (`total`: the scene's count, 0
  /// when unknown).
  void grow(const splats::GaussianCloud& batch, std::uint64_t total);
  /// Takes a remote scene's bytes: decodes its rows, or keeps them for a whole read.
  bool pumpTransfer();
  /// Whether some of `decoder`'s columns lie in buffer files beside the scene (a .gltf's).
  static bool inBufferFiles(const splats::GaussianColumnDecoder& decoder);
  /// The fetch of `decoder`'s columns of the remote scene of `fileBytes` bytes whose head is
  /// buffer_, or null when the loader's rules refuse a file (the URL, a size past its
  /// limit): the scene is then read whole, which says why.
  std::unique_ptr<GaussianColumnsFetch> fetchColumns(
      std::unique_ptr<splats::GaussianColumnDecoder> decoder, std::uint64_t fileBytes);
  /// Takes a remote scene's columns (columns_) and decodes the splats that came.
  bool pumpColumns();
  /// Feeds a remote scene read as one stream (stream_) the bytes that came (a pump's
  /// share, or all of them when `stopped` by --snapshot-at) and draws the splats decoded;
  /// true when it drew some.
  bool pumpStream(bool stopped);
  /// Cut by --snapshot-at: the splats that arrived are the scene (sorted, given a tree),
  /// or, when none did, the load fails saying why.
  void stopWithWhatArrived();
  /// The scene complete: sorts `cloud` (already sorted when `sorted`) on a thread of its own.
  void arrived(std::shared_ptr<const splats::GaussianCloud> cloud, bool sorted);
  /// `bytes`, a whole remote scene not read by rows, decoded and sorted.
  void decodeWhole(std::string bytes);

  net::Loader& loader_;
  std::string url_, referrer_;
  std::shared_ptr<render::SplatSet> set_ = std::make_shared<render::SplatSet>();
  Stage stage_ = Stage::arriving;
  /// The splats drawn while the scene arrives, in file order (set_->gaussians meanwhile).
  std::shared_ptr<splats::GaussianCloud> growing_;
  std::size_t boundsAt_ = 0;  // growing_'s size when the bounds were last computed
  // A local file: its reading thread's pipe.
  std::shared_ptr<Pipe> pipe_;
  // A remote file: its transfer, the bytes not yet decoded (from byte `bufferStart_`), and
  // its rows' decoder once its head showed one (`wholeRead_` when it will not).
  std::unique_ptr<net::Transfer> transfer_;
  std::string buffer_;
  std::uint64_t bufferStart_ = 0, rowsDecoded_ = 0;
  std::unique_ptr<splats::GaussianRowDecoder> rows_;
  // Or its stream's decoder (SPZ v2/v3), fed the bytes as they come: buffer_'s first
  // `streamFed_` bytes were fed.
  std::unique_ptr<splats::GaussianStreamDecoder> stream_;
  std::size_t streamFed_ = 0;
  // Or its columns' transfers, once its head showed a scene read by columns.
  std::unique_ptr<GaussianColumnsFetch> columns_;
  bool wholeRead_ = false;
  bool stopped_ = false;  // cut by --snapshot-at, drawn with what had arrived
  std::future<Sorted> sort_;
  std::future<Tree> tree_;
  std::shared_ptr<std::atomic<bool>> cancelTree_ = std::make_shared<std::atomic<bool>>(false);
  std::vector<std::pair<bool, std::string>> messages_;
};

}  // namespace gs::session::detail
