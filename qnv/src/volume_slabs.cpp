// The gradient step of the volume encoder over slabs (qnv/volume_slabs.hpp). The
// arithmetic is volume_encoder.cpp's, expression for expression, so that the vectors are
// bit-identical to encodeVolume's before quantization.
#include "qnv/volume_slabs.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <thread>

#include "qnv/error.hpp"
#include "qnv/record.hpp"

namespace gs::qnv {

namespace {

// volume_encoder.cpp's difference(): central difference along one axis at index i of n
// samples `stride` apart, divided by the distance between the samples used.
float difference(const float* s, std::size_t stride, std::uint32_t i, std::uint32_t n,
                 float spacing) {
  if (n < 2) return 0.0f;
  if (i == 0) return (s[stride] - s[0]) / spacing;
  if (i + 1 == n) return (s[0] - s[-static_cast<std::ptrdiff_t>(stride)]) / spacing;
  return (s[stride] - s[-static_cast<std::ptrdiff_t>(stride)]) / (2.0f * spacing);
}

void checkRange(const VolumeGridInfo& info, std::uint32_t z0, std::uint32_t z1, const char* what) {
  if (!(z0 < z1 && z1 <= info.dims.z))
    throw InputError(std::string(what) +
                     ": expected slices 0 <= z0 < z1 <= " + std::to_string(info.dims.z) +
                     ", got [" + std::to_string(z0) + ", " + std::to_string(z1) + ")");
}

// The part of a slab one worker computes: rows [rowBegin, rowEnd) of the slab, a row
// being (z, y) with rows counted from the slab's first slice.
struct Chunk {
  std::uint64_t rowBegin = 0, rowEnd = 0;
  std::vector<VolumeVector> vectors;
};

struct SlabContext {
  VolumeGridInfo info;
  const float* window;  // slices [windowZ0, ...) of the volume
  std::uint32_t windowZ0;
  std::uint32_t slabZ0;
  float lo, hi, valueScale;
};

void computeChunk(const SlabContext& c, Chunk& chunk) {
  const glm::uvec3 d = c.info.dims;
  const glm::vec3 spacing = c.info.spacing;
  const std::size_t sliceStride = std::size_t{d.x} * d.y;
  chunk.vectors.clear();
  for (std::uint64_t r = chunk.rowBegin; r < chunk.rowEnd; ++r) {
    const std::uint32_t z = c.slabZ0 + static_cast<std::uint32_t>(r / d.y);
    const std::uint32_t y = static_cast<std::uint32_t>(r % d.y);
    const float* s = c.window + std::size_t{d.x} * (y + std::size_t{d.y} * (z - c.windowZ0));
    const std::uint64_t row = std::uint64_t{d.x} * (y + std::uint64_t{d.y} * z);
    for (std::uint32_t x = 0; x < d.x; ++x) {
      const float v = s[x];
      if (!(v >= c.lo && v <= c.hi)) continue;
      const float gx = difference(s + x, 1, x, d.x, spacing.x);
      const float gy = difference(s + x, d.x, y, d.y, spacing.y);
      const float gz = difference(s + x, sliceStride, z, d.z, spacing.z);
      const float m = std::sqrt(gx * gx + gy * gy + gz * gz);
      if (!(m > 0.0f && std::isfinite(m))) continue;
      VolumeVector out;
      out.position = c.info.origin + glm::vec3(x, y, z) * spacing;
      out.gradient = glm::vec3(gx, gy, gz);
      out.magnitude = m;
      out.value = v;
      out.index = row + x;
      const float slice = (v - c.lo) * c.valueScale;
      out.color =
          static_cast<std::uint8_t>(std::clamp(slice, 0.0f, static_cast<float>(kPaletteSize - 1)));
      chunk.vectors.push_back(out);
    }
  }
}

}  // namespace

MemoryVolumeSlabs::MemoryVolumeSlabs(const Volume& volume) : volume_(volume) {
  if (volume.samples.size() != volume.voxelCount() || volume.voxelCount() == 0)
    throw InputError("in-memory volume of " + std::to_string(volume.dims.x) + "x" +
                     std::to_string(volume.dims.y) + "x" + std::to_string(volume.dims.z) +
                     " voxels holds " + std::to_string(volume.samples.size()) + " samples");
  info_.dims = volume.dims;
  info_.spacing = volume.spacing;
  info_.origin = volume.origin;
  info_.sourceType = volume.sourceType;
}

void MemoryVolumeSlabs::readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) {
  checkRange(info_, z0, z1, "in-memory volume");
  const std::size_t slice = static_cast<std::size_t>(info_.sliceVoxels());
  out.assign(volume_.samples.begin() + static_cast<std::ptrdiff_t>(slice * z0),
             volume_.samples.begin() + static_cast<std::ptrdiff_t>(slice * z1));
}

Volume readWholeVolume(VolumeSlabReader& reader) {
  const VolumeGridInfo& info = reader.info();
  if (info.voxelCount() > kMaxVoxels)
    throw InputError("volume of " + std::to_string(info.dims.x) + "x" +
                     std::to_string(info.dims.y) + "x" + std::to_string(info.dims.z) +
                     " voxels is more than the limit of " + std::to_string(kMaxVoxels) +
                     " voxels (qnv::kMaxVoxels) for a whole volume; read it slab by slab");
  Volume v;
  v.dims = info.dims;
  v.spacing = info.spacing;
  v.origin = info.origin;
  v.sourceType = info.sourceType;
  reader.readSlices(0, info.dims.z, v.samples);
  return v;
}

std::pair<float, float> volumeValueRange(VolumeSlabReader& reader, std::uint32_t slabSlices) {
  const std::uint32_t dz = reader.info().dims.z;
  slabSlices = std::max<std::uint32_t>(slabSlices, 1);
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  std::vector<float> buffer;
  for (std::uint32_t z = 0; z < dz; z += std::min(slabSlices, dz - z)) {
    reader.readSlices(z, z + std::min(slabSlices, dz - z), buffer);
    for (float v : buffer)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  if (lo > hi) lo = hi = 0.0f;
  return {lo, hi};
}

std::uint32_t slabSlicesForMemory(const VolumeGridInfo& info, std::uint64_t memoryBytes) {
  const std::uint64_t slice = std::max<std::uint64_t>(info.sliceVoxels(), 1);
  // Window: the slab and its two neighbours; fresh: the slab's new slices; next: the
  // next slab's, read ahead; vectors: one per voxel of the slab at worst.
  const std::uint64_t fixed = 2 * slice * sizeof(float);
  const std::uint64_t perSlice = slice * (3 * sizeof(float) + sizeof(VolumeVector));
  std::uint64_t slab = memoryBytes > fixed ? (memoryBytes - fixed) / perSlice : 0;
  slab = std::clamp<std::uint64_t>(slab, 1, std::max<std::uint32_t>(info.dims.z, 1));
  return static_cast<std::uint32_t>(slab);
}

VolumeVectorSummary forEachVolumeVector(VolumeSlabReader& reader, std::uint32_t z0,
                                        std::uint32_t z1, const VolumeVectorOptions& options,
                                        const VolumeVectorCallback& callback) {
  const VolumeGridInfo info = reader.info();
  checkRange(info, z0, z1, "gradient slab range");
  const glm::vec3 spacing = info.spacing;
  if (!(spacing.x > 0.0f && spacing.y > 0.0f && spacing.z > 0.0f))
    throw InputError("voxel spacing must be positive");

  VolumeVectorSummary summary;
  summary.slabSlices = options.slabSlices > 0 ? std::min(options.slabSlices, info.dims.z)
                                              : slabSlicesForMemory(info, options.memoryBytes);
  std::pair<float, float> domain;
  if (options.valueWindow)
    domain = *options.valueWindow;
  else if (options.valueRange)
    domain = *options.valueRange;
  else if (info.valueRange)
    domain = *info.valueRange;
  else
    domain = volumeValueRange(reader, summary.slabSlices);
  if (!(domain.first <= domain.second)) throw InputError("value window is empty");
  summary.colorDomain = domain;

  SlabContext context;
  context.info = info;
  context.lo = domain.first;
  context.hi = domain.second;
  context.valueScale = context.hi > context.lo ? kPaletteSize / (context.hi - context.lo) : 0.0f;

  unsigned threads = options.threads > 0 ? options.threads : std::thread::hardware_concurrency();
  threads = std::clamp(threads, 1u, 256u);
  std::vector<Chunk> chunks(threads);

  const std::size_t slice = static_cast<std::size_t>(info.sliceVoxels());
  std::vector<float> window, fresh, next;
  // The next slab's new slices are read by `prefetch` while this slab's vectors are
  // computed and handed out (declared after the buffers: it is joined before they go).
  std::uint32_t nextZ0 = 0, nextZ1 = 0;
  std::exception_ptr prefetchError;
  std::jthread prefetch;
  std::uint32_t windowZ0 = 0, windowZ1 = 0;  // slices held in `window`
  for (std::uint32_t zs = z0; zs < z1;) {
    const std::uint32_t ze = zs + std::min(summary.slabSlices, z1 - zs);
    const std::uint32_t needZ0 = zs > 0 ? zs - 1 : 0;
    const std::uint32_t needZ1 = std::min(ze + 1, info.dims.z);
    // Keep the slices of the previous window that this one needs, read the rest.
    std::uint32_t keepZ0 = needZ0, keepZ1 = needZ0;
    if (windowZ1 > windowZ0 && needZ0 >= windowZ0 && needZ0 < windowZ1) {
      keepZ1 = std::min(windowZ1, needZ1);
      std::memmove(window.data(), window.data() + slice * (needZ0 - windowZ0),
                   slice * (keepZ1 - keepZ0) * sizeof(float));
    }
    window.resize(slice * (needZ1 - needZ0));
    if (prefetch.joinable()) {
      prefetch.join();
      if (prefetchError) std::rethrow_exception(prefetchError);
    }
    if (keepZ1 < needZ1) {
      if (nextZ0 == keepZ1 && nextZ1 == needZ1)
        fresh.swap(next);
      else
        reader.readSlices(keepZ1, needZ1, fresh);
      std::memcpy(window.data() + slice * (keepZ1 - needZ0), fresh.data(),
                  fresh.size() * sizeof(float));
    }
    windowZ0 = needZ0;
    windowZ1 = needZ1;
    nextZ0 = nextZ1 = 0;
    if (ze < z1) {
      const std::uint32_t following = ze + std::min(summary.slabSlices, z1 - ze);
      const std::uint32_t from = needZ1, to = std::min(following + 1, info.dims.z);
      if (from < to) {
        prefetch = std::jthread([&reader, &next, &prefetchError, from, to] {
          try {
            reader.readSlices(from, to, next);
          } catch (...) {
            prefetchError = std::current_exception();
          }
        });
        nextZ0 = from;
        nextZ1 = to;
      }
    }

    context.window = window.data();
    context.windowZ0 = windowZ0;
    context.slabZ0 = zs;
    const std::uint64_t rows = std::uint64_t{ze - zs} * info.dims.y;
    const std::uint64_t used = std::min<std::uint64_t>(threads, rows);
    for (std::uint64_t t = 0; t < used; ++t) {
      chunks[t].rowBegin = rows * t / used;
      chunks[t].rowEnd = rows * (t + 1) / used;
      const std::size_t worst = static_cast<std::size_t>((chunks[t].rowEnd - chunks[t].rowBegin) *
                                                         std::uint64_t{info.dims.x});
      if (chunks[t].vectors.capacity() < worst) chunks[t].vectors.reserve(worst);
    }
    if (used == 1) {
      computeChunk(context, chunks[0]);
    } else {
      std::vector<std::exception_ptr> errors(used);
      std::vector<std::thread> workers;
      workers.reserve(used);
      for (std::uint64_t t = 0; t < used; ++t)
        workers.emplace_back([&, t] {
          try {
            computeChunk(context, chunks[t]);
          } catch (...) {
            errors[t] = std::current_exception();
          }
        });
      for (std::thread& w : workers) w.join();
      for (const std::exception_ptr& e : errors)
        if (e) std::rethrow_exception(e);
    }
    for (std::uint64_t t = 0; t < used; ++t) {
      summary.vectors += chunks[t].vectors.size();
      if (!chunks[t].vectors.empty()) callback(chunks[t].vectors);
    }
    summary.voxels += std::uint64_t{ze - zs} * slice;
    zs = ze;
  }
  return summary;
}

}  // namespace gs::qnv
