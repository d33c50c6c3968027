// The EXAMINE navigator: orbit, pan and dolly around a centre point.
#include "scene/camera.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace gs::scene {

namespace {
constexpr float kPi = 3.14159265358979f;
constexpr float kMinDistance = 1e-4f;
}  // namespace

void ExamineNavigator::setHome(const Camera& camera, const glm::vec3& center) {
  homeCamera_ = camera;
  homeCenter_ = center;
  reset();
}

void ExamineNavigator::reset() {
  camera_ = homeCamera_;
  center_ = homeCenter_;
  updateClip();
}

void ExamineNavigator::setCamera(const Camera& camera) {
  const float d = std::max(distance(), kMinDistance);
  camera_ = camera;
  center_ = camera_.position + camera_.forward() * d;
  updateClip();
}

void ExamineNavigator::setSceneBounds(const vrml::Bounds& bounds, float maxNear) {
  bounds_ = bounds;
  maxNear_ = maxNear;
  updateClip();
}

void ExamineNavigator::orbit(float dx, float dy, int viewportHeight) {
  const float perPixel = kPi / float(std::max(viewportHeight, 1));
  // Dragging right turns the scene right: the camera turns left around the centre.
  const glm::quat yaw = glm::angleAxis(-dx * perPixel, glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::quat pitch = glm::angleAxis(-dy * perPixel, camera_.right());
  const glm::quat turn = glm::normalize(yaw * pitch);
  camera_.position = center_ + turn * (camera_.position - center_);
  camera_.orientation = glm::normalize(turn * camera_.orientation);
  updateClip();
}

void ExamineNavigator::pan(float dx, float dy, int viewportHeight) {
  const float d = std::max(distance(), kMinDistance);
  // World size of one pixel at the centre's depth.
  const float vfov = std::clamp(camera_.fieldOfView, 0.001f, 3.1f);
  const float perPixel = 2.0f * d * std::tan(vfov * 0.5f) / float(std::max(viewportHeight, 1));
  const glm::vec3 offset = (-dx * camera_.right() + dy * camera_.up()) * perPixel;
  camera_.position += offset;
  center_ += offset;
  updateClip();
}

void ExamineNavigator::dolly(float steps) {
  const float d = std::max(distance(), kMinDistance);
  const float next = std::max(d * std::pow(0.9f, steps), kMinDistance);
  const glm::vec3 towards = (center_ - camera_.position) / d;
  camera_.position = center_ - towards * next;
  updateClip();
}

NavigationMode navigationModeOf(const std::vector<std::string>& types, NavigationMode fallback) {
  for (const std::string& t : types) {
    if (t == "EXAMINE") return NavigationMode::examine;
    if (t == "WALK") return NavigationMode::walk;
    if (t == "FLY") return NavigationMode::fly;
  }
  return fallback;
}

void ExamineNavigator::look(float dx, float dy, int viewportHeight) {
  const float perPixel = kPi / float(std::max(viewportHeight, 1));
  const float d = std::max(distance(), kMinDistance);
  float pitchAngle = -dy * perPixel;
  if (mode_ == NavigationMode::walk) {
    // Keep the view within 85 degrees of the horizon.
    const float current = std::asin(std::clamp(camera_.forward().y, -1.0f, 1.0f));
    const float limit = 85.0f * kPi / 180.0f;
    pitchAngle = std::clamp(current + pitchAngle, -limit, limit) - current;
  }
  const glm::quat yaw = glm::angleAxis(-dx * perPixel, glm::vec3(0.0f, 1.0f, 0.0f));
  const glm::quat pitch = glm::angleAxis(pitchAngle, camera_.right());
  camera_.orientation = glm::normalize(yaw * pitch * camera_.orientation);
  center_ = camera_.position + camera_.forward() * d;
  updateClip();
}

void ExamineNavigator::move(float forward, float right, float up) {
  if (mode_ == NavigationMode::examine) {
    const float d = std::max(distance(), kMinDistance);
    if (forward != 0.0f) dolly(std::log(std::max(d - forward, kMinDistance) / d) / std::log(0.9f));
    const glm::vec3 offset = right * camera_.right() + up * camera_.up();
    camera_.position += offset;
    center_ += offset;
    updateClip();
    return;
  }
  const glm::vec3 offset = motion(forward, right, up);
  camera_.position += offset;
  center_ += offset;
  updateClip();
}

glm::vec3 ExamineNavigator::motion(float forward, float right, float up) const {
  glm::vec3 ahead = camera_.forward();
  glm::vec3 side = camera_.right();
  if (mode_ == NavigationMode::walk) {
    ahead.y = 0.0f;
    side.y = 0.0f;
    ahead = glm::length(ahead) > 1e-6f ? glm::normalize(ahead) : glm::vec3(0.0f);
    side = glm::length(side) > 1e-6f ? glm::normalize(side) : glm::vec3(0.0f);
  }
  return forward * ahead + right * side + glm::vec3(0.0f, up, 0.0f);
}

void ExamineNavigator::updateClip() {
  if (!bounds_.empty()) fitClipPlanes(camera_, bounds_, maxNear_);
}

}  // namespace gs::scene
