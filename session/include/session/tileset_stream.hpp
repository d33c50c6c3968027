// A QNV tileset viewed progressively (issue 13 part 1; docs/tilesets.md): its index is
// fetched whole, then the views that draw it choose bricks and prefixes
// (session/tileset_selection.hpp), fetched as HTTP range requests (or file reads) in
// priority order through the session's net::Loader rules and limits (its --snapshot-at
// byte allowance and stop included), each brick decoded
// incrementally by its own qnv::StreamDecoder. The splat set handed to the renderers holds
// the chosen prefixes one after the other in priority order (ancestors first) and is
// rebuilt whenever vectors arrive or the choice changes. Far interior nodes of a tileset
// with merged levels are drawn by their merged bricks (Gaussian streams fetched whole)
// instead of their region's vectors. Every viewport of a session draws
// the same set: they share one fetch queue and one brick cache. Bricks no view chose are
// dropped, farthest first, when the decoded vectors exceed the memory budget.
// A Gaussian tileset's set gets a level-of-detail tree over its splats once it settles
// (built on a thread of its own), so that each view draws the tree's cut by screen-space
// error (render::SplatSet::lodTree) rather than every chosen splat.
// Runs on the thread that draws; transfers and the tree's build run on their own threads.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "net/loader.hpp"
#include "qnv/decoder.hpp"
#include "qnv/tileset.hpp"
#include "render/splat_renderer.hpp"
#include "session/tileset_selection.hpp"

namespace gs::session {

struct TilesetOptions {
  /// Decoded vectors held at most, in bytes (--tileset-memory MB); 32 bytes a vector (a
  /// Gaussian tileset's splat, a merged brick's: mergedRecords). Merged bricks no view
  /// draws go first, then bricks no view chose.
  std::uint64_t memoryBytes = std::uint64_t{512} << 20;
  /// Screen-space error threshold (TilesetBudget::pixelsPerVector).
  double pixelsPerVector = 1.0;
  /// Brick transfers running at once.
  int parallelFetches = 4;
  /// Merged splats up to which their level-of-detail tree is built at once, on the
  /// drawing thread (a few milliseconds); more (merged levels deep in a big capture:
  /// hundreds of thousands) are drawn as they are until a tree built on a thread of its
  /// own is attached, once the bricks settle.
  std::size_t mergedTreeOnThisThread = 16384;
};

/// Counters for tests, benchmarks and the progress display (all since opening).
struct TilesetStatistics {
  std::uint64_t indexBytes = 0;
  std::uint64_t brickBytes = 0;       // bytes of bricks taken from transfers
  std::uint64_t mergedBytes = 0;      // bytes of merged bricks taken whole
  std::uint64_t requests = 0;         // brick range requests started
  std::uint64_t chosenBricks = 0;     // in the last choice
  std::uint64_t chosenMerged = 0;     // nodes drawn by their merged bricks, in the last choice
  std::uint64_t chosenVectors = 0;    // records of the last choice
  std::uint64_t residentVectors = 0;  // decoded and held now, merged bricks' splats charged too
  /// The most residentVectors has been after any pump (held between frames, after its
  /// eviction); within one pump the bricks that just arrived are counted before eviction.
  std::uint64_t peakResidentVectors = 0;
  std::uint64_t evictedBricks = 0;
  std::uint64_t evictedMerged = 0;  // merged bricks let go (no view drew them)
};

class TilesetStream {
 public:
  /// Starts fetching the index at `indexUrl` (a path, file:// or http(s):// URL, already
  /// resolved; bricks are its siblings "bricks/L/X_Y_Z.qnv") under `loader`'s rules for
  /// `referrer` (empty: the user's own input). `loader` must outlive the stream.
  TilesetStream(net::Loader& loader, std::string indexUrl, std::string referrer,
                TilesetOptions options = {});
  ~TilesetStream();
  TilesetStream(const TilesetStream&) = delete;
  TilesetStream& operator=(const TilesetStream&) = delete;

  /// The set the renderers draw (view-dependent; empty until bricks arrive).
  std::shared_ptr<render::SplatSet> set() const { return set_; }
  /// Takes the index when it arrived, chooses bricks from the views recorded in the set,
  /// (re)starts transfers in priority order, decodes what arrived, drops far bricks over
  /// the memory budget and rebuilds the set. True when the set changed.
  bool pump();
  /// Nothing arriving and nothing more wanted for the views seen so far, or the loader
  /// stopped the loads (net::Loader::stopReason: --snapshot-at's bytes or seconds); and,
  /// for a Gaussian tileset, the level-of-detail tree over the set's splats attached (or
  /// found impossible).
  bool settled() const;
  /// Failures (the index, naming its URL) and warnings (bricks) not returned before;
  /// error = true for failures.
  void drainMessages(std::vector<std::pair<bool, std::string>>& out);
  const std::optional<qnv::TilesetIndex>& index() const { return index_; }
  const TilesetStatistics& statistics() const { return stats_; }
  /// The tileset as one line of the window's Streams panel and the progress bars (kind
  /// qnv): bytes of the index, bricks and merged bricks taken, of the whole tileset's
  /// files (known with the index); bytesPerSecond, the bricks' bytes over the seconds
  /// their transfers ran; vectors (a Gaussian tileset: splats) decoded and held, of the tileset's,
  /// the last choice's as the wanted prefix; `loading` while a transfer runs or a chosen prefix is
  /// missing, `idle` once settled (a new view may ask for more), `stopped` once the loader stopped
  /// the loads, `failed` when the index could not be read (`error`).
  net::StreamProgress progress() const;
  /// The URL of the index.
  const std::string& url() const { return url_; }

 public:
  struct Brick;  // one brick's decoder and what it decoded (tileset_stream.cpp)

 private:
  struct MergedBrick;
  bool takeIndex();
  bool pumpMerged();
  bool viewsChanged() const;
  void choose();
  bool pumpBricks();
  void evict();
  /// options_.memoryBytes in records: 32 bytes a decoded vector; a Gaussian tileset's
  /// splat takes its decoded size and its share of the level-of-detail tree (about 0.4
  /// of that again) for its recordsPerElement() records.
  std::uint64_t memoryRecords() const;
  /// What a decoded merged brick is charged, in the same records: a Gaussian tileset's
  /// merged splat as one of its splats; a vector tileset's (SH degree 2, 152 bytes and its
  /// tree's share) as 7 decoded vectors.
  std::uint64_t mergedRecords(const splats::GaussianCloud& merged) const;
  void rebuild();
  /// The merged set again, when mergedDirty_ (with its own level-of-detail tree).
  void rebuildMerged();
  /// settled() but for the tree: nothing arriving and nothing more wanted.
  bool bricksSettled() const;
  /// A Gaussian tileset: attaches a finished tree to the set when it is still the set's,
  /// and starts one over the set's splats once the bricks have settled. True when attached.
  bool pumpTree();
  /// A tree is being built, or is still to be built for the set's splats.
  bool treePending() const;
  /// The same for the merged set's tree, when it is built on a thread of its own (more
  /// than options_.mergedTreeOnThisThread merged splats).
  bool mergedTreePending() const;
  /// Ends every transfer for good (the loader stopped): what arrived stays drawn.
  void stop();

  net::Loader& loader_;
  std::string url_, referrer_, base_;
  TilesetOptions options_;
  std::shared_ptr<render::SplatSet> set_;
  std::optional<qnv::TilesetIndex> index_;
  std::uint32_t words_ = 1;  // records per element: 1, or a Gaussian splat's
  bool indexFailed_ = false;
  std::vector<Brick> bricks_;
  std::vector<BrickChoice> choice_;
  // Merged levels (docs/tilesets.md, "Merged levels"): per brick, its merged brick once
  // asked for; the bricks the last choice draws merged; the set of their Gaussians.
  std::vector<MergedBrick> merged_;
  std::vector<std::size_t> mergedChoice_;
  std::shared_ptr<render::SplatSet> mergedSet_;
  bool mergedDirty_ = false;  // mergedSet_ is to be assembled again
  std::vector<std::pair<std::uint64_t, render::SplatSet::View>> lastViews_;
  bool dirty_ = false;
  bool stopped_ = false;  // the loader stopped the loads: no transfer starts again
  // progress()'s rate: seconds during which a transfer ran, as seen from pump to pump.
  double activeSeconds_ = 0.0;
  std::chrono::steady_clock::time_point lastPump_{};
  bool transferring_ = false;  // a transfer ran at the end of the last pump
  // The level-of-detail tree of a Gaussian tileset's set: the build running (or done, not
  // yet taken), its cancel flag, and the cloud it is (or was last) built over.
  std::future<std::pair<std::shared_ptr<const splats::LodTree>, std::string>> tree_;
  std::shared_ptr<std::atomic<bool>> cancelTree_;
  std::shared_ptr<const splats::GaussianCloud> treeCloud_;
  // The same for the merged set's tree (merged levels deep enough to hold more than
  // options_.mergedTreeOnThisThread splats).
  std::future<std::pair<std::shared_ptr<const splats::LodTree>, std::string>> mergedTree_;
  std::shared_ptr<std::atomic<bool>> cancelMergedTree_;
  // The merged set a tree was last made (or started) for, and the one the build in
  // flight is for: a build that ends after its set was replaced is not attached.
  std::shared_ptr<const splats::GaussianCloud> mergedTreeCloud_, mergedTreeBuilding_;
  // What a Gaussian tileset's set was last made of (rebuild()): unchanged, it is kept.
  std::vector<std::uint64_t> setMadeOf_;
  TilesetStatistics stats_;
  std::vector<std::pair<bool, std::string>> messages_;
  std::size_t messagesShown_ = 0;
};

}  // namespace gs::session
