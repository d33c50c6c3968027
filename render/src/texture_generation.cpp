// TextureCoordinateGenerator modes (texture_generation.hpp).
#include "texture_generation.hpp"

#include "scene/node_access.hpp"

#include <string_view>
#include <utility>
#include <vector>

namespace gs::render::detail {

TexGen texGenOf(const vrml::Node& geometry) {
  TexGen out;
  const vrml::NodePtr& tc = geometry.sfnode("texCoord");
  if (!tc || tc->unresolved || tc->typeId() != vrml::NodeTypeId::TextureCoordinateGenerator)
    return out;
  const std::string mode = scene::sfString(*tc, "mode");
  static constexpr std::pair<std::string_view, TexGenMode> kModes[] = {
      {"", TexGenMode::sphere},
      {"SPHERE", TexGenMode::sphere},
      {"CAMERASPACENORMAL", TexGenMode::cameraSpaceNormal},
      {"CAMERASPACEPOSITION", TexGenMode::cameraSpacePosition},
      {"CAMERASPACEREFLECTIONVECTOR", TexGenMode::cameraSpaceReflection},
      {"SPHERE-LOCAL", TexGenMode::sphereLocal},
      {"COORD", TexGenMode::coord},
      {"COORD-EYE", TexGenMode::coordEye},
      {"SPHERE-REFLECT", TexGenMode::sphereRefract},
      {"SPHERE-REFLECT-LOCAL", TexGenMode::sphereRefract},
      {"WORLDSPACEREFLECTIONVECTOR", TexGenMode::worldSpaceReflection},
      {"WORLDSPACENORMAL", TexGenMode::worldSpaceNormal},
  };
  out.mode = TexGenMode::sphere;
  bool known = false;
  for (const auto& [name, m] : kModes)
    if (name == mode) {
      out.mode = m;
      known = true;
    }
  if (mode == "NOISE" || mode == "NOISE-EYE") {
    out.mode = mode == "NOISE" ? TexGenMode::coord : TexGenMode::coordEye;
    out.problem = "TextureCoordinateGenerator mode \"" + mode + "\" is drawn as \"" +
                  (mode == "NOISE" ? "COORD" : "COORD-EYE") + "\" (no noise function)";
  } else if (!known) {
    out.problem = "unknown TextureCoordinateGenerator mode \"" + mode + "\": read as \"SPHERE\"";
  }
  if (out.mode == TexGenMode::sphereRefract) {
    const std::vector<float>& p = scene::mfFloat(*tc, "parameter");
    if (!p.empty() && p[0] > 0.0f) out.parameter = p[0];
  }
  return out;
}

}  // namespace gs::render::detail
