// The viewer as the execution model sees it (plain data, no renderer): what
// ProximitySensor (6.38) and VisibilitySensor (6.52) compare against.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gs::runtime {

/// The user's camera in world coordinates.
struct ViewerPose {
  glm::vec3 position{0.0f, 0.0f, 10.0f};          // metres
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // rotates the view direction -Z and up +Y
  float fieldOfView = 0.785398f;  // radians, across the smaller side of the view (6.53)
  float aspect = 1.0f;            // width / height of the view, > 0
  float nearClip = 0.125f;        // metres, > 0
  float farClip = 1000.0f;        // metres, > nearClip
};

}  // namespace gs::runtime
