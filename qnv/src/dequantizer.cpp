#include "byte_order.hpp"
#include "qnv/decoder.hpp"

namespace gs::qnv {

Dequantizer::Dequantizer(const StreamHeader& header) : magnitude_(kMagnitudeSteps) {
  for (int axis = 0; axis < 3; ++axis)
    for (std::uint32_t q = 0; q < kPositionSteps; ++q)
      axis_[axis][q] = reconstructCoordinate(q, header.boundsMin[axis], header.boundsMax[axis]);
  for (std::uint32_t t = 0; t < kThetaSteps; ++t)
    for (std::uint32_t p = 0; p < kPhiSteps; ++p)
      direction_[t * kPhiSteps + p] = reconstructDirection(t, p);
  for (std::uint32_t q = 0; q < kMagnitudeSteps; ++q)
    magnitude_[q] =
        reconstructMagnitude(q, header.mapping, header.magnitudeMin, header.magnitudeMax);
  for (std::uint32_t c = 0; c < kPaletteSize; ++c) {
    const Rgba8& rgba = header.palette[c];
    color_[c] = std::uint32_t{rgba.r} | (std::uint32_t{rgba.g} << 8) |
                (std::uint32_t{rgba.b} << 16) | (std::uint32_t{rgba.a} << 24);
  }
}

DecodedVector Dequantizer::decodeOne(std::uint64_t r) const {
  DecodedVector v;
  v.position = {axis_[0][(r >> 54) & 1023u], axis_[1][(r >> 44) & 1023u],
                axis_[2][(r >> 34) & 1023u]};
  v.magnitude = magnitude_[magnitudeCode(r)];
  v.normal = direction_[directionCell(r)];
  v.rgba = color_[r & 255u];
  return v;
}

void Dequantizer::decode(const std::uint64_t* records, std::size_t count,
                         DecodedVector* out) const {
  for (std::size_t i = 0; i < count; ++i) out[i] = decodeOne(records[i]);
}

void Dequantizer::decodeBytes(const char* bytes, std::size_t count, DecodedVector* out) const {
  for (std::size_t i = 0; i < count; ++i)
    out[i] = decodeOne(detail::loadLe<std::uint64_t>(bytes + 8 * i));
}

}  // namespace gs::qnv
