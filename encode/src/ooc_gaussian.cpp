// The out-of-core tileset encode of a Gaussian splatting scene (docs/out-of-core.md,
// "Gaussian splatting scenes"). The scene is read piecewise (splats::GaussianBatchReader:
// binary INRIA .ply, .splat) in two passes, a batch of splats at a time:
//   1. the stream frame: which splats are kept, their box and scale range;
//   2. each kept splat's importance, its leaf and the root's occupied cells: the splat's
//      floats go to its leaf's bucket (OUT/parts/I-of-N/leaves.spill past the bound);
// Then each leaf, in Morton order, is (share 0, with merged levels) added to the merged
// levels' open nodes (splats::GaussianMergedLevels: one node a level, written when the
// leaves under it are done), then ranked and split as buildGaussianTileset splits it: its
// own brick goes to a job that encodes and writes it (--threads jobs at once), what its
// ancestors receive goes to their buckets (interior.spill past the bound), and the
// interior bricks are written last, by jobs too. The files are writeGaussianTileset's for
// the whole scene, byte for byte.
#include <algorithm>
#include <bit>
#include <deque>
#include <future>
#include <memory>
#include <numeric>
#include <set>
#include <stdexcept>

#include "encode/tileset.hpp"
#include "gaussian_files.hpp"
#include "ooc_share.hpp"
#include "spill_buckets.hpp"
#include "splats/gaussian_tileset.hpp"
#include "splats/merged_levels.hpp"

namespace gs::encode {

namespace fs = std::filesystem;
using ooc::since;

namespace {

// One kept splat as the buckets hold it: its importance, its rank among the kept splats
// (the ties' order), then its floats: centre 3, scales 3, rotation w x y z, opacity,
// band-0 colour 3, higher SH 3 x shRestPerSplat().
constexpr std::size_t kHead = 2, kFixed = 14;

std::size_t recordWords(int shDegree) {
  return kHead + kFixed + 3 * static_cast<std::size_t>(splats::shCoefficients(shDegree) - 1);
}

void storeSplat(const splats::GaussianCloud& c, std::size_t i, float importance, std::uint32_t k,
                std::vector<std::uint32_t>& to) {
  const auto f = [&](float v) { to.push_back(std::bit_cast<std::uint32_t>(v)); };
  f(importance);
  to.push_back(k);
  for (int a = 0; a < 3; ++a) f(c.positions[i][a]);
  for (int a = 0; a < 3; ++a) f(c.scales[i][a]);
  const glm::quat q = c.rotations[i];
  f(q.w), f(q.x), f(q.y), f(q.z);
  f(c.opacities[i]);
  for (int a = 0; a < 3; ++a) f(c.shDc[i][a]);
  const auto rest = static_cast<std::size_t>(c.shRestPerSplat());
  for (std::size_t j = 0; j < rest; ++j)
    for (int a = 0; a < 3; ++a) f(c.shRest[i * rest + j][a]);
}

// Splats [first, end) of `records` (recordWords each) as a cloud, in their order.
splats::GaussianCloud cloudOf(const std::vector<std::uint32_t>& records, std::size_t first,
                              std::size_t end, int shDegree) {
  const std::size_t words = recordWords(shDegree);
  splats::GaussianCloud c;
  c.shDegree = shDegree;
  c.resize(end - first);
  const auto rest = static_cast<std::size_t>(c.shRestPerSplat());
  for (std::size_t i = 0; i < c.size(); ++i) {
    const std::uint32_t* r = records.data() + (first + i) * words + kHead;
    const auto f = [&](std::size_t at) { return std::bit_cast<float>(r[at]); };
    c.positions[i] = glm::vec3(f(0), f(1), f(2));
    c.scales[i] = glm::vec3(f(3), f(4), f(5));
    c.rotations[i] = glm::quat(f(6), f(7), f(8), f(9));
    c.opacities[i] = f(10);
    c.shDc[i] = glm::vec3(f(11), f(12), f(13));
    for (std::size_t j = 0; j < rest; ++j)
      c.shRest[i * rest + j] = glm::vec3(f(14 + 3 * j), f(15 + 3 * j), f(16 + 3 * j));
  }
  return c;
}

// Records ranked as buildGaussianTileset ranks splats: importance descending, then rank.
void rankRecords(std::vector<std::uint32_t>& records, std::size_t words) {
  const std::size_t n = records.size() / words;
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  const auto at = [&](std::uint32_t r) { return records.data() + std::size_t{r} * words; };
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const float ia = std::bit_cast<float>(at(a)[0]), ib = std::bit_cast<float>(at(b)[0]);
    return ia > ib || (ia == ib && at(a)[1] < at(b)[1]);
  });
  std::vector<std::uint32_t> ranked;
  ranked.reserve(records.size());
  for (const std::uint32_t r : order) ranked.insert(ranked.end(), at(r), at(r) + words);
  records = std::move(ranked);
}

// An interior node's bucket key: its level above its cell's Morton code.
std::uint64_t nodeKey(const qnv::TilesetCell& node) {
  return std::uint64_t{node.level} << 60 | splats::mortonOfCell(node.cell);
}
qnv::TilesetCell nodeOfKey(std::uint64_t key) {
  return {static_cast<std::uint8_t>(key >> 60),
          splats::cellOfMorton(key & ((std::uint64_t{1} << 60) - 1))};
}

// A brick a job wrote: its index entry, its bytes, and "" or the write's error.
struct WrittenBrick {
  qnv::TilesetBrick brick;
  std::uint64_t bytes = 0;
  std::string error;
};

// Brick jobs on threads of their own, at most `threads` in flight (each holds its splats):
// submit() waits for the oldest first when that many run.
class BrickJobs {
 public:
  explicit BrickJobs(unsigned threads) : threads_(std::max(1u, threads)) {}
  BrickJobs(const BrickJobs&) = delete;
  BrickJobs& operator=(const BrickJobs&) = delete;
  ~BrickJobs() {  // an early return: the jobs in flight end before what they use goes
    for (auto& job : inFlight_)
      if (job.valid()) job.wait();
  }

  template <typename Job>
  void submit(Job&& job) {
    if (inFlight_.size() >= threads_) collectOldest();
    inFlight_.push_back(std::async(std::launch::async, std::forward<Job>(job)));
  }
  // Waits for every job; a job's exception is rethrown here.
  void finish() {
    while (!inFlight_.empty()) collectOldest();
  }
  const std::string& error() const { return error_; }  // the first write that failed
  std::uint64_t bytes() const { return bytes_; }
  std::vector<qnv::TilesetBrick> takeBricks() { return std::move(bricks_); }

 private:
  void collectOldest() {
    std::future<WrittenBrick> job = std::move(inFlight_.front());
    inFlight_.pop_front();
    const WrittenBrick written = job.get();
    if (!written.error.empty()) {
      if (error_.empty()) error_ = written.error;
      return;
    }
    bricks_.push_back(written.brick);
    bytes_ += written.bytes;
  }

  unsigned threads_;
  std::deque<std::future<WrittenBrick>> inFlight_;
  std::vector<qnv::TilesetBrick> bricks_;
  std::uint64_t bytes_ = 0;
  std::string error_;
};

}  // namespace

GaussianOutOfCoreResult writeGaussianTilesetOutOfCore(const TilesetTarget& target,
                                                      splats::GaussianBatchReader& reader,
                                                      const splats::GaussianStreamOptions& options,
                                                      const GaussianCutDefaults& defaults,
                                                      const OutOfCoreOptions& ooc) {
  const auto t0 = std::chrono::steady_clock::now();
  GaussianOutOfCoreResult out;
  TilesetResult& result = out.tileset;
  const auto fail = [&](Failure failure, std::string error) -> GaussianOutOfCoreResult& {
    result.failure = failure;
    result.error = std::move(error);
    result.seconds = since(t0);
    return out;
  };
  const std::uint32_t share = target.share, shares = target.shares;
  if (shares == 0 || shares > qnv::kMaxTilesetShares || share >= shares)
    return fail(Failure::input, "share " + std::to_string(share) + " of " + std::to_string(shares) +
                                    " does not exist");
  const int degree = reader.shDegree();
  const std::size_t words = recordWords(degree);
  out.splats = reader.size();
  out.shDegree = degree;
  // A batch's rows and its cloud: at most an eighth of the bound (and 1 to 65,536 splats).
  const std::size_t batchSplats = static_cast<std::size_t>(
      std::clamp<std::uint64_t>(ooc.memoryBytes / 8 / (reader.rowBytes() + words * 4), 1, 65536));
  const fs::path& dir = target.dir;
  const fs::path part = dir / "parts" / shareName(share, shares);
  // A whole run's spill folder goes when it ends, whether it succeeded or not (its spill
  // files, still open, are unlinked with it).
  struct RemoveParts {
    fs::path parts;
    ~RemoveParts() {
      std::error_code ec;
      if (!parts.empty()) fs::remove_all(parts, ec);
    }
  } removeParts{target.whole ? dir / "parts" : fs::path()};
  try {
    splats::GaussianCloud batch;
    // Pass 1: the frame.
    splats::GaussianFrameBuilder frame(degree, reader.size());
    reader.rewind();
    while (const std::size_t n = reader.read(batch, batchSplats))
      for (std::size_t i = 0; i < n; ++i) frame.addExtent(batch, i);
    frame.finishExtent();
    out.kept = frame.keptCount();
    out.passes = 1;
    if (out.kept == 0)
      return fail(Failure::input, "nothing to encode: " + std::to_string(out.splats) +
                                      " Gaussians, none with an opacity and a size");
    if (out.kept > 0xffffffffu)
      return fail(Failure::input, std::to_string(out.kept) + " splats kept exceed 2^32 - 1");
    // The scene read and something kept: the old files may go (not before: a scene that
    // cannot be encoded leaves a tileset already there as it was).
    if (target.whole) ooc::removeStale(dir);
    qnv::TilesetOptions cut = target.cut;
    if (defaults.brickVectors) cut.brickVectors = splats::defaultGaussianBrickVectors(out.kept);
    out.brickVectors = cut.brickVectors;
    const qnv::TilesetLayout byPosition =
        splats::gaussianLayoutForSplats(frame.header(), out.kept, cut);
    const std::uint8_t depth = byPosition.depth();
    result.depth = depth;
    result.leafCount = byPosition.leafCount();
    result.leaves = byPosition.shareLeaves(share, shares);
    out.frameSeconds = since(t0);

    // Pass 2: importance, leaves, occupancy.
    // The leaves' bucket is keyed by the leaf's Morton code: taken back in ascending key,
    // the leaves come in the order the merged levels take them.
    SpillBuckets leaves(part / "leaves.spill", ooc.memoryBytes / 2, words, out.kept);
    std::vector<std::uint32_t> record;
    std::vector<bool> occupied(std::size_t{splats::kGaussianRootCells} *
                               splats::kGaussianRootCells * splats::kGaussianRootCells);
    std::uint64_t occupiedCount = 0;
    std::uint32_t k = 0;
    qnv::SourceVector at;
    reader.rewind();
    while (const std::size_t n = reader.read(batch, batchSplats)) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!splats::keptInGaussianStream(batch, i)) continue;
        const float a = frame.importanceOf(batch, i);
        const std::uint32_t cell = splats::gaussianRootCell(frame.header(), batch.positions[i]);
        if (!occupied[cell]) ++occupiedCount;
        occupied[cell] = true;
        at.position = batch.positions[i];
        const glm::uvec3 leafCell = byPosition.leafOf(at);
        const std::uint64_t leaf = byPosition.leafIndex(leafCell);
        const bool mine = leaf >= result.leaves.first && leaf < result.leaves.second;
        if (share == 0 || mine) {  // share 0 gives every leaf's best to the interior
          record.clear();
          storeSplat(batch, i, a, k, record);
          leaves.add(splats::mortonOfCell(leafCell), record.data(), 1);
        }
        ++k;
      }
    }
    out.passes = 2;  // the merged levels are summed from the leaves' buckets
    const qnv::StreamHeader& header = frame.finish();
    if (defaults.mergedCells)
      cut.mergedCellsLog2 = splats::gaussianMergedCellsLog2For(occupiedCount, out.kept);
    out.mergedCellsLog2 = cut.mergedCellsLog2;
    const qnv::TilesetLayout layout = splats::gaussianLayoutForSplats(header, out.kept, cut);
    out.bucketSeconds = since(t0) - out.frameSeconds;

    // The bricks: each leaf's own, then the interior nodes'.
    SpillBuckets interior(part / "interior.spill", ooc.memoryBytes / 4, words, out.kept);
    // Each brick encoded and written by a job of its own, --threads of them at once; the
    // ranking and the buckets stay on this thread (the interior nodes' buckets receive in
    // leaf order, though their ranking would not depend on it).
    BrickJobs jobs(ooc::workerThreads(ooc));
    const auto writeBrick = [&](const qnv::TilesetCell& node,
                                std::shared_ptr<const std::vector<std::uint32_t>> records,
                                std::size_t first, std::size_t end) {
      jobs.submit([&, node, records, first, end] {
        const splats::GaussianCloud c = cloudOf(*records, first, end, degree);
        std::vector<std::uint32_t> order(c.size());
        std::iota(order.begin(), order.end(), 0u);
        const qnv::StreamHeader h = layout.brickHeader(node, c.size() * header.recordsPerElement());
        const qnv::BrickFile file =
            qnv::writeBrick(node, h, splats::encodeGaussianSplats(c, order, h, options));
        WrittenBrick written{file.brick, file.bytes.size(),
                             writeFile(dir / file.brick.path(), file.bytes)};
        return written;
      });
    };
    // The merged levels (share 0): each node's merged brick written once the leaves under
    // it are done, if the node has a brick (some leaf gave it splats).
    const bool merged = cut.mergedCellsLog2 > 0 && depth > 0 && share == 0;
    std::set<qnv::TilesetCell> interiorNodes, mergedWritten;
    std::string mergedError;
    double mergedSeconds = 0;
    std::optional<splats::GaussianMergedLevels> mergedLevels;
    if (merged)
      mergedLevels.emplace(layout, cut.mergedCellsLog2,
                           [&](const qnv::TilesetCell& node, splats::GaussianCloud&& cloud) {
                             if (!interiorNodes.count(node) || !mergedError.empty()) return;
                             const std::string bytes = splats::encodeMergedBrick(cloud);
                             mergedError = writeFile(dir / mergedPathOf(node), bytes);
                             result.merged.totalBytes += bytes.size();
                             mergedWritten.insert(node);
                           });
    std::vector<std::uint32_t> members;
    for (const std::uint64_t code : leaves.keys()) {  // Morton order
      auto records = std::make_shared<std::vector<std::uint32_t>>(leaves.take(code));
      const glm::uvec3 leafCell = splats::cellOfMorton(code);
      const std::uint64_t leaf = layout.leafIndex(leafCell);
      const std::size_t count = records->size() / words;
      if (mergedLevels) {  // the leaf's splats in scene order, before they are ranked
        const auto t = std::chrono::steady_clock::now();
        members.resize(count);
        std::iota(members.begin(), members.end(), 0u);
        mergedLevels->addLeaf(leafCell, cloudOf(*records, 0, count, degree), members);
        mergedSeconds += since(t);
      }
      rankRecords(*records, words);
      std::size_t next = 0;
      for (const auto& [node, end] : splats::splitGaussianLeaf(layout, leafCell, count)) {
        if (node.level < depth && share == 0) {
          interior.add(nodeKey(node), records->data() + next * words, end - next);
          interiorNodes.insert(node);
        }
        if (node.level == depth && leaf >= result.leaves.first && leaf < result.leaves.second)
          writeBrick(node, records, next, end);
        next = end;
      }
    }
    if (mergedLevels) {
      const auto t = std::chrono::steady_clock::now();
      mergedLevels->finish();
      mergedSeconds += since(t);
      out.mergedCells = mergedLevels->cellsMerged();
      out.mergedPeakCells = mergedLevels->peakCells();
    }
    for (const std::uint64_t key : interior.keys()) {
      const qnv::TilesetCell node = nodeOfKey(key);
      auto records = std::make_shared<std::vector<std::uint32_t>>(interior.take(key));
      rankRecords(*records, words);
      writeBrick(node, records, 0, records->size() / words);
    }
    jobs.finish();
    if (!jobs.error().empty()) return fail(Failure::write, jobs.error());
    result.merged.totalBytes += jobs.bytes();
    out.leafSpillBytes = leaves.spilledBytes();
    out.interiorSpillBytes = interior.spilledBytes();
    qnv::TilesetIndex index = qnv::assembleTilesetIndex(layout, jobs.takeBricks());
    if (cut.mergedCellsLog2 > 0 && depth > 0) {
      index.mergedCellsLog2 = cut.mergedCellsLog2;
      index.mergedEveryLevel = true;
    }
    out.brickSeconds = since(t0) - out.frameSeconds - out.bucketSeconds - mergedSeconds;
    out.mergedSeconds = mergedSeconds;
    if (!mergedError.empty()) return fail(Failure::write, mergedError);
    // A node with a brick whose splats merged to nothing: an empty merged stream.
    std::vector<std::pair<qnv::TilesetCell, std::string>> mergedBricks;
    if (merged)
      for (const qnv::TilesetBrick& b : index.bricks) {
        const qnv::TilesetCell node{b.level, glm::uvec3(b.x, b.y, b.z)};
        if (index.hasMerged(b.level) && !mergedWritten.count(node))
          mergedBricks.emplace_back(node, splats::encodeMergedBrick({}));
      }
    TilesetTarget used = target;  // the parts record the cut the bricks were made with
    used.cut = cut;
    finishGaussianTileset(used, options, std::move(index), mergedBricks, t0, result);
  } catch (const splats::FormatError& error) {  // the scene, read again, is not what it was
    out.unreadable = true;
    return fail(Failure::input, error.what());
  } catch (const SpillFailure& error) {
    return fail(Failure::write, error.what());
  } catch (const qnv::InputError& error) {
    return fail(Failure::input, error.what());
  }
  return out;
}

}  // namespace gs::encode
