#include "splats/vector_splat.hpp"

#include <algorithm>
#include <cmath>

namespace gs::splats {

VectorProfile vectorProfile(bool surface, float sigma, float opacityScale, float voxelSize,
                            float magnitudeMax, float magnitude, float transferAlpha) {
  VectorProfile p;
  if (surface) {
    const float radius = std::sqrt(std::max(magnitude, 0.0f) / 3.14159265f);
    p.spread = 2.0f * sigma * radius;
    p.peak = p.spread > 0.0f ? opacityScale * magnitude / (2.0f * 3.14159265f * p.spread * p.spread)
                             : 0.0f;
    p.peak *= transferAlpha;
  } else {
    p.spread = 2.0f * sigma * voxelSize;
    p.peak =
        opacityScale * transferAlpha * std::sqrt(std::clamp(magnitude / magnitudeMax, 0.0f, 1.0f));
  }
  p.peak = std::clamp(p.peak, 0.0f, 1.0f);
  return p;
}

VectorProfile vectorProfile(const qnv::StreamHeader& h, float magnitude, float transferAlpha) {
  return vectorProfile(h.kind == qnv::StreamKind::surface, h.profile.sigma, h.profile.opacityScale,
                       std::max({h.voxelSpacing.x, h.voxelSpacing.y, h.voxelSpacing.z, 1e-6f}),
                       std::max(h.magnitudeMax, 1e-30f), magnitude, transferAlpha);
}

}  // namespace gs::splats
