// Private to render/: four floats at a time for the CPU splat rasterizers (splat_cpu.cpp,
// gaussian_cpu.cpp), through GCC and Clang vector extensions (SSE on x86-64, NEON on ARM,
// plain code elsewhere).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace gs::render::detail {

using F4 = float __attribute__((vector_size(16)));
using I4 = std::int32_t __attribute__((vector_size(16)));

inline F4 load4(const float* p) {
  F4 v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

inline void store4(float* p, F4 v) {
  std::memcpy(p, &v, sizeof v);
}

/// v where mask is all ones, 0 where it is 0.
inline F4 select4(I4 mask, F4 v) {
  return reinterpret_cast<F4>(mask & reinterpret_cast<I4>(v));
}

/// exp(x) for x in [-8, 0]: 2^n 2^f, n the nearest integer to x log2(e) and f in
/// [-0.5, 0.5], with a degree-4 polynomial for 2^f in Estrin's order; relative error below
/// 6e-5 (5.6e-5 measured, tests/render/test_splat_cpu.cpp).
inline F4 exp4(F4 x) {
  const F4 t = x * 1.44269504f;                        // log2(e); t <= 0
  const I4 n = __builtin_convertvector(t - 0.5f, I4);  // truncated: the nearest
  const F4 f = t - __builtin_convertvector(n, F4);     // [-0.5, 0.5]
  const F4 f2 = f * f;
  const F4 p =
      (1.0f + f * 0.693147181f) + f2 * ((0.240226507f + f * 0.0555041087f) + f2 * 0.00961812911f);
  return p * reinterpret_cast<F4>((n + 127) << 23);
}

/// A channel 0..1 (clamped) as an 8-bit level, rounded.
inline std::uint8_t level8(float c) {
  if (!(c > 0.0f)) return 0;
  return static_cast<std::uint8_t>(std::min(c, 1.0f) * 255.0f + 0.5f);
}

}  // namespace gs::render::detail
