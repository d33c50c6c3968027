// Depth sorting of QNV splats for compositing (Nagasawa, "Beyond VRML", section 3.1,
// equation (1) composites the vectors in depth order). Pure CPU code, no OpenGL: the
// splat pass and the CPU reference (splat_reference.hpp) both order splats with it.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/mat4x4.hpp>

#include "qnv/decoder.hpp"

namespace gs::render {

/// Orders vectors by the eye-space depth of their positions: z = (view * (position, 1)).z,
/// more negative = farther (OpenGL eye space looks down -Z).
///
/// Algorithm: an LSD radix sort of 32-bit keys made from the float depth (the sign-flip
/// trick makes the unsigned key order the float order; -0 counts as +0), 3 passes of
/// 11 bits with all three histograms built in the key pass, a pass skipped when every key
/// shares its digit. It is stable: vectors of equal depth keep their index order in both
/// directions. Cost: about 5 sequential passes over 4-byte arrays plus one read of the
/// vectors; single thread.
///
/// Memory: the scratch buffers (two key arrays and one index array, 12 bytes per vector)
/// live in the object and only grow. After the first call with a given count (or after
/// reserve()) a call with that count or fewer allocates nothing, and `order` is resized
/// only when its size differs from the count, so a renderer that keeps one DepthSorter
/// and one `order` vector per stream does no allocation per frame.
///
/// A NaN depth (a NaN position or matrix) counts as the farthest of all (first back to
/// front, last front to back), deterministically. Not thread-safe: one sorter per thread.
class DepthSorter {
 public:
  DepthSorter() = default;

  /// `order` receives the indices 0..n-1 of the first n = min(count, vectors.size())
  /// vectors, farthest first (ascending eye-space z). Throws std::length_error for
  /// n >= 2^32 (indices are 32-bit).
  void sortBackToFront(std::span<const qnv::DecodedVector> vectors, const glm::mat4& view,
                       std::vector<std::uint32_t>& order, std::size_t count = kAll);
  /// As sortBackToFront, nearest first (descending eye-space z).
  void sortFrontToBack(std::span<const qnv::DecodedVector> vectors, const glm::mat4& view,
                       std::vector<std::uint32_t>& order, std::size_t count = kAll);

  /// As sortFrontToBack for bare centres (a splats::GaussianCloud's positions): `order`
  /// receives 0..n-1 of the first n = min(count, positions.size()) nearest first.
  void sortFrontToBack(std::span<const glm::vec3> positions, const glm::mat4& view,
                       std::vector<std::uint32_t>& order, std::size_t count = kAll);

  /// Grows the scratch buffers to hold `count` vectors now, so the first frame does not
  /// allocate either.
  void reserve(std::size_t count);
  /// Bytes of scratch memory held (12 per vector of the largest count seen).
  std::size_t scratchBytes() const;

  /// Where the scratch buffers are, to check that a call did not reallocate (tests).
  struct ScratchInfo {
    const void* keys = nullptr;
    const void* keysAlt = nullptr;
    const void* indices = nullptr;
    std::size_t capacity = 0;  // vectors the buffers hold without allocating
  };
  ScratchInfo scratch() const;

  /// "All vectors of the span".
  static constexpr std::size_t kAll = static_cast<std::size_t>(-1);

 private:
  /// The sort of n positions `stride` bytes apart, starting at `positions`.
  void sort(const unsigned char* positions, std::size_t stride, std::size_t n,
            const glm::mat4& view, std::vector<std::uint32_t>& order, bool frontToBack);

  std::vector<std::uint32_t> keys_;
  std::vector<std::uint32_t> keysAlt_;
  std::vector<std::uint32_t> indices_;
};

}  // namespace gs::render
