// A scalar volume as the volume encoder consumes it (paper section 3.2: one gradient
// vector per voxel). The readers of formats/ (NRRD, NIfTI-1, raw) produce it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace gs::qnv {

/// The sample type a volume file declared; samples are converted to float on reading.
enum class ScalarType {
  int8,
  uint8,
  int16,
  uint16,
  int32,
  uint32,
  int64,
  uint64,
  float32,
  float64
};

/// Bytes per sample of `type` (1..8).
std::size_t scalarBytes(ScalarType type);

/// Samples on a regular grid, x fastest, then y, then z:
/// samples[x + dims.x * (y + dims.y * z)]. spacing is the distance between neighbouring
/// samples along each axis (file units, > 0); origin is the position of sample (0,0,0).
/// Invariant: samples.size() == dims.x * dims.y * dims.z, each dim >= 1.
struct Volume {
  glm::uvec3 dims{0, 0, 0};
  glm::vec3 spacing{1, 1, 1};
  glm::vec3 origin{0, 0, 0};
  std::vector<float> samples;
  ScalarType sourceType = ScalarType::float32;

  std::size_t voxelCount() const {
    return std::size_t{dims.x} * std::size_t{dims.y} * std::size_t{dims.z};
  }
  float at(std::uint32_t x, std::uint32_t y, std::uint32_t z) const {
    return samples[x + std::size_t{dims.x} * (y + std::size_t{dims.y} * z)];
  }
};

/// Readers refuse volumes above this many voxels (2^30, 4 GiB of floats) with InputError.
inline constexpr std::size_t kMaxVoxels = std::size_t{1} << 30;

}  // namespace gs::qnv
