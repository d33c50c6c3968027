// The CPU splat path: per-thread setup and binning, then tiles composited front to back
// (see splat_cpu.hpp for the algorithm and splat_reference.hpp for the definitions).
#include "splat_cpu.hpp"

#include "simd4.hpp"
#include "tile_raster.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <barrier>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <thread>

namespace gs::render::detail {

namespace {

constexpr int kTile = 32;                     // tile side, pixels
constexpr float kSaturated = 1.0f / 2048.0f;  // transmittance below which a pixel is done
// The least alpha that changes an 8-bit framebuffer: blending a premultiplied source of
// alpha a over a destination d moves it by 255 a (c - d) levels, which rounds to nothing
// below half a level for any colour. The GL paths draw into RGBA8, where such fragments
// vanish; the cpu path drops them too, so both show the same picture (without it the
// millions of faint gradients of a whole CT stream add up to a haze the GL paths never
// show), and a splat whose peak is below it is not drawn at all.
constexpr float kVisibleAlpha = splats::kVisiblePeak;
constexpr float kExtent2 = kSplatExtent * kSplatExtent;  // 9: r2 beyond it is cut
constexpr int kMaxLights = 8;

/// A linear function of the pixel coordinates: x px + y py + c.
struct Linear {
  float x = 0.0f, y = 0.0f, c = 0.0f;
};

/// One visible splat, ready for its pixels (see splat_cpu.hpp, step 1).
struct Prepared {
  Linear den, a, b;      // d . N, d . T*, d . B* of pixel (x, y)'s ray d
  float offset, cu, cv;  // C . N, C . T*, C . B*
  float peak;            // profile peak, 0..1
  glm::vec3 color;       // shaded, premultiplied by nothing yet
  int x0, y0, x1, y1;    // pixel box, inclusive, inside the viewport
};

/// Per-frame constants of the setup.
struct Frame {
  glm::mat4 modelView{1.0f};
  glm::mat3 rotation{1.0f};  // upper 3x3 of modelView
  glm::mat4 projection{1.0f};
  glm::mat3 normalMatrix{1.0f};
  float kx = 0, cx = 0, ky = 0, cy = 0;  // ray of pixel (x, y): (kx x + cx, ky y + cy, -1)
  int width = 0, height = 0;
  float nearClip = 0, farClip = 0;
  const SplatStyle* style = nullptr;
  std::array<SplatLight, kMaxLights> lights{};
  int lightCount = 0;

  Linear linear(const glm::vec3& v) const {
    return {kx * v.x, ky * v.y, cx * v.x + cy * v.y - v.z};
  }
};

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// The pixel box of the patch with centre `c` and half-axes `h`, `k` (eye space): the
/// patch clipped to the near plane, projected, one pixel of margin, clipped to the
/// viewport (rows bottom to top). False when empty or wholly beyond the far plane.
bool pixelBox(const glm::vec3& c, const glm::vec3& h, const glm::vec3& k, const Frame& f,
              Prepared& out) {
  const std::array<glm::vec3, 4> corners = {c - h - k, c + h - k, c + h + k, c - h + k};
  std::array<glm::vec3, 8> clipped;
  int count = 0;
  bool beyondFar = true;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3& a = corners[static_cast<std::size_t>(i)];
    const glm::vec3& b = corners[static_cast<std::size_t>((i + 1) % 4)];
    beyondFar = beyondFar && -a.z > f.farClip;
    const bool inA = -a.z >= f.nearClip, inB = -b.z >= f.nearClip;
    if (inA) clipped[static_cast<std::size_t>(count++)] = a;
    if (inA != inB) {
      const float t = (-f.nearClip - a.z) / (b.z - a.z);
      glm::vec3 p = a + t * (b - a);
      p.z = -f.nearClip;
      clipped[static_cast<std::size_t>(count++)] = p;
    }
  }
  if (count == 0 || beyondFar) return false;
  float minX = INFINITY, minY = INFINITY, maxX = -INFINITY, maxY = -INFINITY;
  const float w = static_cast<float>(f.width), hgt = static_cast<float>(f.height);
  for (int i = 0; i < count; ++i) {
    const glm::vec4 clip = f.projection * glm::vec4(clipped[static_cast<std::size_t>(i)], 1.0f);
    const float px = (clip.x / clip.w + 1.0f) * 0.5f * w;
    const float py = (clip.y / clip.w + 1.0f) * 0.5f * hgt;
    if (!std::isfinite(px) || !std::isfinite(py)) return false;
    minX = std::min(minX, px);
    maxX = std::max(maxX, px);
    minY = std::min(minY, py);
    maxY = std::max(maxY, py);
  }
  // Pixel x is covered when x + 0.5 lies in [minX, maxX]; one pixel of margin.
  const auto toPixel = [](float v, float limit) {
    return static_cast<int>(std::clamp(v, -2.0f, limit + 2.0f));
  };
  out.x0 = std::max(toPixel(std::floor(minX - 0.5f), w) - 1, 0);
  out.x1 = std::min(toPixel(std::ceil(maxX - 0.5f), w) + 1, f.width - 1);
  out.y0 = std::max(toPixel(std::floor(minY - 0.5f), hgt) - 1, 0);
  out.y1 = std::min(toPixel(std::ceil(maxY - 0.5f), hgt) + 1, f.height - 1);
  return out.x0 <= out.x1 && out.y0 <= out.y1;
}

/// False when the vector draws nothing in this frame.
bool prepare(const qnv::DecodedVector& vector, const Frame& f, Prepared& out) {
  const float length = glm::length(vector.normal);
  if (!(length > 0.0f) || !std::isfinite(length) || !finite(vector.position)) return false;
  const glm::vec3 n = vector.normal / length;
  const glm::vec4 rgba = unpackRgba(vector.rgba);
  const SplatProfile profile = splatProfile(*f.style, vector.magnitude, rgba.a);
  if (!(profile.peak >= kVisibleAlpha) || !(profile.spread > 0.0f) ||
      !std::isfinite(profile.spread)) {
    return false;
  }
  glm::vec3 t, b;
  splatAxes(n, t, b);
  // Eye-space centre and axes of one spread: the patch is C + u T + v B, |u|, |v| <= 3.
  const glm::vec3 c(f.modelView * glm::vec4(vector.position, 1.0f));
  const glm::vec3 axisT = f.rotation * (t * profile.spread);
  const glm::vec3 axisB = f.rotation * (b * profile.spread);
  if (!pixelBox(c, kSplatExtent * axisT, kSplatExtent * axisB, f, out)) return false;
  // The dual basis: (u T + v B) . T* = u, . B* = v.
  const float tt = glm::dot(axisT, axisT), tb = glm::dot(axisT, axisB), bb = glm::dot(axisB, axisB);
  const float det = tt * bb - tb * tb;
  if (!(det > 0.0f) || !std::isfinite(det)) return false;
  const glm::vec3 dualT = (bb * axisT - tb * axisB) / det;
  const glm::vec3 dualB = (tt * axisB - tb * axisT) / det;
  const glm::vec3 normal = glm::cross(axisT, axisB);
  out.den = f.linear(normal);
  out.a = f.linear(dualT);
  out.b = f.linear(dualB);
  out.offset = glm::dot(c, normal);
  out.cu = glm::dot(c, dualT);
  out.cv = glm::dot(c, dualB);
  out.peak = profile.peak;
  // Flat two-sided shading with the world normal, as the shaders' splatLit.
  const glm::vec3 world = glm::normalize(f.normalMatrix * vector.normal);
  glm::vec3 light(f.style->ambient);
  for (int i = 0; i < f.lightCount; ++i) {
    const SplatLight& l = f.lights[static_cast<std::size_t>(i)];
    light += (1.0f - f.style->ambient) * std::abs(glm::dot(world, l.direction)) * l.color;
  }
  out.color = glm::min(glm::vec3(rgba) * light, glm::vec3(1.0f));
  return finite(out.color);
}

using Tile = TileBuffers<kTile>;

/// Composites splat `p` into the tile at (tx0, ty0) of size tw x th; `live` counts the
/// tile's unsaturated pixels. `p` is a copy: the tile's float stores cannot alias it, so
/// its fields stay in registers.
void composite(const Prepared p, int tx0, int ty0, int tw, int th, float nearClip, Tile& tile,
               int& live) {
  const int xs = std::max(p.x0, tx0), xe = std::min(p.x1, tx0 + tw - 1);
  const int ys = std::max(p.y0, ty0), ye = std::min(p.y1, ty0 + th - 1);
  // Each row's span of the disk u^2 + v^2 <= 9: with D = d . N, U = (C . N)(d . T*) -
  // (C . T*) D and V likewise (linear in x and y), U^2 + V^2 - 9 D^2 <= 0 is a quadratic
  // qa x^2 + 2 qb x + qc in x. Where it opens upwards (qa > 0: the patch wholly in front
  // of the eye) the span lies between its roots -qb / qa -+ sqrt(qb^2 - qa qc) / qa, whose
  // centre is linear and whose discriminant is quadratic in the row (taken from the first
  // row, in double: the coefficients cancel); one pixel of margin for rounding (each pixel
  // is still tested exactly).
  const double off = p.offset, cu = p.cu, cv = p.cv, nine = kExtent2;
  const double d1 = p.den.x, dY = p.den.y;
  const double pu = off * p.a.x - cu * d1, pv = off * p.b.x - cv * d1;
  const double qa = pu * pu + pv * pv - nine * d1 * d1;
  const double quY = off * p.a.y - cu * dY, qvY = off * p.b.y - cv * dY;
  const double y0 = ys;
  const double qu0 = quY * y0 + (off * p.a.c - cu * p.den.c);
  const double qv0 = qvY * y0 + (off * p.b.c - cv * p.den.c);
  const double d0 = dY * y0 + double(p.den.c);
  const double b1 = pu * quY + pv * qvY - nine * d1 * dY;  // qb = b1 t + b0, t = y - ys
  const double b0 = pu * qu0 + pv * qv0 - nine * d1 * d0;
  const double c2 = quY * quY + qvY * qvY - nine * dY * dY;  // qc = (c2 t + c1) t + c0
  const double c1 = 2.0 * (quY * qu0 + qvY * qv0 - nine * dY * d0);
  const double c0 = qu0 * qu0 + qv0 * qv0 - nine * d0 * d0;
  const double e2 = b1 * b1 - qa * c2, e1 = 2.0 * b1 * b0 - qa * c1, e0 = b0 * b0 - qa * c0;
  const double inverseQa = qa > 0.0 ? 1.0 / qa : 0.0;
  const double spanLo = double(xs) - 2.0, spanHi = double(xe) + 2.0;
  for (int y = ys; y <= ye; ++y) {
    const float fy = static_cast<float>(y);
    const float rowDen = p.den.y * fy + p.den.c;
    const float rowA = p.a.y * fy + p.a.c;
    const float rowB = p.b.y * fy + p.b.c;
    int rowStart = xs, rowEnd = xe;
    if (qa > 0.0) {
      const double t = y - ys;
      const double disc = (e2 * t + e1) * t + e0;
      if (!(disc >= 0.0)) continue;
      const double half = std::sqrt(disc) * inverseQa;
      const double centre = -(b1 * t + b0) * inverseQa;
      // Clamped to at least -2: truncation after + 8 is the floor.
      const double lo = std::clamp(centre - half, spanLo, spanHi) + 8.0;
      const double hi = std::clamp(centre + half, spanLo, spanHi) + 8.0;
      rowStart = std::max(xs, static_cast<int>(lo) - 8 - 1);
      rowEnd = std::min(xe, static_cast<int>(hi) - 8 + 2);
    }
    // Four pixels at a time from a multiple of 4 in the tile (the tile's columns past the
    // viewport are saturated: they take nothing). A pixel outside the disk, the clip range
    // or the scene's depth, or already saturated, gets alpha 0.
    const int row = (y - ty0) * kTile;
    const F4 lane = {0.0f, 1.0f, 2.0f, 3.0f};
    for (int x = tx0 + ((rowStart - tx0) & ~3); x <= rowEnd; x += 4) {
      const auto i = static_cast<std::size_t>(row + x - tx0);
      const F4 transmittance = load4(&tile.t[i]);
      const F4 fx = static_cast<float>(x) + lane;
      const F4 depth = p.offset / (p.den.x * fx + rowDen);  // inf or NaN when parallel
      const F4 u = depth * (p.a.x * fx + rowA) - p.cu;
      const F4 v = depth * (p.b.x * fx + rowB) - p.cv;
      const F4 r2 = u * u + v * v;
      const I4 open = transmittance > kSaturated;
      if ((open[0] | open[1] | open[2] | open[3]) == 0) continue;  // all four saturated
      const I4 inside =
          (r2 <= kExtent2) & (depth >= nearClip) & (depth <= load4(&tile.limit[i])) & open;
      const F4 profile = p.peak * exp4(-0.5f * select4(inside, r2));
      const F4 alpha = select4(inside & (profile >= kVisibleAlpha), profile);
      const F4 weight = transmittance * alpha;
      store4(&tile.r[i], load4(&tile.r[i]) + weight * p.color.r);
      store4(&tile.g[i], load4(&tile.g[i]) + weight * p.color.g);
      store4(&tile.b[i], load4(&tile.b[i]) + weight * p.color.b);
      const F4 left = transmittance - weight;
      store4(&tile.t[i], left);
      const I4 done = open & (left <= kSaturated);  // -1 where the pixel just saturated
      live += done[0] + done[1] + done[2] + done[3];
    }
  }
}

}  // namespace

struct CpuSplatRasterizer::Scratch {
  // Per chunk, per tile: the prepared splats touching the tile, in order (a splat over
  // several tiles is copied to each: a tile then reads its splats sequentially).
  std::vector<std::vector<std::vector<Prepared>>> bins;
};

CpuSplatRasterizer::CpuSplatRasterizer()
    : threads_(std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 2, 64)),
      scratch_(std::make_unique<Scratch>()) {}

CpuSplatRasterizer::~CpuSplatRasterizer() = default;

void CpuSplatRasterizer::draw(std::span<const qnv::DecodedVector> vectors,
                              std::span<const std::uint32_t> order, const SplatStyle& style,
                              std::span<const SplatLight> lights, const CpuSplatView& view,
                              std::span<const float> depth, std::vector<std::uint8_t>& out) {
  if (view.width <= 0 || view.height <= 0) return;
  const std::size_t pixels =
      static_cast<std::size_t>(view.width) * static_cast<std::size_t>(view.height);
  out.resize(pixels * 4);
  if (depth.size() < pixels) depth = {};

  Frame f;
  f.modelView = view.modelView;
  f.rotation = glm::mat3(view.modelView);
  f.projection = view.projection;
  f.normalMatrix = view.normalMatrix;
  f.width = view.width;
  f.height = view.height;
  f.nearClip = view.nearClip;
  f.farClip = view.farClip;
  f.style = &style;
  f.lightCount = static_cast<int>(std::min<std::size_t>(lights.size(), kMaxLights));
  for (int i = 0; i < f.lightCount; ++i)
    f.lights[static_cast<std::size_t>(i)] = lights[static_cast<std::size_t>(i)];
  // Pixel (x, y) has NDC (2 (x + 0.5) / w - 1, 2 (y + 0.5) / h - 1); its ray at eye depth 1
  // is ((ndc.x + P[2][0]) / P[0][0], (ndc.y + P[2][1]) / P[1][1], -1).
  const glm::mat4& p = view.projection;
  const float w = static_cast<float>(view.width), h = static_cast<float>(view.height);
  f.kx = 2.0f / (w * p[0][0]);
  f.cx = (1.0f / w - 1.0f + p[2][0]) / p[0][0];
  f.ky = 2.0f / (h * p[1][1]);
  f.cy = (1.0f / h - 1.0f + p[2][1]) / p[1][1];
  // Window depth to eye depth: e = P[3][2] / (ndc z + P[2][2]).
  const float depthA = p[2][2], depthB = p[3][2];

  const int tilesX = (view.width + kTile - 1) / kTile, tilesY = (view.height + kTile - 1) / kTile;
  const int tiles = tilesX * tilesY;
  const int chunks = threads_;
  Scratch& s = *scratch_;
  s.bins.resize(static_cast<std::size_t>(chunks));
  std::atomic<int> nextTile{0};
  std::barrier sync(threads_);

  const auto work = [&](int chunk) {
    // 1. Setup and binning of this chunk of the order.
    std::vector<std::vector<Prepared>>& bins = s.bins[static_cast<std::size_t>(chunk)];
    if (bins.size() < static_cast<std::size_t>(tiles)) bins.resize(static_cast<std::size_t>(tiles));
    for (auto& bin : bins) bin.clear();
    const std::size_t begin = order.size() * static_cast<std::size_t>(chunk) / chunks;
    const std::size_t end = order.size() * static_cast<std::size_t>(chunk + 1) / chunks;
    Prepared splat;
    for (std::size_t k = begin; k < end; ++k) {
      // The order visits the vectors at random: fetch a few splats ahead.
      constexpr std::size_t kAhead = 16;
      if (k + kAhead < end && order[k + kAhead] < vectors.size())
        __builtin_prefetch(&vectors[order[k + kAhead]]);
      const std::uint32_t index = order[k];
      if (index >= vectors.size() || !prepare(vectors[index], f, splat)) continue;
      for (int ty = splat.y0 / kTile; ty <= splat.y1 / kTile; ++ty) {
        for (int tx = splat.x0 / kTile; tx <= splat.x1 / kTile; ++tx)
          bins[static_cast<std::size_t>(ty * tilesX + tx)].push_back(splat);
      }
    }
    sync.arrive_and_wait();

    // 2. Tiles, front to back.
    Tile tile;
    for (int t = nextTile.fetch_add(1); t < tiles; t = nextTile.fetch_add(1)) {
      const int tx0 = (t % tilesX) * kTile, ty0 = (t / tilesX) * kTile;
      const int tw = std::min(kTile, view.width - tx0), th = std::min(kTile, view.height - ty0);
      if (clearIfEmpty(s.bins, chunks, t, out.data(), view.width, tx0, ty0, tw, th)) continue;
      startTile(tile, tx0, ty0, tw, th, view.width, view.farClip, depth, depthA, depthB);
      int live = tw * th;
      for (int c = 0; c < chunks && live > 0; ++c) {
        for (const Prepared& binned :
             s.bins[static_cast<std::size_t>(c)][static_cast<std::size_t>(t)]) {
          composite(binned, tx0, ty0, tw, th, f.nearClip, tile, live);
          if (live <= 0) break;
        }
      }
      writeTile(tile, out.data(), view.width, tx0, ty0, tw, th);
    }
  };

  runOnThreads(threads_, work);
}

}  // namespace gs::render::detail
