// Private to render/: X3D's TextureCoordinateGenerator (ISO/IEC 19775-1 X3D 4.0 clause
// 18.4.8) as the surface vertex shader makes its coordinates (shaders.cpp,
// generatedTexCoord): the mode numbers both sides share.
#pragma once

#include "vrml/node.hpp"

#include <string>

namespace gs::render::detail {

/// How texture coordinates are generated; 0 means they are read from the mesh.
enum class TexGenMode : int {
  none = 0,
  sphere = 1,                 // SPHERE: sphere map of the eye-space reflection
  cameraSpaceNormal = 2,      // CAMERASPACENORMAL: (x, y) of the eye-space normal
  cameraSpacePosition = 3,    // CAMERASPACEPOSITION: (x, y) of the eye-space position
  cameraSpaceReflection = 4,  // CAMERASPACEREFLECTIONVECTOR
  sphereLocal = 5,            // SPHERE-LOCAL: the local normal mapped to [0, 1]
  coord = 6,                  // COORD (NOISE is drawn as COORD)
  coordEye = 7,               // COORD-EYE (NOISE-EYE is drawn as COORD-EYE)
  sphereRefract = 8,          // SPHERE-REFLECT(-LOCAL): sphere map of the refraction
  worldSpaceReflection = 9,   // castle-model-viewer's WORLDSPACEREFLECTIONVECTOR
  worldSpaceNormal = 10,      // castle-model-viewer's WORLDSPACENORMAL
};

struct TexGen {
  TexGenMode mode = TexGenMode::none;
  float parameter = 1.0f;  // SPHERE-REFLECT's index of refraction (parameter[0])
  std::string problem;     // a mode drawn as another one, or unknown: for a warning
};

/// The generation `geometry`'s texCoord field asks for: none unless it holds a
/// TextureCoordinateGenerator. Its mode is matched exactly (X3D's names; "SPHERE" when
/// empty); an unknown mode reads as SPHERE, the clause's default, with a problem.
TexGen texGenOf(const vrml::Node& geometry);

}  // namespace gs::render::detail
