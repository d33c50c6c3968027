#include "session/tileset_stream.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>

#include "base/url.hpp"
#include "scene/camera.hpp"
#include "session/splat_inputs.hpp"
#include "splats/qnv_gaussians.hpp"

namespace gs::session {

struct TilesetStream::Brick {
  std::unique_ptr<qnv::StreamDecoder> decoder;
  std::vector<qnv::DecodedVector> vectors;  // in brick order (largest first)
  /// A Gaussian tileset's brick: its splats in brick order (opacity 0 where a packet has
  /// not arrived), instead of `vectors`.
  std::shared_ptr<splats::GaussianCloud> splats;
  std::uint64_t fed = 0;  // bytes given to the decoder, from offset 0
  std::unique_ptr<net::Transfer> transfer;
  std::uint64_t transferEnd = 0;    // end of the bytes the running transfer asked for
  std::uint64_t wantedBytes = 0;    // end of the prefix chosen (0: not chosen)
  std::uint64_t wantedRecords = 0;  // records of that prefix
  /// Vectors past the chosen prefix were dropped (evict()): `fed` counts the bytes kept,
  /// and the next transfer starts again from offset 0 with a new decoder.
  bool trimmed = false;
  double priority = 0.0;  // in the last choice it was in
  bool failed = false;
  std::size_t warningsShown = 0;
};

struct TilesetStream::MergedBrick {
  std::unique_ptr<net::Transfer> transfer;
  std::string bytes;
  std::shared_ptr<const splats::GaussianCloud> cloud;  // once decoded
  bool failed = false;
};

namespace {

// Whether brick `a` lies above brick `b` in the octree.
bool isAncestor(const qnv::TilesetBrick& a, const qnv::TilesetBrick& b) {
  if (a.level >= b.level) return false;
  const unsigned d = b.level - a.level;
  return (b.x >> d) == a.x && (b.y >> d) == a.y && (b.z >> d) == a.z;
}

bool sameView(const render::SplatSet::View& a, const render::SplatSet::View& b) {
  return a.camera.position == b.camera.position && a.camera.orientation == b.camera.orientation &&
         a.camera.fieldOfView == b.camera.fieldOfView && a.camera.nearClip == b.camera.nearClip &&
         a.model == b.model && a.aspect == b.aspect && a.heightPixels == b.heightPixels &&
         a.vectors == b.vectors;
}

// Records a brick holds decoded (a Gaussian splat counts its recordsPerElement()).
std::uint64_t heldRecords(const TilesetStream::Brick& b, std::uint32_t words) {
  return b.splats ? std::uint64_t{b.splats->size()} * words : b.vectors.size();
}

TilesetView tilesetView(const render::SplatSet::View& v) {
  TilesetView t;
  t.position = v.camera.position;
  t.forward = v.camera.forward();
  t.up = v.camera.up();
  t.aspect = v.aspect;
  t.verticalFov = scene::verticalFieldOfView(v.camera.fieldOfView, v.aspect);
  t.heightPixels = v.heightPixels > 0 ? v.heightPixels : 512;
  t.nearClip = v.camera.nearClip;
  t.model = v.model;
  return t;
}

}  // namespace

TilesetStream::TilesetStream(net::Loader& loader, std::string indexUrl, std::string referrer,
                             TilesetOptions options)
    : loader_(loader),
      url_(std::move(indexUrl)),
      referrer_(std::move(referrer)),
      options_(options),
      set_(std::make_shared<render::SplatSet>()),
      mergedSet_(std::make_shared<render::SplatSet>()) {
  set_->viewDependent = true;
  mergedSet_->gaussians = std::make_shared<splats::GaussianCloud>();
  set_->merged = mergedSet_;
  takeIndex();  // starts the fetch
}

TilesetStream::~TilesetStream() {
  if (cancelTree_) cancelTree_->store(true);  // the future's destructor waits for its end
  if (cancelMergedTree_) cancelMergedTree_->store(true);
}

bool TilesetStream::takeIndex() {
  if (index_ || indexFailed_) return false;
  std::string bytes, error;
  if (!loader_.fetchInBackground(url_, referrer_, bytes, error)) {
    if (!error.empty()) {
      indexFailed_ = true;
      messages_.push_back({true, error});
    }
    return false;
  }
  stats_.indexBytes = bytes.size();
  loader_.grant(bytes.size());  // counted as the streams' bytes are; taken whole
  index_ = qnv::parseTilesetIndex(bytes, url_, error);
  if (!index_) {
    indexFailed_ = true;
    messages_.push_back({true, error});
    return false;
  }
  bricks_.resize(index_->bricks.size());
  merged_.resize(index_->bricks.size());
  render::SplatSet& set = *set_;
  set.style = render::SplatStyle::fromHeader(index_->header);
  words_ = index_->header.recordsPerElement();
  set.expectedVectors = index_->header.vectorCount / words_;  // splats, for a Gaussian one
  set.bounds = vrml::Bounds{};
  set.bounds.extend(index_->header.boundsMin);
  set.bounds.extend(index_->header.boundsMax);
  ++set.revision;
  return true;
}

bool TilesetStream::viewsChanged() const {
  const auto& views = set_->viewRequests->views();
  return views.size() != lastViews_.size() ||
         !std::equal(views.begin(), views.end(), lastViews_.begin(),
                     [](const auto& a, const auto& b) {
                       return a.first == b.first && sameView(a.second, b.second);
                     });
}

void TilesetStream::choose() {
  if (!viewsChanged()) return;
  const auto& requested = set_->viewRequests->views();
  const std::vector<std::pair<std::uint64_t, render::SplatSet::View>> views(requested.begin(),
                                                                            requested.end());
  lastViews_ = views;
  std::vector<std::vector<BrickChoice>> perView;
  TilesetBudget budget;
  budget.memoryVectors = memoryRecords();
  budget.pixelsPerVector = options_.pixelsPerVector;
  std::vector<TilesetView> tilesetViews;
  for (const auto& [key, view] : views) tilesetViews.push_back(tilesetView(view));
  std::vector<std::uint8_t> unavailable(merged_.size(), 0);
  for (std::size_t i = 0; i < merged_.size(); ++i) unavailable[i] = merged_[i].failed;
  const MergedChoice mergedChoice = chooseMerged(*index_, tilesetViews, kMergedPixels, unavailable);
  if (mergedChoice.merged != mergedChoice_) {  // else the merged set stays as it is
    mergedChoice_ = mergedChoice.merged;
    mergedDirty_ = true;
  }
  for (std::size_t v = 0; v < views.size(); ++v) {
    budget.vectors = views[v].second.vectors > UINT64_MAX / words_
                         ? UINT64_MAX
                         : views[v].second.vectors * words_;
    perView.push_back(selectBricks(*index_, tilesetViews[v], budget, mergedChoice.skip));
  }
  choice_ = mergeChoices(perView);
  for (Brick& b : bricks_) b.wantedBytes = 0;
  stats_.chosenBricks = choice_.size();
  stats_.chosenMerged = mergedChoice_.size();
  stats_.chosenVectors = 0;
  for (const BrickChoice& c : choice_) {
    Brick& b = bricks_[c.brick];
    b.wantedBytes = c.bytes;
    b.wantedRecords = c.records;
    b.priority = c.priority;
    stats_.chosenVectors += c.records;
  }
  // Re-prioritise: transfers of bricks no longer wanted stop (their bytes so far stay).
  for (Brick& b : bricks_)
    if (b.transfer && b.wantedBytes <= b.fed) b.transfer.reset();
  dirty_ = true;
}

bool TilesetStream::pumpBricks() {
  bool changed = false;
  const auto& header = index_->header;
  std::string chunk;
  int running = 0;
  for (std::size_t i = 0; i < bricks_.size(); ++i) {
    Brick& b = bricks_[i];
    if (!b.transfer) continue;
    const qnv::TilesetBrick& info = index_->bricks[i];
    // The status first: once it says finished, the take() after it has every byte.
    const net::TransferStatus s = b.transfer->status();
    chunk.clear();
    b.transfer->take(chunk);
    // Under --snapshot-at's cap, the bytes past it are not used (the loader stops all at
    // its next pump).
    const std::uint64_t granted = loader_.grant(chunk.size());
    const bool cut = granted < chunk.size();
    if (cut) {
      chunk.resize(static_cast<std::size_t>(granted));
      stopped_ = true;
    }
    if (!chunk.empty()) {
      stats_.brickBytes += chunk.size();
      const std::uint64_t limit = info.vectorCount;
      if (!b.decoder) {
        b.decoder = std::make_unique<qnv::StreamDecoder>(url_ + " " + info.path());
        if (header.kind == qnv::StreamKind::gaussian) {
          b.splats = std::make_shared<splats::GaussianCloud>();
          b.splats->setShDegree(header.shDegree);
          b.splats->colorSpace = splats::colorSpaceOf(header);
        }
      }
      if (b.splats)  // set for each feed: it reports to this pump's `changed`
        b.decoder->setRecordSink(
            [&b, &changed, limit](std::uint64_t first, std::span<const std::uint64_t> records) {
              if (first + records.size() > limit) return;  // a sequence the index does not allow
              // Believe a packet's place only as far as the bytes fed could hold (a splat
              // takes at least 2 bytes), as readQnvGaussians does: a hostile index and brick
              // cannot size the cloud.
              const std::uint64_t words = b.decoder->header()->recordsPerElement();
              if (first / words > b.fed / 2 + 65536) return;
              splats::placeGaussianRecords(*b.decoder->header(), first, records, *b.splats);
              changed = true;
            });
      auto sink = [&](std::uint64_t first, std::span<const qnv::DecodedVector> v) {
        if (first + v.size() > limit) return;  // a sequence number the index does not allow
        if (b.vectors.size() < first + v.size())
          b.vectors.resize(first + v.size(), qnv::DecodedVector{{}, 0.0f, {0, 0, 1}, 0});
        std::copy(v.begin(), v.end(), b.vectors.begin() + static_cast<std::ptrdiff_t>(first));
        changed = true;
      };
      b.fed += chunk.size();
      bool bad = !b.decoder->feed(chunk, sink);
      std::string why = b.decoder->error();
      if (const auto& h = b.decoder->header();
          !bad && h &&
          (h->packetBytes != header.packetBytes || h->vectorCount != info.vectorCount ||
           h->kind != header.kind || h->shDegree != header.shDegree)) {
        bad = true;
        why = url_ + " " + info.path() + ": the brick's header disagrees with the index";
      }
      if (bad) {
        b.failed = true;
        b.transfer.reset();
        messages_.push_back({false, why});
        changed = true;
        continue;
      }
    }
    if (cut) {  // the cap: this brick's prefix ends here, not short of its file
      b.transfer.reset();
      changed = true;
      continue;
    }
    if (s.finished()) {
      if (s.state == net::TransferState::failed) {
        b.failed = true;
        messages_.push_back({false, s.error});
      } else if (b.fed < b.transferEnd && s.state == net::TransferState::done) {
        b.failed = true;  // the file is shorter than its index says: do not ask again
        messages_.push_back({false, url_ + " " + info.path() + ": the brick ends after " +
                                        std::to_string(b.fed) + " of " +
                                        std::to_string(b.transferEnd) + " bytes"});
      }
      b.transfer.reset();
      changed = true;
      continue;
    }
    ++running;
  }
  // Start transfers in priority order for the prefixes not yet fetched.
  for (const BrickChoice& c : choice_) {
    if (stopped_) break;
    if (running >= options_.parallelFetches) break;
    Brick& b = bricks_[c.brick];
    if (b.failed || b.transfer || b.fed >= b.wantedBytes) continue;
    if (b.trimmed) {  // the decoder needs the stream from its header
      b.fed = 0;
      b.decoder.reset();
      b.trimmed = false;
    }
    std::string error;
    const std::string url = base::resolveUrl(url_, index_->bricks[c.brick].path());
    net::FetchRequest r = loader_.requestFor(url, referrer_.empty() ? "" : referrer_, error);
    if (r.url.empty()) {
      b.failed = true;
      messages_.push_back({false, error});
      continue;
    }
    r.offset = b.fed;
    r.length = b.wantedBytes - b.fed;
    b.transferEnd = b.wantedBytes;
    b.transfer = net::startTransfer(std::move(r));
    ++stats_.requests;
    ++running;
  }
  return changed;
}

bool TilesetStream::pumpMerged() {
  bool changed = false;
  int running = 0;
  for (std::size_t i : mergedChoice_) {
    MergedBrick& m = merged_[i];
    if (m.cloud || m.failed) continue;
    const qnv::TilesetBrick& info = index_->bricks[i];
    const std::string url = base::resolveUrl(url_, info.mergedPath());
    if (!m.transfer) {  // merged bricks are small: fetched whole, before the vectors
      if (running >= options_.parallelFetches || stopped_) continue;
      std::string error;
      net::FetchRequest r = loader_.requestFor(url, referrer_, error);
      if (r.url.empty()) {
        m.failed = true;
        messages_.push_back({false, error});
        continue;
      }
      // At most R^3 splats of 4 records: twice that in bytes, and the header, is the most
      // a merged brick can hold, whatever the server sends.
      const std::uint64_t cells = std::uint64_t{1} << (3 * index_->mergedCellsLog2);
      r.maxBytes = std::min(r.maxBytes, qnv::kHeaderBytes + cells * 64 + 65536);
      m.transfer = net::startTransfer(std::move(r));
      ++stats_.requests;
    }
    const net::TransferStatus s = m.transfer->status();
    const std::size_t before = m.bytes.size();
    m.transfer->take(m.bytes);
    stats_.mergedBytes += m.bytes.size() - before;
    if (!s.finished()) {
      ++running;
      continue;
    }
    m.transfer.reset();
    changed = mergedDirty_ = true;
    // Under --snapshot-at's cap a merged brick is used whole or not at all.
    if (s.state == net::TransferState::done && loader_.grant(m.bytes.size()) < m.bytes.size()) {
      stopped_ = true;
      m.bytes = {};
      continue;
    }
    if (s.state != net::TransferState::done) {
      m.failed = true;
      messages_.push_back({false, s.error + " (its region is drawn from its vectors)"});
    } else {
      try {
        m.cloud = std::make_shared<const splats::GaussianCloud>(
            splats::readQnvGaussians(m.bytes, url_ + " " + info.mergedPath()));
      } catch (const std::exception& e) {
        m.failed = true;
        messages_.push_back(
            {false, std::string(e.what()) + " (its region is drawn from its vectors)"});
      }
    }
    m.bytes = {};
    if (m.failed) lastViews_.clear();  // choose again: the node is refined instead
  }
  return changed;
}

std::uint64_t TilesetStream::memoryRecords() const {
  if (!index_ || index_->header.kind != qnv::StreamKind::gaussian)
    return options_.memoryBytes / sizeof(qnv::DecodedVector);
  // A decoded splat: centre, scales, rotation, opacity, DC colour and its SH coefficients;
  // and its share of the level-of-detail tree built over the settled set (docs/splats-lod.md:
  // 0.34 nodes a splat, each a 40-byte node, a merged Gaussian and its coverage, and a
  // 4-byte leaf entry: 38 bytes a splat at SH degree 0, 99 at degree 3).
  const std::uint64_t splatBytes =
      56 + 12 * static_cast<std::uint64_t>(splats::shCoefficients(index_->header.shDegree) - 1);
  const std::uint64_t treeBytes = 4 + (44 + splatBytes) * 34 / 100;
  return options_.memoryBytes / (splatBytes + treeBytes) * words_;
}

std::uint64_t TilesetStream::mergedRecords(const splats::GaussianCloud& merged) const {
  if (index_->header.kind == qnv::StreamKind::gaussian) return merged.size() * words_;
  // A vector tileset's merged splat (SH degree 2) and its tree share, in 32-byte records.
  const std::uint64_t splatBytes =
      56 + 12 * static_cast<std::uint64_t>(splats::shCoefficients(merged.shDegree) - 1);
  const std::uint64_t treeBytes = 4 + (44 + splatBytes) * 34 / 100;
  return merged.size() *
         ((splatBytes + treeBytes + sizeof(qnv::DecodedVector) - 1) / sizeof(qnv::DecodedVector));
}

void TilesetStream::evict() {
  const std::uint64_t limit = memoryRecords();
  std::uint64_t resident = 0;
  for (const Brick& b : bricks_) resident += heldRecords(b, words_);
  for (const MergedBrick& m : merged_)
    if (m.cloud) resident += mergedRecords(*m.cloud);
  if (resident > limit) {
    // Merged bricks no view draws first: small, and fetched again whole when wanted (a
    // fly-through over a capture's deep merged levels would otherwise keep them all).
    std::vector<std::uint8_t> drawn(merged_.size(), 0);
    for (std::size_t m : mergedChoice_) drawn[m] = 1;
    for (std::size_t i = 0; i < merged_.size() && resident > limit; ++i) {
      MergedBrick& m = merged_[i];
      if (drawn[i] || !m.cloud) continue;
      resident -= mergedRecords(*m.cloud);
      m.cloud.reset();
      ++stats_.evictedMerged;
    }
  }
  if (resident > limit) {
    // Bricks no view chose, lowest priority (farthest, smallest on screen) first.
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < bricks_.size(); ++i)
      if (bricks_[i].wantedBytes == 0 && heldRecords(bricks_[i], words_) > 0) order.push_back(i);
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return bricks_[a].priority < bricks_[b].priority;
    });
    for (std::size_t i : order) {
      if (resident <= limit) break;
      Brick& b = bricks_[i];
      resident -= heldRecords(b, words_);
      b = Brick{};
      ++stats_.evictedBricks;
    }
    // Still over: chosen bricks holding more than their chosen prefix (left from an
    // earlier view that chose more of them) keep only that prefix.
    for (Brick& b : bricks_) {
      if (resident <= limit) break;
      const std::uint64_t held = heldRecords(b, words_);
      if (b.wantedBytes == 0 || b.transfer || held <= b.wantedRecords) continue;
      resident -= held - b.wantedRecords;
      if (b.splats) {
        auto kept = std::make_shared<splats::GaussianCloud>();
        kept->setShDegree(b.splats->shDegree);
        kept->appendRange(*b.splats, 0, static_cast<std::size_t>(b.wantedRecords / words_));
        b.splats = std::move(kept);
      } else {
        b.vectors.resize(static_cast<std::size_t>(b.wantedRecords));
        b.vectors.shrink_to_fit();
      }
      b.fed = b.wantedBytes;
      b.trimmed = true;
    }
  }
  stats_.residentVectors = resident;
  stats_.peakResidentVectors = std::max(stats_.peakResidentVectors, resident);
}

void TilesetStream::rebuild() {
  render::SplatSet& set = *set_;
  std::shared_ptr<splats::GaussianCloud> cloud;  // a Gaussian tileset's splats
  if (index_->header.kind == qnv::StreamKind::gaussian) {
    // What the set is made of: the chosen prefixes (and the bytes their bricks were fed,
    // which change their splats) and the merged regions. A view that moves without
    // changing them keeps the set, and so its level-of-detail tree, whose cut does not
    // depend on the set's order (the choice's priorities may change it).
    std::vector<std::array<std::uint64_t, 5>> prefixes;
    for (const BrickChoice& c : choice_) {
      const Brick& b = bricks_[c.brick];
      prefixes.push_back({c.brick, c.records, b.fed, b.splats ? b.splats->size() : 0,
                          reinterpret_cast<std::uintptr_t>(b.splats.get())});
    }
    std::sort(prefixes.begin(), prefixes.end());
    std::vector<std::uint64_t> made;
    for (const auto& p : prefixes) made.insert(made.end(), p.begin(), p.end());
    made.push_back(UINT64_MAX);
    made.insert(made.end(), mergedChoice_.begin(), mergedChoice_.end());
    if (set.gaussians && made == setMadeOf_) {
      rebuildMerged();
      return;
    }
    setMadeOf_ = std::move(made);
    cloud = std::make_shared<splats::GaussianCloud>();
    cloud->setShDegree(index_->header.shDegree);
    cloud->colorSpace = splats::colorSpaceOf(index_->header);
  }
  set.vectors.clear();
  // A volume's vectors sit on voxel centres: a merged node's region reaches half a voxel
  // past its brick's box of centres.
  const glm::vec3 margin = index_->header.kind == qnv::StreamKind::volume
                               ? 0.5f * index_->header.voxelSpacing
                               : glm::vec3(0.0f);
  std::vector<std::pair<glm::vec3, glm::vec3>> regions;  // merged regions below a brick
  for (const BrickChoice& c : choice_) {
    const Brick& b = bricks_[c.brick];
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(c.records / words_),
                                                b.splats ? b.splats->size() : b.vectors.size());
    regions.clear();
    for (std::size_t m : mergedChoice_)
      if (isAncestor(index_->bricks[c.brick], index_->bricks[m]))
        regions.push_back(
            {index_->bricks[m].boundsMin - margin, index_->bricks[m].boundsMax + margin});
    const auto inMerged = [&](const glm::vec3& p) {
      return std::any_of(regions.begin(), regions.end(), [&](const auto& r) {
        return glm::all(glm::greaterThanEqual(p, r.first)) && glm::all(glm::lessThan(p, r.second));
      });
    };
    if (cloud) {
      if (!b.splats) continue;
      // Runs of splats outside the merged regions, copied a run at a time.
      for (std::size_t k = 0; k < n;) {
        std::size_t end = k;
        while (end < n && (regions.empty() || !inMerged(b.splats->positions[end]))) ++end;
        if (end > k) cloud->appendRange(*b.splats, k, end);
        k = end + 1;  // past the splat in a merged region (or the end)
      }
      continue;
    }
    if (regions.empty()) {
      set.vectors.insert(set.vectors.end(), b.vectors.begin(),
                         b.vectors.begin() + static_cast<std::ptrdiff_t>(n));
      continue;
    }
    // An ancestor of merged nodes: its vectors inside them are drawn by the merged bricks.
    for (std::size_t k = 0; k < n; ++k)
      if (!inMerged(b.vectors[k].position)) set.vectors.push_back(b.vectors[k]);
  }
  if (cloud) {
    set.gaussians = std::move(cloud);
    set.lodTree = nullptr;  // the old tree indexes the old splats; a new one when settled
    treeCloud_.reset();     // (a build in flight holds its own)
    if (tree_.valid()) cancelTree_->store(true);
  }
  ++set.revision;
  rebuildMerged();
}

void TilesetStream::rebuildMerged() {
  if (!mergedDirty_) return;  // the merged splats only change with the choice or arrivals
  mergedDirty_ = false;
  auto mergedCloud = std::make_shared<splats::GaussianCloud>();
  // Merged bricks of vectors hold SH degree 2 (shading); of Gaussians the scene's degree.
  mergedCloud->setShDegree(
      index_->header.kind == qnv::StreamKind::gaussian ? index_->header.shDegree : 2);
  std::size_t total = 0;
  for (std::size_t m : mergedChoice_)
    if (const auto& part = merged_[m].cloud) total += part->size();
  mergedCloud->reserve(total);
  for (std::size_t m : mergedChoice_)
    if (const auto& part = merged_[m].cloud) mergedCloud->appendRange(*part, 0, part->size());
  mergedSet_->gaussians = std::move(mergedCloud);
  // Merged Gaussians far below a pixel would each be widened to the rasterizer's low-pass
  // filter at their full opacity (a far Gaussian tileset became an opaque disc): their own
  // tree merges them further, to the pixel, their coverage kept, as a stream's far cut does.
  // A few thousand (the merged root's and its children's) get it at once, on this thread,
  // in milliseconds; more (deeper merged levels: hundreds of thousands) on a thread of
  // their own once the bricks settle (pumpTree), drawn as they are until then. Without it
  // (no memory) they are drawn as they are.
  mergedSet_->lodTree = nullptr;
  if (mergedTree_.valid()) cancelMergedTree_->store(true);
  const std::size_t mergedSplats = mergedSet_->gaussians->size();
  if (mergedSplats > 1 && mergedSplats <= options_.mergedTreeOnThisThread) {
    auto [tree, problem] = buildTreeOf(mergedSet_->gaussians, nullptr, url_ + " (merged levels)");
    mergedSet_->lodTree = std::move(tree);
    mergedTreeCloud_ = mergedSet_->gaussians;
    if (!problem.empty()) messages_.push_back({false, problem + ": drawn as they are"});
  }
  mergedSet_->computeBounds();
  ++mergedSet_->revision;
}

bool TilesetStream::pump() {
  // The rate's clock runs while a transfer of this tileset runs (between pumps).
  const auto now = std::chrono::steady_clock::now();
  if (transferring_) activeSeconds_ += std::chrono::duration<double>(now - lastPump_).count();
  lastPump_ = now;
  transferring_ = false;
  bool changed = takeIndex();
  if (!index_) return changed;
  if (!loader_.stopReason().empty()) stop();  // again each pump: cheap, and idempotent
  choose();
  if (pumpMerged()) {
    dirty_ = true;
    choose();  // a merged brick that failed: its region's vectors now
  }
  if (pumpBricks()) dirty_ = true;
  if (dirty_) {
    evict();
    rebuild();
    dirty_ = false;
    changed = true;
  }
  changed |= pumpTree();
  for (const Brick& b : bricks_) transferring_ |= static_cast<bool>(b.transfer);
  for (const MergedBrick& m : merged_) transferring_ |= static_cast<bool>(m.transfer);
  return changed;
}

bool TilesetStream::treePending() const {
  if (tree_.valid()) return true;
  const auto& cloud = set_->gaussians;
  return index_ && index_->header.kind == qnv::StreamKind::gaussian && cloud && cloud->size() > 1 &&
         treeCloud_ != cloud;
}

bool TilesetStream::mergedTreePending() const {
  return mergedTree_.valid() || (mergedSet_->gaussians && mergedSet_->gaussians->size() > 1 &&
                                 mergedSet_->gaussians->size() > options_.mergedTreeOnThisThread &&
                                 mergedTreeCloud_ != mergedSet_->gaussians);
}

bool TilesetStream::pumpTree() {
  bool attached = false;
  if (mergedTree_.valid() &&
      mergedTree_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    auto [tree, problem] = mergedTree_.get();
    const auto builtFor = std::move(mergedTreeBuilding_);
    if (!problem.empty()) messages_.push_back({false, problem + ": drawn as they are"});
    // Only the tree of the set drawn now (not one of a set replaced while it was built,
    // whose build had ended before its cancel flag was set).
    if (tree && builtFor == mergedSet_->gaussians) {
      mergedSet_->lodTree = std::move(tree);
      ++mergedSet_->revision;
      attached = true;
    }
  }
  if (!mergedTree_.valid() && mergedTreePending() && bricksSettled()) {
    mergedTreeCloud_ = mergedTreeBuilding_ = mergedSet_->gaussians;
    cancelMergedTree_ = std::make_shared<std::atomic<bool>>(false);
    mergedTree_ = std::async(std::launch::async, buildTreeOf, mergedTreeBuilding_,
                             cancelMergedTree_, url_ + " (merged levels)");
  }
  if (tree_.valid()) {
    if (tree_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return attached;
    auto [tree, problem] = tree_.get();
    if (!problem.empty())  // once per set: a new build waits for a new set
      messages_.push_back({false, problem + ": its views draw every splat chosen"});
    if (tree && treeCloud_ == set_->gaussians) {
      set_->lodTree = std::move(tree);
      ++set_->revision;
      attached = true;
    }
  }
  // One build per settled set: while bricks arrive the set changes at every pump, and its
  // splats are drawn whole until it settles.
  if (treePending() && bricksSettled()) {
    treeCloud_ = set_->gaussians;
    cancelTree_ = std::make_shared<std::atomic<bool>>(false);
    tree_ = std::async(std::launch::async, buildTreeOf, treeCloud_, cancelTree_, url_);
  }
  return attached;
}

void TilesetStream::stop() {
  stopped_ = true;
  for (Brick& b : bricks_) b.transfer.reset();
  for (MergedBrick& m : merged_) {
    m.transfer.reset();
    m.bytes = {};
  }
}

bool TilesetStream::settled() const {
  return bricksSettled() && !treePending() && !mergedTreePending();
}

bool TilesetStream::bricksSettled() const {
  if (indexFailed_) return true;
  if (!index_) return false;
  if (stopped_ && !loader_.stopReason().empty()) return true;
  if (viewsChanged()) return false;
  for (std::size_t m : mergedChoice_)
    if (!merged_[m].cloud && !merged_[m].failed) return false;
  for (const BrickChoice& c : choice_) {
    const Brick& b = bricks_[c.brick];
    if (b.transfer || (!b.failed && b.fed < b.wantedBytes)) return false;
  }
  return true;
}

net::StreamProgress TilesetStream::progress() const {
  net::StreamProgress p;
  p.url = url_;
  p.kind = net::StreamKind::qnv;
  p.bytes = stats_.indexBytes + stats_.brickBytes + stats_.mergedBytes;
  // Bricks and merged bricks over the time their transfers ran (the index is fetched
  // before the clock starts).
  p.bytesPerSecond =
      activeSeconds_ > 0.0
          ? static_cast<double>(stats_.brickBytes + stats_.mergedBytes) / activeSeconds_
          : 0.0;
  p.vectors = stats_.residentVectors / words_;  // splats, for a Gaussian tileset
  p.wantedVectors = stats_.chosenVectors / words_;
  if (indexFailed_) {
    p.state = net::StreamState::failed;
    for (const auto& [error, text] : messages_)
      if (error) {
        p.error = text;
        break;
      }
    return p;
  }
  if (!index_) return p;  // waiting for the index
  p.expectedVectors = index_->header.vectorCount / words_;
  std::uint64_t files = stats_.indexBytes;
  for (const qnv::TilesetBrick& b : index_->bricks) files += b.fileBytes;
  p.expectedBytes = static_cast<std::int64_t>(std::min<std::uint64_t>(files, INT64_MAX));
  if (stopped_ && !loader_.stopReason().empty()) {
    p.state = net::StreamState::stopped;
    p.error = url_ + ": " + loader_.stopReason();
  } else {
    p.state = settled() ? net::StreamState::idle : net::StreamState::loading;
  }
  return p;
}

void TilesetStream::drainMessages(std::vector<std::pair<bool, std::string>>& out) {
  for (std::size_t i = 0; i < bricks_.size(); ++i) {
    Brick& b = bricks_[i];
    if (!b.decoder) continue;
    const auto& w = b.decoder->warnings();
    for (; b.warningsShown < w.size(); ++b.warningsShown)
      messages_.push_back({false, w[b.warningsShown]});
  }
  for (; messagesShown_ < messages_.size(); ++messagesShown_)
    out.push_back(messages_[messagesShown_]);
}

}  // namespace gs::session
