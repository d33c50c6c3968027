#include "qnv/surface_tileset.hpp"

#include "histogram_crossing.hpp"

#include <algorithm>
#include <bit>
#include <limits>
#include <utility>
#include <vector>

#include <glm/common.hpp>

#include "qnv/error.hpp"

namespace gs::qnv {

namespace {

constexpr std::size_t kBins = std::size_t{1} << 16;

// Distinct colours and their counts in an open-addressing table of 64-bit slots
// (key << 32 | count; 0 is empty, since a counted colour has count >= 1; counts stay
// below 2^32 as triangles do), at most half full: 8 to 24 bytes a colour.
class ColorCounter {
 public:
  explicit ColorCounter(std::uint64_t maxColors) : maxColors_(maxColors) {}
  // False once more than maxColors distinct colours were seen (the table is then dropped).
  bool add(std::uint32_t key) {
    if (full_) return false;
    if (2 * (size_ + 1) > slots_.size()) grow();
    if (full_) return false;
    std::uint64_t* slot = find(key);
    if (*slot == 0) {
      *slot = (std::uint64_t{key} << 32) | 1u;
      ++size_;
    } else {
      ++*slot;
    }
    return true;
  }
  bool full() const { return full_; }
  std::uint64_t size() const { return size_; }
  // The counts, and the table freed.
  std::vector<std::pair<std::uint32_t, std::uint64_t>> take() {
    std::vector<std::pair<std::uint32_t, std::uint64_t>> out;
    out.reserve(size_);
    for (std::uint64_t s : slots_)
      if (s != 0) out.push_back({static_cast<std::uint32_t>(s >> 32), s & 0xffffffffu});
    slots_ = {};
    size_ = 0;
    return out;
  }

 private:
  std::uint64_t* find(std::uint32_t key) {
    const std::size_t mask = slots_.size() - 1;
    for (std::size_t i = (key * std::uint64_t{0x9E3779B97F4A7C15}) >> 20 & mask;;
         i = (i + 1) & mask)
      if (slots_[i] == 0 || (slots_[i] >> 32) == key) return &slots_[i];
  }
  void grow() {
    if (size_ + 1 > maxColors_) {
      full_ = true;
      slots_ = {};
      return;
    }
    std::vector<std::uint64_t> old = std::exchange(slots_, {});
    slots_.assign(std::max<std::size_t>(64, 2 * old.size()), 0);
    for (std::uint64_t s : old)
      if (s != 0) *find(static_cast<std::uint32_t>(s >> 32)) = s;
  }

  std::uint64_t maxColors_;
  std::vector<std::uint64_t> slots_;
  std::uint64_t size_ = 0;
  bool full_ = false;
};

// The box, area range and colour counts of the triangles measured, as
// selectSurfaceVectors computes them over its kept set.
struct Measure {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{std::numeric_limits<float>::lowest()};
  float aMin = std::numeric_limits<float>::max(), aMax = 0.0f;
  std::uint64_t count = 0;
  ColorCounter colors;

  explicit Measure(std::uint64_t maxColors) : colors(maxColors) {}
  void add(const SourceVector& v, const Rgba8& color) {
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
    aMin = std::min(aMin, v.magnitude);
    aMax = std::max(aMax, v.magnitude);
    ++count;
    colors.add(paletteKey(color));
  }
};

}  // namespace

SurfaceSelectionPlan planSurfaceSelection(TriangleSoupReader& soup,
                                          const SurfaceEncodeOptions& options,
                                          std::uint64_t maxColors) {
  const std::uint64_t triangles = soup.triangleCount();
  if (triangles > std::numeric_limits<std::uint32_t>::max())
    throw InputError("too many triangles to encode (" + std::to_string(triangles) + ")");

  // Pass 1: candidates, the histogram of the upper 16 bits, and every candidate measured
  // (what keeping all needs).
  std::vector<std::uint64_t> coarse(kBins, 0);
  Measure all(maxColors);
  soup.forEachTriangle([&](std::uint64_t first, std::span<const SurfaceTriangle> batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      SourceVector v;
      if (!triangleVector(batch[i].a, batch[i].b, batch[i].c, first + i, v)) continue;
      ++coarse[std::bit_cast<std::uint32_t>(v.magnitude) >> 16];
      all.add(v, batch[i].color);
    }
  });
  const std::uint64_t candidates = all.count;

  SurfaceSelectionPlan plan;
  const std::uint64_t kept = std::min(options.selection.keepOf(triangles), candidates);
  plan.summary = {triangles, candidates, kept};
  Measure keptMeasure(maxColors);
  Measure* measured = &all;
  if (kept == 0 && candidates > 0) {  // keep none
    plan.keepAll = false;
    plan.threshold = std::numeric_limits<float>::infinity();
  } else if (kept < candidates) {
    // Pass 2: the lower 16 bits inside the crossing bin.
    plan.keepAll = false;
    plan.passes = 3;
    const auto [bin, above] =
        detail::histogramCrossing(coarse, kept, "area histogram holds fewer triangles");
    std::vector<std::uint64_t> fine(kBins, 0);
    soup.forEachTriangle(
        [&, bin = bin](std::uint64_t first, std::span<const SurfaceTriangle> batch) {
          for (std::size_t i = 0; i < batch.size(); ++i) {
            SourceVector v;
            if (!triangleVector(batch[i].a, batch[i].b, batch[i].c, first + i, v)) continue;
            const std::uint32_t bits = std::bit_cast<std::uint32_t>(v.magnitude);
            if ((bits >> 16) == bin) ++fine[bits & 0xffffu];
          }
        });
    const auto [low, aboveFine] =
        detail::histogramCrossing(fine, kept - above, "area histogram holds fewer triangles");
    plan.threshold = std::bit_cast<float>(static_cast<std::uint32_t>((bin << 16) | low));
    plan.tiesKept = kept - above - aboveFine;
    // Pass 3: the kept triangles' box, area range and colours.
    all.colors.take();  // pass 1's colours are not needed: freed
    SurfaceKeepFilter filter(plan);
    soup.forEachTriangle([&](std::uint64_t first, std::span<const SurfaceTriangle> batch) {
      for (std::size_t i = 0; i < batch.size(); ++i) {
        SourceVector v;
        if (!triangleVector(batch[i].a, batch[i].b, batch[i].c, first + i, v)) continue;
        if (filter.keep(v.magnitude)) keptMeasure.add(v, batch[i].color);
      }
    });
    measured = &keptMeasure;
  }
  if (kept == 0) measured = &keptMeasure;  // nothing kept: the empty measure
  if (measured->colors.full())
    throw InputError("the kept triangles have more than " + std::to_string(maxColors) +
                     " distinct colours, more than --memory allows to count (raise it)");

  StreamHeader& h = plan.header;
  h.kind = StreamKind::surface;
  h.mapping = options.mapping;
  h.profile = options.profile;
  if (measured->count == 0) {
    h.boundsMin = h.boundsMax = glm::vec3(0.0f);
    h.magnitudeMin = h.magnitudeMax = 1.0f;
  } else {
    h.boundsMin = measured->lo;
    h.boundsMax = measured->hi;
    h.magnitudeMin = measured->aMin;
    h.magnitudeMax = measured->aMax;
  }
  plan.palette = buildPaletteFromCounts(measured->colors.take());
  h.palette = plan.palette.palette;
  h.vectorCount = kept;
  return plan;
}

}  // namespace gs::qnv
