// LSD radix sort of splats by eye-space depth (see splat_sort.hpp).
#include "render/splat_sort.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace gs::render {

namespace {

constexpr int kDigitBits = 11;
constexpr int kPasses = 3;  // 3 x 11 bits >= 32
constexpr std::uint32_t kBuckets = 1u << kDigitBits;
constexpr std::uint32_t kDigitMask = kBuckets - 1u;

inline std::uint32_t digit(std::uint32_t key, int pass) {
  return (key >> (pass * kDigitBits)) & kDigitMask;
}

/// Unsigned key whose order is the order of `z` ascending (farthest first); NaN first of
/// all (as the farthest); -0 and +0 share a key.
inline std::uint32_t depthKey(float z) {
  const float zz = z + 0.0f;  // -0 + +0 = +0
  const std::uint32_t u = std::bit_cast<std::uint32_t>(zz);
  const std::uint32_t mask = (0u - (u >> 31)) | 0x80000000u;
  return zz == zz ? (u ^ mask) : 0u;
}

}  // namespace

void DepthSorter::reserve(std::size_t count) {
  if (count >= (std::size_t{1} << 32)) throw std::length_error("DepthSorter: too many vectors");
  if (keys_.size() < count) keys_.resize(count);
  if (keysAlt_.size() < count) keysAlt_.resize(count);
  if (indices_.size() < count) indices_.resize(count);
}

std::size_t DepthSorter::scratchBytes() const {
  return (keys_.capacity() + keysAlt_.capacity() + indices_.capacity()) * sizeof(std::uint32_t);
}

DepthSorter::ScratchInfo DepthSorter::scratch() const {
  ScratchInfo info;
  info.keys = keys_.data();
  info.keysAlt = keysAlt_.data();
  info.indices = indices_.data();
  info.capacity = std::min({keys_.size(), keysAlt_.size(), indices_.size()});
  return info;
}

void DepthSorter::sortBackToFront(std::span<const qnv::DecodedVector> vectors,
                                  const glm::mat4& view, std::vector<std::uint32_t>& order,
                                  std::size_t count) {
  const std::size_t n = std::min(count, vectors.size());
  sort(reinterpret_cast<const unsigned char*>(vectors.data()) +
           offsetof(qnv::DecodedVector, position),
       sizeof(qnv::DecodedVector), n, view, order, false);
}

void DepthSorter::sortFrontToBack(std::span<const qnv::DecodedVector> vectors,
                                  const glm::mat4& view, std::vector<std::uint32_t>& order,
                                  std::size_t count) {
  const std::size_t n = std::min(count, vectors.size());
  sort(reinterpret_cast<const unsigned char*>(vectors.data()) +
           offsetof(qnv::DecodedVector, position),
       sizeof(qnv::DecodedVector), n, view, order, true);
}

void DepthSorter::sortFrontToBack(std::span<const glm::vec3> positions, const glm::mat4& view,
                                  std::vector<std::uint32_t>& order, std::size_t count) {
  const std::size_t n = std::min(count, positions.size());
  sort(reinterpret_cast<const unsigned char*>(positions.data()), sizeof(glm::vec3), n, view, order,
       true);
}

void DepthSorter::sort(const unsigned char* positions, std::size_t stride, std::size_t n,
                       const glm::mat4& view, std::vector<std::uint32_t>& order, bool frontToBack) {
  reserve(n);
  if (order.size() != n) order.resize(n);
  if (n == 0) return;

  // Keys and the histograms of all passes in one sweep over the vectors. Eye-space z is
  // row 2 of the view matrix applied to (position, 1), summed in glm's order
  // ((m0 x + m1 y) + (m2 z + m3)) so that it equals (view * vec4(position, 1)).z exactly.
  std::array<std::array<std::uint32_t, kBuckets>, kPasses> histogram{};
  const float m0 = view[0][2], m1 = view[1][2], m2 = view[2][2], m3 = view[3][2];
  const std::uint32_t flip = frontToBack ? 0xffffffffu : 0u;  // descending z: invert keys
  std::uint32_t* const keys = keys_.data();
  for (std::size_t i = 0; i < n; ++i) {
    glm::vec3 p;
    std::memcpy(&p, positions + i * stride, sizeof p);
    const float z = (m0 * p.x + m1 * p.y) + (m2 * p.z + m3);
    const std::uint32_t key = depthKey(z) ^ flip;
    keys[i] = key;
    for (int pass = 0; pass < kPasses; ++pass) ++histogram[pass][digit(key, pass)];
  }

  // Passes where every key has the same digit change nothing: skip them.
  std::array<int, kPasses> passes{};
  int passCount = 0;
  for (int pass = 0; pass < kPasses; ++pass) {
    if (histogram[pass][digit(keys[0], pass)] != n) passes[passCount++] = pass;
  }
  if (passCount == 0) {
    std::iota(order.begin(), order.end(), 0u);
    return;
  }

  // Ping-pong: the first pass reads the identity permutation, the last one writes its
  // indices into `order` (so no final copy) and no keys.
  const std::uint32_t* srcKeys = keys;
  const std::uint32_t* srcIndices = nullptr;
  for (int j = 0; j < passCount; ++j) {
    const int pass = passes[j];
    const bool last = j == passCount - 1;
    std::uint32_t* dstKeys = srcKeys == keys ? keysAlt_.data() : keys;
    std::uint32_t* dstIndices = ((passCount - 1 - j) % 2 == 0) ? order.data() : indices_.data();

    std::array<std::uint32_t, kBuckets> offset;
    std::uint32_t sum = 0;
    for (std::uint32_t b = 0; b < kBuckets; ++b) {
      offset[b] = sum;
      sum += histogram[pass][b];
    }
    const int shift = pass * kDigitBits;
    if (srcIndices == nullptr) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t key = srcKeys[i];
        const std::uint32_t at = offset[(key >> shift) & kDigitMask]++;
        dstKeys[at] = key;
        dstIndices[at] = static_cast<std::uint32_t>(i);
      }
    } else if (!last) {
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t key = srcKeys[i];
        const std::uint32_t at = offset[(key >> shift) & kDigitMask]++;
        dstKeys[at] = key;
        dstIndices[at] = srcIndices[i];
      }
    } else {
      for (std::size_t i = 0; i < n; ++i) {
        const std::uint32_t at = offset[(srcKeys[i] >> shift) & kDigitMask]++;
        dstIndices[at] = srcIndices[i];
      }
    }
    srcKeys = dstKeys;
    srcIndices = dstIndices;
  }
}

}  // namespace gs::render
