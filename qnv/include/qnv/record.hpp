// The QNV record: one quantized normal vector in 64 bits, exactly the layout of figure 6
// of Nagasawa, "Beyond VRML" (section 3.6). docs/qnv-format.md pins bit order, rounding
// and reconstruction; this header is its code.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include <glm/vec3.hpp>

namespace gs::qnv {

/// Field widths in bits (figure 6): 10 + 10 + 10 + 5 + 6 + 15 + 8 = 64.
inline constexpr int kPositionBits = 10;
inline constexpr int kThetaBits = 5;
inline constexpr int kPhiBits = 6;
inline constexpr int kMagnitudeBits = 15;
inline constexpr int kColorBits = 8;

inline constexpr std::uint32_t kPositionSteps = 1u << kPositionBits;    // 1024 per axis
inline constexpr std::uint32_t kThetaSteps = 1u << kThetaBits;          // 32 over [0, pi]
inline constexpr std::uint32_t kPhiSteps = 1u << kPhiBits;              // 64 over [0, 2 pi)
inline constexpr std::uint32_t kMagnitudeSteps = 1u << kMagnitudeBits;  // 32768
inline constexpr std::uint32_t kPaletteSize = 1u << kColorBits;         // 256
/// theta and phi together index one of 2048 direction cells.
inline constexpr std::uint32_t kDirectionCells = kThetaSteps * kPhiSteps;

/// The seven integer fields of one record, each within its range
/// (x, y, z < 1024; theta < 32; phi < 64; a < 32768; c < 256).
struct RecordFields {
  std::uint16_t x = 0, y = 0, z = 0;
  std::uint8_t theta = 0, phi = 0;
  std::uint16_t a = 0;
  std::uint8_t c = 0;
  bool operator==(const RecordFields&) const = default;
};

/// Packs the fields most significant first: X bits 63..54, Y 53..44, Z 43..34,
/// Theta 33..29, Phi 28..23, A 22..8, C 7..0. Out-of-range fields are masked to their
/// width. In a .qnv file the 64-bit word is stored little-endian.
constexpr std::uint64_t packRecord(const RecordFields& f) {
  return (std::uint64_t{f.x & 1023u} << 54) | (std::uint64_t{f.y & 1023u} << 44) |
         (std::uint64_t{f.z & 1023u} << 34) | (std::uint64_t{f.theta & 31u} << 29) |
         (std::uint64_t{f.phi & 63u} << 23) | (std::uint64_t{f.a & 32767u} << 8) |
         std::uint64_t{f.c};
}

/// Inverse of packRecord; every 64-bit word is a valid record.
constexpr RecordFields unpackRecord(std::uint64_t r) {
  return {static_cast<std::uint16_t>((r >> 54) & 1023u),
          static_cast<std::uint16_t>((r >> 44) & 1023u),
          static_cast<std::uint16_t>((r >> 34) & 1023u),
          static_cast<std::uint8_t>((r >> 29) & 31u),
          static_cast<std::uint8_t>((r >> 23) & 63u),
          static_cast<std::uint16_t>((r >> 8) & 32767u),
          static_cast<std::uint8_t>(r & 255u)};
}

/// The 11-bit direction cell (theta << 6 | phi) of a packed record: bits 33..23.
constexpr std::uint32_t directionCell(std::uint64_t r) {
  return static_cast<std::uint32_t>((r >> 23) & 2047u);
}
/// The 15-bit magnitude code of a packed record.
constexpr std::uint32_t magnitudeCode(std::uint64_t r) {
  return static_cast<std::uint32_t>((r >> 8) & 32767u);
}

/// Quantizes one coordinate into 1024 cells over [lo, hi]:
/// floor((v - lo) / (hi - lo) * 1024) clamped to 0..1023; 0 when hi <= lo or v is NaN.
std::uint16_t quantizeCoordinate(float v, float lo, float hi);
/// Cell centre of `q`: lo + (q + 0.5) * (hi - lo) / 1024. Error at most half a step.
float reconstructCoordinate(std::uint32_t q, float lo, float hi);

/// Quantizes a direction (any non-zero length; normalized here) into theta (polar angle
/// from +Z, 32 cells over [0, pi]) and phi (azimuth from +X towards +Y, 64 cells over
/// [0, 2 pi)), each floor(angle / step). A zero or non-finite vector gives (0, 0).
void quantizeDirection(const glm::vec3& d, std::uint8_t& theta, std::uint8_t& phi);
/// Unit vector at the centre of direction cell (theta, phi): angles (t + 0.5) * pi / 32
/// and (p + 0.5) * 2 pi / 64. Any direction is within acos(cos^2(pi/64)) = 3.977 degrees
/// of its cell centre (the worst case is a corner of an equatorial cell), which is under
/// the angular step of pi/32 = 5.625 degrees.
glm::vec3 reconstructDirection(std::uint32_t theta, std::uint32_t phi);

/// How the 15-bit A code maps to a magnitude (kept in the stream header).
enum class MagnitudeMapping : std::uint8_t {
  /// a = lo * (hi / lo)^((q + 0.5) / 32768); relative error <= (hi / lo)^(1 / 65536) - 1.
  logarithmic = 1,
  /// a = lo + (q + 0.5) * (hi - lo) / 32768; absolute error <= (hi - lo) / 65536.
  linear = 2,
};

/// Quantizes magnitude `a` (> 0) for the range [lo, hi] (0 < lo <= hi). Values outside
/// the range clamp to code 0 or 32767.
std::uint16_t quantizeMagnitude(float a, MagnitudeMapping mapping, float lo, float hi);
/// quantizeMagnitude with the range's logarithm computed once, for encoders.
class MagnitudeQuantizer {
 public:
  MagnitudeQuantizer(MagnitudeMapping mapping, float lo, float hi);
  std::uint16_t operator()(float a) const;

 private:
  MagnitudeMapping mapping_;
  double lo_, scale_;  // code = floor((f(a) - lo_) * scale_), f = ln or identity
};

/// Rounds magnitude code `q` to `bits` significant bits (1..15; 15 leaves it unchanged):
/// the low 15 - bits bits become 100..0, the middle of the coarse cell, so the value
/// reconstructs within half a coarse step (plus half a fine one). Monotone, so records
/// sorted largest first stay sorted. Entropy packets then send the shared low bits once
/// (docs/qnv-format.md, "Shared low bits": `ghostspace encode --magnitude-bits`).
/// Lossy: for a logarithmic range hi / lo the relative error grows to about
/// (hi / lo)^(2^-(bits + 1)) - 1, 0.45% at 10 bits for a range of 10^4.
constexpr std::uint32_t roundMagnitudeCode(std::uint32_t q, int bits) {
  const int drop = kMagnitudeBits - bits;
  if (drop <= 0) return q;
  return ((q >> drop) << drop) | (1u << (drop - 1));
}

/// roundMagnitudeCode on the A field of every record; the other fields are unchanged.
inline void roundMagnitudes(std::span<std::uint64_t> records, int bits) {
  constexpr std::uint64_t kField = std::uint64_t{kMagnitudeSteps - 1} << 8;
  for (std::uint64_t& r : records)
    r = (r & ~kField) | (std::uint64_t{roundMagnitudeCode(magnitudeCode(r), bits)} << 8);
}

/// Cell centre of code q (geometric centre for the logarithmic mapping).
float reconstructMagnitude(std::uint32_t q, MagnitudeMapping mapping, float lo, float hi);

}  // namespace gs::qnv
