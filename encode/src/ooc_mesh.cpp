// The out-of-core tileset encode of a mesh (docs/out-of-core.md, "Meshes"). The PLY file
// is read once with formats::streamPly into two files of the share's part folder:
// mesh.vertices (position and colour, 16 bytes a vertex) and mesh.triangles (three
// vertex indices and the face colour, 16 bytes a triangle). Every later pass reads
// mesh.triangles front to back, 1 MiB at a time, and fetches the corners through a
// direct-mapped cache of 32 KiB blocks of mesh.vertices holding a quarter of the memory bound
// (a soup whose vertices fit is read once; a file with little locality pays a read per
// miss). The passes: the selection (qnv::planSurfaceSelection: 1 or 3 passes), then the
// vector pass, which sends each kept triangle's vector to the leaf holding its centroid
// (ooc::ShareEncoder: the other three quarters of the bound, spilled past them), then every
// leaf row of this share is finished, as the volume encode does.
#include <chrono>
#include <filesystem>
#include <optional>
#include <vector>

#include "encode/tileset.hpp"
#include "formats/mesh_readers.hpp"
#include "ooc_share.hpp"
#include "qnv/error.hpp"
#include "qnv/surface_tileset.hpp"
#include "qnv/tileset_writer.hpp"

namespace gs::encode {

namespace fs = std::filesystem;
using ooc::since;

namespace {

struct SoupVertex {
  glm::vec3 position{0};
  qnv::Rgba8 color{0, 0, 0, 255};
};
struct SoupTriangle {
  std::uint32_t corner[3] = {0, 0, 0};
  qnv::Rgba8 color{0, 0, 0, 255};
};
static_assert(sizeof(SoupVertex) == 16 && sizeof(SoupTriangle) == 16);

constexpr std::size_t kBatch = 65536;           // triangles or vertices per 1 MiB
constexpr std::uint32_t kBlockVertices = 2048;  // 32 KiB cache blocks

// A PLY file copied to the part folder, then read back as a triangle soup.
class PlySoup final : public formats::PlySink, public qnv::TriangleSoupReader {
 public:
  PlySoup(const fs::path& part, std::uint64_t cacheBytes)
      : cacheBytes_(cacheBytes),
        vertexFile_(part / "mesh.vertices"),
        triangleFile_(part / "mesh.triangles") {}

  void begin(const formats::PlyLayout& layout) override { layout_ = layout; }
  void vertex(const glm::vec3& position, qnv::Rgba8 color) override {
    vertexBuffer_.push_back({position, color});
    if (vertexBuffer_.size() == kBatch) flush();
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, qnv::Rgba8 color) override {
    triangleBuffer_.push_back({{a, b, c}, color});
    if (triangleBuffer_.size() == kBatch) flush();
  }
  // After streamPly: the last pieces written, the cache made.
  void finish() {
    flush();
    vertexBuffer_ = {};
    triangleBuffer_ = {};
    const std::uint64_t blocks = (vertices_ + kBlockVertices - 1) / kBlockVertices;
    const std::uint64_t fit = cacheBytes_ / (kBlockVertices * sizeof(SoupVertex));
    slotCount_ = std::max<std::uint64_t>(1, std::min(blocks, fit));
    slots_.assign(slotCount_ * kBlockVertices, SoupVertex{});
    tags_.assign(slotCount_, ~std::uint64_t{0});
  }

  std::uint64_t vertexCount() const { return vertices_; }
  std::uint64_t fileBytes() const { return vertexFile_.size() + triangleFile_.size(); }
  std::uint64_t cacheMisses() const { return misses_; }
  std::uint64_t triangleCount() const override { return triangles_; }

  void forEachTriangle(const qnv::TriangleBatchCallback& callback) override {
    std::vector<SoupTriangle> in(kBatch);
    std::vector<qnv::SurfaceTriangle> out(kBatch);
    const qnv::Rgba8 base = qnv::TriangleMesh{}.baseColor;
    for (std::uint64_t first = 0; first < triangles_; first += kBatch) {
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(kBatch, triangles_ - first));
      triangleFile_.read(first * sizeof(SoupTriangle), in.data(), n * sizeof(SoupTriangle));
      for (std::size_t i = 0; i < n; ++i) {
        const SoupVertex a = vertexAt(in[i].corner[0]), b = vertexAt(in[i].corner[1]),
                         c = vertexAt(in[i].corner[2]);
        qnv::SurfaceTriangle& t = out[i];
        t.a = a.position;
        t.b = b.position;
        t.c = c.position;
        t.color = layout_.faceColors     ? in[i].color
                  : layout_.vertexColors ? qnv::triangleMeanColor(a.color, b.color, c.color)
                                         : base;
      }
      callback(first, std::span<const qnv::SurfaceTriangle>(out.data(), n));
    }
  }

 private:
  void flush() {
    if (!vertexBuffer_.empty())
      vertexFile_.append(vertexBuffer_.data(), vertexBuffer_.size() * sizeof(SoupVertex));
    vertices_ += vertexBuffer_.size();
    vertexBuffer_.clear();
    if (!triangleBuffer_.empty())
      triangleFile_.append(triangleBuffer_.data(), triangleBuffer_.size() * sizeof(SoupTriangle));
    triangles_ += triangleBuffer_.size();
    triangleBuffer_.clear();
  }
  // Vertex `index` (< vertices_: streamPly checks every index against the count).
  SoupVertex vertexAt(std::uint32_t index) {
    const std::uint64_t block = index / kBlockVertices;
    const std::uint64_t slot = block % slotCount_;
    SoupVertex* data = slots_.data() + slot * kBlockVertices;
    if (tags_[slot] != block) {
      const std::uint64_t count =
          std::min<std::uint64_t>(kBlockVertices, vertices_ - block * kBlockVertices);
      vertexFile_.read(block * kBlockVertices * sizeof(SoupVertex), data,
                       static_cast<std::size_t>(count) * sizeof(SoupVertex));
      tags_[slot] = block;
      ++misses_;
    }
    return data[index % kBlockVertices];
  }

  std::uint64_t cacheBytes_;
  formats::PlyLayout layout_;
  ooc::SpillFile vertexFile_, triangleFile_;
  std::vector<SoupVertex> vertexBuffer_;
  std::vector<SoupTriangle> triangleBuffer_;
  std::uint64_t vertices_ = 0, triangles_ = 0;
  std::uint64_t slotCount_ = 1, misses_ = 0;
  std::vector<SoupVertex> slots_;
  std::vector<std::uint64_t> tags_;
};

}  // namespace

MeshOutOfCoreResult writeMeshTilesetOutOfCore(const TilesetTarget& target, const fs::path& ply,
                                              const qnv::SurfaceEncodeOptions& encode,
                                              const OutOfCoreOptions& ooc) {
  MeshOutOfCoreResult result;
  TilesetResult& out = result.tileset;
  const std::uint32_t share = target.share, shares = target.shares;
  const qnv::TilesetOptions& cut = target.cut;
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path& dir = target.dir;
  const std::uint64_t memory = ooc.memoryBytes;
  const unsigned threads = ooc::workerThreads(ooc);
  try {
    if (target.whole) ooc::removeStale(dir);  // the whole output: nothing stale may remain
    const fs::path part = dir / "parts" / shareName(share, shares);
    std::optional<PlySoup> soupHolder;
    soupHolder.emplace(part, memory / 4);
    PlySoup& soup = *soupHolder;
    formats::streamPly(ply.string(), soup);
    soup.finish();
    result.copySeconds = since(t0);

    // Distinct colours counted: half the bound (the vertex cache holds a quarter, nothing
    // else is held yet) at 40 bytes each, at least 65536 (2.5 MiB).
    const std::uint64_t maxColors = std::max<std::uint64_t>(65536, memory / 2 / 40);
    const auto t1 = std::chrono::steady_clock::now();
    const qnv::SurfaceSelectionPlan plan = qnv::planSurfaceSelection(soup, encode, maxColors);
    result.planSeconds = since(t1);
    const qnv::TilesetLayout layout(plan.header, cut);

    std::optional<ooc::ShareEncoder> encoder;
    // The palette lookup (5 bytes a colour) stays through the vector pass: it comes out of
    // the leaves' three quarters.
    const std::uint64_t lookup = 5 * plan.palette.keys.size() * 4 / 3;
    encoder.emplace(dir, part, layout, share, shares,
                    memory > 2 * lookup ? memory - lookup : memory / 2, threads);
    ooc::ShareEncoder& writer = *encoder;
    const auto range = writer.range();
    const auto t2 = std::chrono::steady_clock::now();
    if (range.first < range.second) {
      qnv::SurfaceKeepFilter filter(plan);
      soup.forEachTriangle([&](std::uint64_t first, std::span<const qnv::SurfaceTriangle> batch) {
        for (std::size_t i = 0; i < batch.size(); ++i) {
          qnv::SourceVector v;
          if (!qnv::triangleVector(batch[i].a, batch[i].b, batch[i].c, first + i, v)) continue;
          if (!filter.keep(v.magnitude)) continue;
          v.color = plan.palette.indexOf(batch[i].color);
          const std::uint64_t leaf = layout.leafIndex(layout.leafOf(v));
          if (leaf >= range.first && leaf < range.second) writer.add(leaf, v);
        }
      });
      const std::uint64_t perRow = std::uint64_t{layout.leafGrid().x} * layout.leafGrid().y;
      for (std::uint64_t row = range.first / perRow; row <= (range.second - 1) / perRow; ++row)
        writer.finishRow(static_cast<std::uint32_t>(row));
    }
    if (std::string error = writer.writeParts(part, cut); !error.empty())
      throw qnv::InputError(error);
    result.vectorSeconds = since(t2);
    out.shareBytes = writer.bytesWritten();
    result.leafSpillBytes = writer.leafSpillBytes();
    result.interiorSpillBytes = writer.interiorSpillBytes();
    result.copiedBytes = soup.fileBytes();
    result.vertices = soup.vertexCount();
    result.cacheMisses = soup.cacheMisses();
    encoder.reset();  // removes the spill files
    soupHolder.reset();
    if (target.whole)
      if (std::string error = mergeShares(dir, out.merged); !error.empty())
        throw qnv::InputError(error);
    result.summary = plan.summary;
    result.passes = plan.passes;
    result.colors = plan.palette.keys.size();
    out.leaves = range;
    out.leafCount = layout.leafCount();
    out.depth = layout.depth();
  } catch (const qnv::InputError& error) {
    out.failure = Failure::input;
    out.error = error.what();
  }
  out.seconds = since(t0);
  return result;
}

}  // namespace gs::encode
