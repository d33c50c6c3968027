#pragma once
// Automatic level of detail of a window viewport: the controller that holds a frame-time
// target by moving the drawn fraction of the QNV vectors (paper section 3.6: a prefix of a
// magnitude-sorted stream is the best picture of its size). Pure functions, no GL.

#include <cstdint>

namespace gs::app {

/// The vectors a viewport may draw in its next frame: `userBudget` (0: none) capped at
/// what the measured rate draws in twice the target, `splatRate` (splats per second the
/// last frame drew, 0 when none was measured) times 2 * `targetSeconds` (> 0). Before a
/// rate is known the cap is kFirstFrameVectors. Returns 0 for "no budget" only when
/// neither applies. At least kMinAutoVectors, so the picture never goes empty.
std::uint64_t autoLodBudget(std::uint64_t userBudget, double splatRate, double targetSeconds);

/// The factor by which the fraction moves after a frame that took `takenSeconds` (> 0)
/// against `targetSeconds`: sqrt(target / taken) clamped to [0.5, 2] (damped), except
/// that a frame over twice its target drops by target / taken at once (no damping, at
/// least /64 a frame), so one slow frame is followed by a fast one.
double autoLodRatio(double targetSeconds, double takenSeconds);

/// The cap before any frame was measured: 250,000 vectors (about 0.1 s through llvmpipe
/// on two cores at 512x512, docs/rendering.md).
inline constexpr std::uint64_t kFirstFrameVectors = 250'000;
/// The smallest cap the rate gives: 1,000 vectors.
inline constexpr std::uint64_t kMinAutoVectors = 1'000;

}  // namespace gs::app
