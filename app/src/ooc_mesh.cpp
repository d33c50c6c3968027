// The out-of-core tileset encode of a mesh (docs/out-of-core.md, "Meshes"). The PLY file
// is read once with formats::streamPly into two files of the share's part folder:
// mesh.vertices (position and colour, 16 bytes a vertex) and mesh.triangles (three
// vertex indices and the face colour, 16 bytes a triangle). Every later pass reads
// mesh.triangles front to back, 1 MiB at a time, and fetches the corners through a
// direct-mapped cache of 32 KiB blocks of mesh.vertices holding a quarter of --memory
// (a soup whose vertices fit is read once; a file with little locality pays a read per
// miss). The passes: the selection (qnv::planSurfaceSelection: 1 or 3 passes), then the
// vector pass, which sends each kept triangle's vector to the leaf holding its centroid
// (ooc::ShareEncoder: the other three quarters of --memory, spilled past them), then every
// leaf row of this share is finished, as the volume encode does.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <thread>
#include <vector>

#include "encode_tileset.hpp"
#include "formats/mesh_readers.hpp"
#include "ooc_share.hpp"
#include "ooc_tileset.hpp"
#include "qnv/error.hpp"
#include "qnv/surface_tileset.hpp"
#include "qnv/tileset_writer.hpp"

namespace gs::app {

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

int writeMeshTilesetOutOfCore(const Options& options, const std::string& input,
                              const qnv::SurfaceEncodeOptions& encode,
                              const qnv::WriteOptions& write) {
  const EncodeOptions& e = options.encode;
  std::uint32_t share = 0, shares = 1;
  qnv::TilesetOptions cut;
  if (!tilesetShareOptions(e, write, share, shares, cut)) return 2;
  const auto t0 = std::chrono::steady_clock::now();
  const fs::path dir = e.tileset;
  const auto memory = static_cast<std::uint64_t>(e.memoryMB * 1048576.0);
  const unsigned threads =
      e.threads > 0 ? e.threads : std::max(1u, std::thread::hardware_concurrency());
  try {
    if (e.bricks.empty()) {  // the whole output: nothing stale may remain
      std::error_code ec;
      fs::remove_all(dir / "bricks", ec);
      fs::remove_all(dir / "parts", ec);
      fs::remove(dir / "index.qnvt", ec);
    }
    const fs::path part = dir / "parts" / shareName(share, shares);
    std::optional<PlySoup> soupHolder;
    soupHolder.emplace(part, memory / 4);
    PlySoup& soup = *soupHolder;
    formats::streamPly(input, soup);
    soup.finish();
    const double copySeconds = since(t0);

    // Distinct colours counted: half the bound (the vertex cache holds a quarter, nothing
    // else is held yet) at 40 bytes each, at least 65536 (2.5 MiB).
    const std::uint64_t maxColors = std::max<std::uint64_t>(65536, memory / 2 / 40);
    const auto t1 = std::chrono::steady_clock::now();
    const qnv::SurfaceSelectionPlan plan = qnv::planSurfaceSelection(soup, encode, maxColors);
    const double planSeconds = since(t1);
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
    const double vectorSeconds = since(t2);
    const std::uint64_t written = writer.bytesWritten();
    const std::uint64_t leafSpill = writer.leafSpillBytes();
    const std::uint64_t interiorSpill = writer.interiorSpillBytes();
    const std::uint64_t copied = soup.fileBytes(), vertices = soup.vertexCount();
    const std::uint64_t misses = soup.cacheMisses();
    encoder.reset();  // removes the spill files
    soupHolder.reset();
    Merged merged;
    if (e.bricks.empty())
      if (std::string error = mergeShares(dir, merged); !error.empty())
        throw qnv::InputError(error);
    const qnv::EncodeSummary& s = plan.summary;
    std::printf(
        "%s: %llu triangles (%llu vertices), %llu with a non-zero area, kept %llu (%.2f%%), %llu "
        "colours; out "
        "of core in %g MiB: copied %llu bytes %.3f s, %u selection pass%s %.3f s, vector pass "
        "%.3f s, %llu vertex block reads, spilled %llu + %llu bytes\n",
        input.c_str(), static_cast<unsigned long long>(s.elements),
        static_cast<unsigned long long>(vertices), static_cast<unsigned long long>(s.candidates),
        static_cast<unsigned long long>(s.kept),
        s.elements ? 100.0 * static_cast<double>(s.kept) / static_cast<double>(s.elements) : 0.0,
        static_cast<unsigned long long>(plan.palette.keys.size()), e.memoryMB,
        static_cast<unsigned long long>(copied), copySeconds, plan.passes,
        plan.passes > 1 ? "es" : "", planSeconds, vectorSeconds,
        static_cast<unsigned long long>(misses), static_cast<unsigned long long>(leafSpill),
        static_cast<unsigned long long>(interiorSpill));
    ooc::printEncodeResult(dir, input, e.bricks.empty(), merged, share, shares, range, layout,
                           written, t0);
  } catch (const qnv::InputError& error) {
    std::fprintf(stderr, "ghostspace: encode: %s\n", error.what());
    return 1;
  }
  return 0;
}

}  // namespace gs::app
