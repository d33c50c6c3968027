// Cameras and navigation maths: pure computation, no OpenGL and no GLFW, so it is
// unit-testable. Units: metres, radians, pixels. Matrices are glm's, column-major,
// OpenGL conventions (right-handed eye space looking down -Z, clip z in -1..1).
#pragma once

#include "geometry/geometry.hpp"

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gs::scene {

/// A viewer: where it is, where it looks, and its lens (VRML97 Viewpoint semantics).
/// The default orientation looks along -Z with +Y up, as VRML97's default Viewpoint.
struct Camera {
  glm::vec3 position{0.0f, 0.0f, 10.0f};          // world coordinates, metres
  glm::quat orientation{1.0f, 0.0f, 0.0f, 0.0f};  // rotates -Z (view) and +Y (up)
  float fieldOfView = 0.785398f;  // radians, across the smaller viewport side (6.53)
  float nearClip = 0.125f;        // metres, > 0
  float farClip = 1000.0f;        // metres, > nearClip
  /// An OrthoViewpoint's parallel projection (X3D 4.0 clause 23.4.5): the region
  /// (minX, minY, maxX, maxY) of the view plane, metres in the camera's coordinates, is
  /// shown whole and the viewport's longer axis sees more; fieldOfView is then unused.
  bool orthographic = false;
  glm::vec4 orthoRegion{-1.0f, -1.0f, 1.0f, 1.0f};
  /// What the Viewpoint's coordinate system does beyond `orientation`: the scale and
  /// shear of the Transforms above it, in the camera's axes (the camera's axes in the
  /// world are orientation * deform). X_ITE views a Viewpoint under a scaled Transform
  /// through that Transform's whole matrix, so a world scaled with its Viewpoint looks
  /// unscaled. Identity when the Transforms only turn and move, and for a flattening or
  /// mirroring one (its turn alone is kept); kept while navigating. Invertible.
  glm::mat3 deform{1.0f};

  /// Unit vector the camera looks along (orientation applied to -Z).
  glm::vec3 forward() const { return orientation * glm::vec3(0.0f, 0.0f, -1.0f); }
  /// Unit up vector (orientation applied to +Y).
  glm::vec3 up() const { return orientation * glm::vec3(0.0f, 1.0f, 0.0f); }
  /// Unit right vector (orientation applied to +X).
  glm::vec3 right() const { return orientation * glm::vec3(1.0f, 0.0f, 0.0f); }
};

/// World-to-eye matrix of `camera`.
glm::mat4 viewMatrix(const Camera& camera);

/// Perspective projection for a viewport of `aspect` = width / height. The field of view
/// spans the smaller viewport side (VRML97 6.53): vertical when aspect >= 1, horizontal
/// otherwise. Clamps the field of view to 0.001..3.1 radians. An orthographic camera gets
/// the parallel projection of its orthoRegion, widened on one axis to the aspect.
glm::mat4 projectionMatrix(const Camera& camera, float aspect);

/// Vertical field of view (radians) that projectionMatrix uses for `aspect`.
float verticalFieldOfView(float fieldOfView, float aspect);

/// A camera with the orientation and field of view of `direction`, moved back along its
/// view direction, looking at the box centre, just far enough (plus a 5% margin) that all
/// eight corners of `bounds` (world coordinates) are inside the view of a viewport of
/// aspect `aspect`; near and far planes are set around the box (see fitClipPlanes). An
/// empty box returns `direction` unchanged.
Camera fitCamera(const vrml::Bounds& bounds, float aspect, const Camera& direction);

/// The camera castle-model-viewer starts with in a world without a Viewpoint
/// (castle-engine's CameraViewpointForWholeScene with direction -Z and up +Y): `defaults`'
/// field of view, at the box centre's X and Y and at the box's largest Z plus twice its
/// average side ((size.x + size.y + size.z) / 3), looking along -Z with +Y up; clip
/// planes as fitClipPlanes. Unlike fitCamera it does not depend on the viewport's aspect.
/// An empty box returns `defaults` unchanged.
Camera wholeSceneCamera(const vrml::Bounds& bounds, const Camera& defaults);

/// Sets `camera`'s near and far planes to enclose the sphere around `bounds` seen from
/// the camera's position: far just beyond the sphere's far side, near the sphere's near
/// side (at least far / 10000, so the depth buffer keeps precision; at most `maxNear`
/// when positive, e.g. NavigationInfo avatarSize[0] / 2, but never below far /
/// kMaxFarNearRatio: a 24-bit depth buffer keeps nothing beyond that). An empty box leaves
/// the camera unchanged.
inline constexpr float kMaxFarNearRatio = 1e6f;
void fitClipPlanes(Camera& camera, const vrml::Bounds& bounds, float maxNear = 0.0f);

/// Where the user has moved from a Viewpoint's own camera (X3D 4.0 clause 23.3.5,
/// `retainUserOffsets`): the move and turn in the viewpoint's own axes, so that they apply
/// again when the viewpoint has moved or turned since.
struct UserOffset {
  glm::vec3 translation{0.0f};                 // metres, in the viewpoint's axes
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};  // after the viewpoint's orientation
};

/// The offset of camera `user` from the camera `defined` that its Viewpoint gives:
/// translation = inverse(defined.orientation) (user.position - defined.position), rotation
/// = inverse(defined.orientation) user.orientation.
UserOffset userOffset(const Camera& user, const Camera& defined);

/// `defined` moved and turned by `offset` (the inverse of userOffset): its lens, clip
/// planes and deform kept.
Camera withUserOffset(const Camera& defined, const UserOffset& offset);

/// The navigation types of NavigationInfo (clause 6.29).
enum class NavigationMode {
  examine,  // orbit around a centre, pan, dolly
  walk,     // look around; move on the horizontal plane (gravity and walls: collision.hpp)
  fly,      // look around; move along the view direction (walls: collision.hpp)
};

/// The first of NavigationInfo's `type` strings this browser supports ("EXAMINE",
/// "WALK", "FLY"; "ANY" and unknown ones are skipped); `fallback` when none is.
NavigationMode navigationModeOf(const std::vector<std::string>& types, NavigationMode fallback);

/// The navigation of VRML97 NavigationInfo: EXAMINE (the camera orbits a centre point,
/// pans in its view plane and dollies towards the centre), WALK and FLY (the camera looks
/// around from where it stands and moves). Inputs are mouse motions in pixels and
/// distances in metres; no window library is involved.
class ExamineNavigator {
 public:
  /// Radians of orbit per pixel of mouse motion is pi / viewport height (dragging across
  /// the whole height turns the view by half a turn).
  ExamineNavigator() = default;

  /// Starts from `camera` orbiting around `center` (world coordinates) and remembers both
  /// as the home that reset() returns to.
  void setHome(const Camera& camera, const glm::vec3& center);
  /// Returns to the camera and centre given to setHome().
  void reset();
  /// Replaces the camera (e.g. when the user picks a Viewpoint) keeping the orbit centre's
  /// distance along the new view direction (the centre moves in front of the camera).
  void setCamera(const Camera& camera);
  /// When not empty, near and far planes follow these world bounds after each motion
  /// (fitClipPlanes with `maxNear`).
  void setSceneBounds(const vrml::Bounds& bounds, float maxNear = 0.0f);

  /// Orbits for a mouse drag of (dx, dy) pixels (x to the right, y downwards) in a viewport
  /// `viewportHeight` pixels high: horizontal motion turns around the world +Y axis
  /// through the centre, vertical motion around the camera's right axis (the scene follows
  /// the mouse).
  void orbit(float dx, float dy, int viewportHeight);
  /// Pans for a drag of (dx, dy) pixels: camera and centre move in the view plane so that
  /// points at the centre's depth follow the mouse.
  void pan(float dx, float dy, int viewportHeight);
  /// Dollies towards the centre: `steps` > 0 (a mouse wheel notch each) moves closer by
  /// 10% of the distance per step, < 0 moves away. The distance stays >= 1e-4 metres.
  void dolly(float steps);

  /// WALK and FLY: turns the view for a drag of (dx, dy) pixels, pi / viewportHeight
  /// radians per pixel: yaw around the world +Y axis, pitch around the camera's right axis
  /// (kept within +-85 degrees of the horizon when walking). The orbit centre moves along.
  void look(float dx, float dy, int viewportHeight);
  /// WALK and FLY: moves by `forward` metres along the view direction (WALK: its
  /// horizontal part, so the eye height stays), `right` metres sideways and `up` metres
  /// along world +Y. EXAMINE: forward dollies (positive: closer) and right/up pan.
  void move(float forward, float right, float up);
  /// WALK and FLY: the world offset (metres) move() would apply, for a caller that
  /// checks it against the world first (scene/collision.hpp walkStep).
  glm::vec3 motion(float forward, float right, float up) const;

  NavigationMode mode() const { return mode_; }
  void setMode(NavigationMode mode) { mode_ = mode; }

  const Camera& camera() const { return camera_; }
  const glm::vec3& center() const { return center_; }
  /// Distance from the camera to the orbit centre, metres.
  float distance() const { return glm::length(center_ - camera_.position); }

 private:
  void updateClip();
  Camera camera_;
  glm::vec3 center_{0.0f};
  Camera homeCamera_;
  glm::vec3 homeCenter_{0.0f};
  vrml::Bounds bounds_;
  float maxNear_ = 0.0f;
  NavigationMode mode_ = NavigationMode::examine;
};

}  // namespace gs::scene
