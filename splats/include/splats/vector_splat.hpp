// A QNV vector as a Gaussian splat (issue 40 item 1; docs/splats.md): a flat disc whose
// normal is the vector's direction, isotropic in its plane, with the paper's opacity
// profile (Nagasawa, "Beyond VRML", section 3.1). render/splat_model.hpp draws vectors
// with it; splats/merged_levels.hpp merges them into the Gaussians of a tileset's merged
// levels. Units: world units (metres).
#pragma once

#include "qnv/stream.hpp"

namespace gs::splats {

/// The opacity profile of one QNV vector (Nagasawa section 3.1; render/splat_model.hpp
/// draws it): the disc's in-plane standard deviation `spread` (world units) and `peak`
/// opacity (0..1).
struct VectorProfile {
  float spread = 0.0f;
  float peak = 0.0f;
};

/// Surfaces (`surface` true): the disk of area A has radius R = sqrt(A / pi); spread =
/// 2 sigma R, peak = opacityScale * A / (2 pi spread^2) * transferAlpha, so the integrated
/// opacity is A. Volumes: spread = 2 sigma voxelSize, peak = opacityScale * transferAlpha *
/// sqrt(A / magnitudeMax). Peak clamped to [0, 1]; A (magnitude) >= 0, magnitudeMax > 0.
VectorProfile vectorProfile(bool surface, float sigma, float opacityScale, float voxelSize,
                            float magnitudeMax, float magnitude, float transferAlpha);

/// The least opacity a vector's splat draws at (render/src/splat_cpu.cpp skips weaker
/// vectors and pixels; so does the merge of splats/merged_levels.hpp, to draw the same haze).
inline constexpr float kVisiblePeak = 0.5f / 255.0f;

/// vectorProfile for a vector of a stream with header `h` (its kind, profile and spacing).
VectorProfile vectorProfile(const qnv::StreamHeader& h, float magnitude, float transferAlpha);

}  // namespace gs::splats
