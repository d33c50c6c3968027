// The CPU Gaussian rasterizer: per-thread setup and binning, then tiles composited front
// to back (see gaussian_cpu.hpp).
#include "gaussian_cpu.hpp"

#include "simd4.hpp"
#include "tile_raster.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <cmath>
#include <cstring>
#include <thread>

namespace gs::render::detail {

namespace {

constexpr int kTile =
    32;  // tile side, pixels (Kerbl et al.'s are 16: a far vector's box crossed 2.1 of them)
constexpr float kSaturated = 1e-4f;         // transmittance below which a pixel is done
constexpr float kMinAlpha = 1.0f / 255.0f;  // fragments below it are skipped (Kerbl et al.)
constexpr float kMaxAlpha = 0.99f;

/// One visible Gaussian, ready for its pixels.
struct Prepared {
  float cx, cy;        // centre, pixels (pixel i's centre at i + 0.5)
  float ca, cb, cc;    // conic: power = -0.5 (ca dx^2 + cc dy^2) - cb dx dy
  float opacity;       // 0..1
  float minAlpha;      // fragments below it are not drawn
  float cut;           // the least power drawn: max(-8, ln(minAlpha / opacity)) less 0.01
  float depth;         // eye depth of the centre
  float r, g, b;       // colour (sRGB, >= 0)
  int x0, y0, x1, y1;  // pixel box, inclusive, inside the viewport
};

/// A covariance's six distinct entries (xx, xy, xz, yy, yz, zz).
struct Covariance6 {
  float xx, xy, xz, yy, yz, zz;
};

using Tile = TileBuffers<kTile>;

// A frame whose splats reach fewer than kBandsBelow tiles per thread composites each tile
// as kBands bands of rows, one job each: a far cut's few tiles would otherwise leave a
// thread idle while another finishes the busiest tile.
constexpr int kBands = 4;
constexpr int kBandsBelow = 4;

void composite(const Prepared p, int tx0, int ty0, int tw, int th, Tile& tile, int& live) {
  const int xs = std::max(p.x0, tx0), xe = std::min(p.x1, tx0 + tw - 1);
  const int ys = std::max(p.y0, ty0), ye = std::min(p.y1, ty0 + th - 1);
  const F4 lane = {0.5f, 1.5f, 2.5f, 3.5f};
  const bool wide = xe - xs >= 8 && p.ca > 0.0f;
  I4 closed = {0, 0, 0, 0};  // minus the pixels this splat saturated, per lane
  for (int y = ys; y <= ye; ++y) {
    const float dy = static_cast<float>(y) + 0.5f - p.cy;
    const float rowC = -0.5f * p.cc * dy * dy;
    const float rowB = -p.cb * dy;
    const int row = (y - ty0) * kTile;
    // A wide splat's row: only its pixels inside the ellipse where the power reaches the
    // cut, 0.5 ca dx^2 - rowB dx - (rowC + cut) <= 0 (a margin of 0.01 px); none when it
    // misses the row. (A narrow one's box is about its ellipse already: a root per row
    // would cost more than it saves.)
    int rs = xs, re = xe;
    if (wide) {
      const float disc = rowB * rowB + 2.0f * p.ca * (rowC - p.cut);
      if (!(disc >= 0.0f)) continue;
      const float root = std::sqrt(disc);
      const float lo = p.cx - 0.5f + (rowB - root) / p.ca - 0.01f;
      const float hi = p.cx - 0.5f + (rowB + root) / p.ca + 0.01f;
      if (!(lo <= static_cast<float>(xe)) || !(hi >= static_cast<float>(xs))) continue;
      rs = std::max(xs, static_cast<int>(std::ceil(lo)));
      re = std::min(xe, static_cast<int>(std::floor(hi)));
    }
    for (int x = tx0 + ((rs - tx0) & ~3); x <= re; x += 4) {
      const auto i = static_cast<std::size_t>(row + x - tx0);
      const F4 transmittance = load4(&tile.t[i]);
      const I4 open = transmittance > kSaturated;
      if ((open[0] | open[1] | open[2] | open[3]) == 0) continue;
      const F4 dx = (static_cast<float>(x) - p.cx) + lane;
      const F4 power = (-0.5f * p.ca) * dx * dx + rowB * dx + rowC;
      const I4 column =
          (dx >= static_cast<float>(rs) - p.cx) & (dx < static_cast<float>(re + 1) - p.cx);
      const I4 inside =
          column & (power <= 0.0f) & (power > -8.0f) & open & (p.depth <= load4(&tile.limit[i]));
      F4 alpha = p.opacity * exp4(select4(inside, power));
      alpha = alpha < kMaxAlpha ? alpha : kMaxAlpha;
      alpha = select4(inside & (alpha >= p.minAlpha), alpha);
      const F4 weight = transmittance * alpha;
      store4(&tile.r[i], load4(&tile.r[i]) + weight * p.r);
      store4(&tile.g[i], load4(&tile.g[i]) + weight * p.g);
      store4(&tile.b[i], load4(&tile.b[i]) + weight * p.b);
      const F4 left = transmittance - weight;
      store4(&tile.t[i], left);
      closed += open & (left <= kSaturated);
    }
  }
  live += closed[0] + closed[1] + closed[2] + closed[3];
}

/// What the setup reads of one splat of a source: its centre and covariance (source
/// coordinates) and peak opacity, or false when it draws nothing.
struct SplatInput {
  glm::vec3 position;
  glm::mat3 sigma;
  float opacity;
};

/// A GaussianCloud's splats: covariances cached per cloud, colours from the SH.
struct CloudSource {
  const splats::GaussianCloud& cloud;
  const Covariance6* covariances;
  glm::vec3 eye;
  float opacityScale;
  static constexpr float minAlpha = kMinAlpha;
  static constexpr bool keepIntegral = false;  // captures keep Kerbl et al.'s opacity

  std::size_t size() const { return cloud.size(); }
  bool input(std::uint32_t index, SplatInput& in) const {
    in.opacity = std::min(cloud.opacities[index] * opacityScale, 1.0f);
    if (!(in.opacity >= minAlpha)) return false;
    const Covariance6& c = covariances[index];
    in.sigma = glm::mat3(c.xx, c.xy, c.xz, c.xy, c.yy, c.yz, c.xz, c.yz, c.zz);
    in.position = cloud.positions[index];
    return true;
  }
  bool color(std::uint32_t index, const SplatInput& in, glm::vec3& out) const {
    std::array<glm::vec3, 16> sh;
    const int rest = cloud.shRestPerSplat();
    sh[0] = cloud.shDc[index];
    for (int j = 0; j < rest; ++j)
      sh[static_cast<std::size_t>(j + 1)] =
          cloud.shRest[index * static_cast<std::size_t>(rest) + static_cast<std::size_t>(j)];
    const glm::vec3 toward = in.position - eye;
    const float length = glm::length(toward);
    const glm::vec3 direction = length > 0.0f ? toward / length : glm::vec3(0.0f, 0.0f, -1.0f);
    out =
        glm::max(splats::evaluateSh(cloud.shDegree, sh.data(), direction) + 0.5f, glm::vec3(0.0f));
    if (cloud.colorSpace == splats::ColorSpace::linear) {
      for (int ch = 0; ch < 3; ++ch)
        out[ch] = out[ch] <= 0.0031308f ? 12.92f * out[ch]
                                        : 1.055f * std::pow(out[ch], 1.0f / 2.4f) - 0.055f;
    }
    return std::isfinite(out.r) && std::isfinite(out.g) && std::isfinite(out.b);
  }
};

/// QNV vectors as the flat-disc Gaussians of vectorGaussian, lit flat (shadeSplat).
struct VectorSource {
  std::span<const qnv::DecodedVector> vectors;
  const SplatStyle& style;
  std::span<const SplatLight> lights;
  glm::mat3 normalMatrix;
  static constexpr float minAlpha = splats::kVisiblePeak;
  static constexpr bool keepIntegral = true;  // the paper's profile conserves its integral

  std::size_t size() const { return vectors.size(); }
  bool input(std::uint32_t index, SplatInput& in) const {
    VectorGaussian g;
    if (!vectorGaussian(vectors[index], style, g)) return false;
    in.position = g.position;
    in.sigma = g.covariance;
    in.opacity = g.opacity;
    return true;
  }
  bool color(std::uint32_t index, const SplatInput&, glm::vec3& out) const {
    const qnv::DecodedVector& v = vectors[index];
    const glm::vec3 world = glm::normalize(normalMatrix * v.normal);
    out = shadeSplat(world, glm::vec3(unpackRgba(v.rgba)), lights, style.ambient);
    return std::isfinite(out.r) && std::isfinite(out.g) && std::isfinite(out.b);
  }
};

}  // namespace

struct CpuGaussianRasterizer::Scratch {
  std::vector<std::vector<std::vector<Prepared>>> bins;  // per chunk, per tile
  std::vector<Prepared> prepared;                        // per splat index (x0 > x1: none)
  const void* cloudKey = nullptr;
  std::size_t cloudSize = 0;
  std::uint64_t cloudRevision = 0;
  std::vector<Covariance6> covariances;
  std::unique_ptr<WorkerPool> pool;  // the frame's threads, kept between frames
};

CpuGaussianRasterizer::CpuGaussianRasterizer()
    : threads_(std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 2, 64)),
      scratch_(std::make_unique<Scratch>()) {
  scratch_->pool = std::make_unique<WorkerPool>(threads_);
}

CpuGaussianRasterizer::~CpuGaussianRasterizer() = default;

void CpuGaussianRasterizer::draw(const splats::GaussianCloud& cloud,
                                 std::span<const std::uint32_t> order, const CpuGaussianView& view,
                                 const SceneDepthReader& depth, std::vector<std::uint8_t>& out,
                                 std::uint64_t revision, std::span<const std::uint32_t> subset) {
  Scratch& s = *scratch_;
  // Covariances once per cloud (they do not depend on the view).
  const std::size_t n = cloud.size();
  if (s.cloudKey != &cloud || s.cloudSize != n || s.cloudRevision != revision) {
    s.covariances.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
      const glm::mat3 m = splats::covariance(cloud.scales[i], cloud.rotations[i]);
      s.covariances[i] = {m[0][0], m[1][0], m[2][0], m[1][1], m[2][1], m[2][2]};
    }
    s.cloudKey = &cloud;
    s.cloudSize = n;
    s.cloudRevision = revision;
  }
  rasterize(CloudSource{cloud, s.covariances.data(), view.eye, view.opacityScale}, order, view,
            depth, out, subset);
}

void CpuGaussianRasterizer::drawVectors(std::span<const qnv::DecodedVector> vectors,
                                        std::span<const std::uint32_t> order,
                                        const SplatStyle& style, std::span<const SplatLight> lights,
                                        const glm::mat3& normalMatrix, const CpuGaussianView& view,
                                        const SceneDepthReader& depth,
                                        std::vector<std::uint8_t>& out) {
  rasterize(VectorSource{vectors, style, lights.first(std::min<std::size_t>(lights.size(), 8)),
                         normalMatrix},
            order, view, depth, out, {});
}

template <typename Source>
void CpuGaussianRasterizer::rasterize(const Source& source, std::span<const std::uint32_t> order,
                                      const CpuGaussianView& view, const SceneDepthReader& depth,
                                      std::vector<std::uint8_t>& out,
                                      std::span<const std::uint32_t> subset) {
  touched_ = {};
  if (view.width <= 0 || view.height <= 0) return;
  const std::size_t pixels =
      static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height);
  out.resize(pixels * 4);
  Scratch& s = *scratch_;
  const std::size_t n = source.size();

  splats::ProjectionView pv;
  pv.modelView = view.modelView;
  const glm::mat4& p = view.projection;
  const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
  pv.fx = p[0][0] * w * 0.5f;
  pv.fy = p[1][1] * h * 0.5f;
  pv.cx = 0.5f * w * (1.0f - p[2][0]);
  pv.cy = 0.5f * h * (1.0f - p[2][1]);
  pv.width = view.width;
  pv.height = view.height;
  pv.nearClip = view.nearClip;
  pv.farClip = view.farClip;
  const float depthA = p[2][2], depthB = p[3][2];

  const int tilesX = (view.width + kTile - 1) / kTile, tilesY = (view.height + kTile - 1) / kTile;
  const int tiles = tilesX * tilesY;
  s.pool->start();
  const int chunks = s.pool->threads();  // every one of them meets at the barriers
  s.bins.resize(static_cast<std::size_t>(chunks));
  std::atomic<int> nextJob{0};
  std::barrier sync(chunks);
  // Set by chunk 0 once the splats are binned: the tiles they reached, the scene's depth
  // under them, and the jobs the tiles are split into (a tile, or a band of its rows when
  // there are too few tiles to keep every thread busy: a far cut reaches a handful).
  PixelRect reached{view.width, view.height, 0, 0};
  DepthWindow sceneDepth;
  int bands = 1;
  constexpr float minAlpha = Source::minAlpha;

  // One splat's setup: its EWA projection, box and colour; false when it draws nothing.
  const auto prepare = [&](std::uint32_t index, Prepared& prepared) {
    SplatInput in;
    if (!source.input(index, in)) return false;
    splats::ProjectedGaussian g;
    if (!splats::projectGaussian(in.position, in.sigma, pv, g)) return false;
    // A vector's peak scaled to keep its integral, and its fragments' cut with it: a
    // fragment is drawn where the unfiltered profile would reach minAlpha, so that the
    // many faint fragments of far sub-pixel vectors add up to what their point-sampled
    // peaks did (docs/splats.md, "One model").
    const float keep = Source::keepIntegral ? g.lowPassKeep : 1.0f;
    prepared.opacity = in.opacity * keep;
    prepared.minAlpha = minAlpha * keep;
    if (!(prepared.opacity >= prepared.minAlpha) || !(prepared.opacity > 0.0f)) return false;
    // The box of pixels of the 3-sigma square (as Kerbl et al.'s), narrowed to the box of
    // the ellipse where the power reaches the cut (the 2D covariance's diagonal times
    // -2 cut): no pixel outside it is drawn. The box holds the pixels from floor(centre -
    // reach) to floor(centre + reach); half a pixel of margin (and 0.01 for rounding) takes
    // in every pixel whose centre, at i + 0.5, lies within the ellipse's reach.
    prepared.cut = std::max(-8.0f, std::log(prepared.minAlpha / prepared.opacity)) - 0.01f;
    const float conicDet = g.conic.x * g.conic.z - g.conic.y * g.conic.y;
    const float reachX = std::sqrt(-2.0f * prepared.cut * g.conic.z / conicDet) + 0.51f;
    const float reachY = std::sqrt(-2.0f * prepared.cut * g.conic.x / conicDet) + 0.51f;
    const float ex = std::isfinite(reachX) ? std::min(g.extent.x, reachX) : g.extent.x;
    const float ey = std::isfinite(reachY) ? std::min(g.extent.y, reachY) : g.extent.y;
    // Clamped in float before the conversion (a huge splat's box must not overflow int).
    const auto pixel = [](float v, int size) {
      return static_cast<int>(std::floor(std::clamp(v, -1.0f, static_cast<float>(size))));
    };
    prepared.x0 = std::max(0, pixel(g.center.x - ex, view.width));
    prepared.x1 = std::min(view.width - 1, pixel(g.center.x + ex, view.width));
    prepared.y0 = std::max(0, pixel(g.center.y - ey, view.height));
    prepared.y1 = std::min(view.height - 1, pixel(g.center.y + ey, view.height));
    if (prepared.x0 > prepared.x1 || prepared.y0 > prepared.y1) return false;
    glm::vec3 color;
    if (!source.color(index, in, color)) return false;
    if (view.fog.type != 0)
      color = fogged(view.fog, color, glm::vec3(view.modelView * glm::vec4(in.position, 1.0f)));
    prepared.cx = g.center.x;
    prepared.cy = g.center.y;
    prepared.ca = g.conic.x;
    prepared.cb = g.conic.y;
    prepared.cc = g.conic.z;
    prepared.depth = g.depth;
    prepared.r = color.r;
    prepared.g = color.g;
    prepared.b = color.b;
    return true;
  };
  // The set-up runs in index order (the source's arrays read in sequence, not at the depth
  // order's random places), for the splats [0, setUp) (the order's usual indices: a depth
  // order of a prefix); an index beyond them is set up when binned. With a subset, for
  // its splats, the order holding places in it.
  const std::size_t setUp = subset.empty() ? std::min(n, order.size()) : subset.size();
  if (s.prepared.size() < setUp) s.prepared.resize(setUp);

  const auto work = [&](int chunk) {
    std::vector<std::vector<Prepared>>& bins = s.bins[static_cast<std::size_t>(chunk)];
    if (bins.size() < static_cast<std::size_t>(tiles)) bins.resize(static_cast<std::size_t>(tiles));
    for (auto& bin : bins) bin.clear();
    for (std::size_t i = setUp * static_cast<std::size_t>(chunk) / chunks,
                     last = setUp * static_cast<std::size_t>(chunk + 1) / chunks;
         i < last; ++i) {
      Prepared& prepared = s.prepared[i];
      const std::uint32_t index = subset.empty() ? static_cast<std::uint32_t>(i) : subset[i];
      if (index >= n || !prepare(index, prepared)) prepared.x0 = 1, prepared.x1 = 0;
    }
    sync.arrive_and_wait();
    // Binning in depth order, each thread one contiguous share of the order.
    const std::size_t begin = order.size() * static_cast<std::size_t>(chunk) / chunks;
    const std::size_t end = order.size() * static_cast<std::size_t>(chunk + 1) / chunks;
    constexpr std::size_t kAhead = 16;  // set-up splats prefetched ahead of the one binned
    for (std::size_t k = begin; k < end; ++k) {
      if (k + kAhead < end && order[k + kAhead] < setUp)
        __builtin_prefetch(&s.prepared[order[k + kAhead]]);
      const std::uint32_t index = order[k];
      if (index >= (subset.empty() ? n : setUp)) continue;
      Prepared late;
      if (index >= setUp && !prepare(index, late)) continue;
      const Prepared& prepared = index < setUp ? s.prepared[index] : late;
      if (prepared.x0 > prepared.x1) continue;
      for (int ty = prepared.y0 / kTile; ty <= prepared.y1 / kTile; ++ty)
        for (int tx = prepared.x0 / kTile; tx <= prepared.x1 / kTile; ++tx)
          bins[static_cast<std::size_t>(ty * tilesX + tx)].push_back(prepared);
    }
    sync.arrive_and_wait();

    if (chunk == 0) {
      int busy = 0;
      for (int t = 0; t < tiles; ++t) {
        if (!binned(s.bins, chunks, t)) continue;
        ++busy;
        const int tx0 = (t % tilesX) * kTile, ty0 = (t / tilesX) * kTile;
        reached = reached.united(
            {tx0, ty0, std::min(tx0 + kTile, view.width), std::min(ty0 + kTile, view.height)});
      }
      if (depth && !reached.empty()) {
        sceneDepth = {depth(reached), reached.x0, reached.y0, reached.width(), reached.height()};
      }
      bands = busy >= kBandsBelow * chunks ? 1 : kBands;
    }
    sync.arrive_and_wait();

    Tile tile;
    const int bandRows = kTile / bands, jobs = tiles * bands;
    for (int job = nextJob.fetch_add(1); job < jobs; job = nextJob.fetch_add(1)) {
      const int t = job / bands, band = job % bands;
      const int tx0 = (t % tilesX) * kTile, ty0 = (t / tilesX) * kTile + band * bandRows;
      if (tx0 >= reached.x1 || tx0 < reached.x0 || ty0 >= reached.y1 || ty0 < reached.y0) continue;
      const int tw = std::min(kTile, view.width - tx0), th = std::min(bandRows, view.height - ty0);
      if (th <= 0) continue;
      if (!binned(s.bins, chunks, t)) {
        clearTile(out.data(), view.width, tx0, ty0, tw, th);
        continue;
      }
      startTile(tile, tx0, ty0, tw, th, view.farClip, sceneDepth, depthA, depthB);
      int live = tw * th;
      for (int c = 0; c < chunks && live > 0; ++c) {
        for (const Prepared& splat :
             s.bins[static_cast<std::size_t>(c)][static_cast<std::size_t>(t)]) {
          if (splat.y1 < ty0 || splat.y0 >= ty0 + th) continue;  // not in this band's rows
          composite(splat, tx0, ty0, tw, th, tile, live);
          if (live <= 0) break;
        }
      }
      writeTile(tile, out.data(), view.width, tx0, ty0, tw, th);
    }
  };

  s.pool->run(work);
  touched_ = reached;
}

}  // namespace gs::render::detail
