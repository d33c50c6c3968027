// Camera matrices, framing and the EXAMINE navigator: pure maths, no context.
#include "scene/camera.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>

using gs::scene::Camera;
using gs::scene::ExamineNavigator;

namespace {
glm::vec3 project(const Camera& c, float aspect, glm::vec3 p) {
  const glm::vec4 clip =
      gs::scene::projectionMatrix(c, aspect) * gs::scene::viewMatrix(c) * glm::vec4(p, 1.0f);
  return glm::vec3(clip) / clip.w;
}
bool near(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
  return glm::length(a - b) < eps;
}
}  // namespace

TEST_CASE("the default camera is VRML97's default Viewpoint", "[scene][camera]") {
  Camera c;
  CHECK(near(c.position, {0, 0, 10}));
  CHECK(near(c.forward(), {0, 0, -1}));
  CHECK(near(c.up(), {0, 1, 0}));
  CHECK(c.fieldOfView == Approx(0.785398f));
  // The origin projects to the centre of the viewport.
  CHECK(near(project(c, 1.0f, {0, 0, 0}) * glm::vec3(1, 1, 0), {0, 0, 0}));
}

TEST_CASE("the field of view spans the smaller viewport side", "[scene][camera]") {
  Camera c;
  c.position = {0, 0, 0};
  const float edge = std::tan(c.fieldOfView * 0.5f);  // at distance 1
  // Landscape: a point at the vertical edge of the field of view maps to y = 1.
  CHECK(project(c, 2.0f, {0, edge, -1}).y == Approx(1.0f).margin(1e-4));
  // Portrait: the horizontal extent is the field of view.
  CHECK(project(c, 0.5f, {edge, 0, -1}).x == Approx(1.0f).margin(1e-4));
  CHECK(gs::scene::verticalFieldOfView(c.fieldOfView, 0.5f) > c.fieldOfView);
}

TEST_CASE("fitCamera frames the whole box and keeps the view direction", "[scene][camera]") {
  gs::vrml::Bounds b;
  b.extend(glm::vec3(-3, -1, -2));
  b.extend(glm::vec3(5, 2, 1));
  Camera dir;
  dir.orientation = glm::angleAxis(0.6f, glm::normalize(glm::vec3(1, 1, 0)));
  for (float aspect : {0.5f, 1.0f, 2.0f}) {
    const Camera c = gs::scene::fitCamera(b, aspect, dir);
    CHECK(near(c.forward(), dir.forward()));
    CHECK(c.nearClip > 0.0f);
    CHECK(c.farClip > c.nearClip);
    for (int i = 0; i < 8; ++i) {
      const glm::vec3 corner((i & 1) ? b.max.x : b.min.x, (i & 2) ? b.max.y : b.min.y,
                             (i & 4) ? b.max.z : b.min.z);
      const glm::vec3 ndc = project(c, aspect, corner);
      CHECK(std::abs(ndc.x) <= 1.0f);
      CHECK(std::abs(ndc.y) <= 1.0f);
      CHECK(std::abs(ndc.z) <= 1.0f);  // between the clip planes
    }
    // The box centre is in the middle of the view.
    const glm::vec3 centre = project(c, aspect, b.center());
    CHECK(std::abs(centre.x) < 1e-4f);
    CHECK(std::abs(centre.y) < 1e-4f);
  }
  // An empty box changes nothing.
  const Camera same = gs::scene::fitCamera(gs::vrml::Bounds{}, 1.0f, dir);
  CHECK(near(same.position, dir.position));
}

TEST_CASE("EXAMINE orbit keeps the distance and turns around the centre", "[scene][camera]") {
  ExamineNavigator nav;
  Camera start;
  nav.setHome(start, glm::vec3(0.0f));
  // Half the viewport height turns a quarter turn: the camera ends on the -X or +X axis.
  nav.orbit(100.0f, 0.0f, 200);
  CHECK(nav.distance() == Approx(10.0f));
  CHECK(std::abs(nav.camera().position.x) == Approx(10.0f).margin(1e-3));
  CHECK(near(nav.camera().forward(), -glm::normalize(nav.camera().position), 1e-4f));
  // Dragging right moves the scene right: the camera goes to the left (-X).
  CHECK(nav.camera().position.x < 0.0f);
  nav.orbit(0.0f, 50.0f, 200);  // pitch: still looking at the centre
  CHECK(nav.distance() == Approx(10.0f));
  CHECK(near(nav.camera().forward(), -glm::normalize(nav.camera().position), 1e-4f));
  nav.reset();
  CHECK(near(nav.camera().position, start.position));
}

TEST_CASE("EXAMINE pan and dolly", "[scene][camera]") {
  ExamineNavigator nav;
  nav.setHome(Camera{}, glm::vec3(0.0f));
  nav.pan(10.0f, 0.0f, 100);
  // The scene follows the mouse: camera and centre move left together.
  CHECK(nav.camera().position.x < 0.0f);
  CHECK(nav.center().x == Approx(nav.camera().position.x));
  CHECK(nav.distance() == Approx(10.0f));
  nav.dolly(1.0f);
  CHECK(nav.distance() == Approx(9.0f));
  nav.dolly(-2.0f);
  CHECK(nav.distance() == Approx(9.0f / 0.81f));
  for (int i = 0; i < 1000; ++i) nav.dolly(10.0f);
  CHECK(nav.distance() > 0.0f);
}

TEST_CASE("the navigator keeps clip planes around the scene", "[scene][camera]") {
  ExamineNavigator nav;
  gs::vrml::Bounds b;
  b.extend(glm::vec3(-1));
  b.extend(glm::vec3(1));
  nav.setHome(Camera{}, glm::vec3(0.0f));
  nav.setSceneBounds(b);
  for (int i = 0; i < 30; ++i) nav.dolly(-1.0f);  // far away
  CHECK(nav.camera().farClip > nav.distance() + 1.0f);
  CHECK(nav.camera().nearClip < nav.distance() - 1.7f);
}

TEST_CASE("WALK and FLY navigation: look and move", "[scene][navigation]") {
  using gs::scene::NavigationMode;
  CHECK(gs::scene::navigationModeOf({"ANY", "FLY", "WALK"}, NavigationMode::examine) ==
        NavigationMode::fly);
  CHECK(gs::scene::navigationModeOf({"NONE", "ANY"}, NavigationMode::walk) == NavigationMode::walk);
  gs::scene::Camera start;  // at 0 0 10 looking along -Z
  start.position = {0.0f, 1.6f, 10.0f};
  gs::scene::ExamineNavigator nav;
  nav.setHome(start, glm::vec3(0.0f, 1.6f, 0.0f));
  nav.setMode(NavigationMode::walk);
  // Looking down 45 degrees, then walking 2 m: the eye height stays.
  nav.look(0.0f, 150.0f, 600);  // pi / 600 per pixel: 45 degrees
  CHECK(nav.camera().forward().y == Approx(-std::sqrt(0.5f)).margin(1e-4));
  nav.move(2.0f, 0.0f, 0.0f);
  CHECK(nav.camera().position.y == Approx(1.6f));
  CHECK(nav.camera().position.z == Approx(8.0f).margin(1e-4));
  // Walking never looks more than 85 degrees down.
  nav.look(0.0f, 1000.0f, 600);
  CHECK(std::asin(-nav.camera().forward().y) == Approx(85.0 * 3.14159265 / 180.0).margin(1e-3));
  // Flying goes where it looks.
  nav.setMode(NavigationMode::fly);
  nav.setCamera(start);
  nav.look(0.0f, 150.0f, 600);
  nav.move(2.0f, 0.0f, 0.0f);
  CHECK(nav.camera().position.y == Approx(1.6f - std::sqrt(2.0f)).margin(1e-4));
  // A drag to the left by half the height turns the view a quarter turn: it faces -X.
  nav.setCamera(start);
  nav.look(-300.0f, 0.0f, 600);
  CHECK(nav.camera().forward().x == Approx(-1.0f).margin(1e-4));
  nav.move(0.0f, 1.0f, 0.5f);  // sideways and up
  CHECK(nav.camera().position.y == Approx(2.1f).margin(1e-4));
}

TEST_CASE("wholeSceneCamera: castle-model-viewer's camera for a world without a Viewpoint",
          "[scene][camera]") {
  // torus.glb's box: 2.5 x 0.5 x 2.5 around the origin; average side 11/6.
  gs::vrml::Bounds box;
  box.extend(glm::vec3(-1.25f, -0.25f, -1.25f));
  box.extend(glm::vec3(1.25f, 0.25f, 1.25f));
  box.extend(glm::vec3(0.5f, 0.0f, 0.0f));  // inside: changes nothing
  gs::scene::Camera defaults;
  defaults.fieldOfView = 0.6f;
  defaults.orientation = glm::angleAxis(1.0f, glm::vec3(0.0f, 1.0f, 0.0f));
  const gs::scene::Camera c = gs::scene::wholeSceneCamera(box, defaults);
  CHECK(c.position.x == Approx(0.0f).margin(1e-6));
  CHECK(c.position.y == Approx(0.0f).margin(1e-6));
  CHECK(c.position.z == Approx(1.25f + 2.0f * 11.0f / 6.0f).epsilon(1e-5));
  CHECK(c.forward().z == Approx(-1.0f));  // looks along -Z whatever the defaults' orientation
  CHECK(c.fieldOfView == 0.6f);
  CHECK(c.nearClip < 2.0f * 11.0f / 6.0f);  // the box is inside the clip planes
  CHECK(c.farClip > c.position.z + 1.25f);
  // An empty box leaves the camera as it was.
  CHECK(gs::scene::wholeSceneCamera(gs::vrml::Bounds{}, defaults).position == defaults.position);
}

TEST_CASE("a deformed camera's clip planes hold the scene in its own units", "[scene][camera]") {
  // A Viewpoint under Transform { scale 0.5 0.5 0.5 } at (0 0 10) of that Transform: the
  // camera sits at world z = 5 and measures depths in half metres, so the 2 m box at the
  // origin is 9 to 11 units deep; near and far must hold that, not the world's 4 to 6.
  Camera c;
  c.position = {0, 0, 5};
  c.deform = glm::mat3(0.5f);
  gs::vrml::Bounds box;
  box.extend(glm::vec3(-1.0f));
  box.extend(glm::vec3(1.0f));
  gs::scene::fitClipPlanes(c, box);
  for (const float z : {-1.0f, 1.0f}) {
    const glm::vec4 eye = gs::scene::viewMatrix(c) * glm::vec4(0, 0, z, 1);
    CHECK(-eye.z > c.nearClip);
    CHECK(-eye.z < c.farClip);
  }
  CHECK(project(c, 1.0f, {0, 0, 1}).z > -1.0f);
  CHECK(project(c, 1.0f, {0, 0, -1}).z < 1.0f);
}

TEST_CASE("a user offset from a viewpoint applies again after the viewpoint turned",
          "[scene][camera]") {
  Camera defined;
  defined.position = {0, 0, 10};
  Camera user = defined;
  user.position = {1, 0, 8};  // a step right and two forward
  user.orientation = glm::angleAxis(0.5f, glm::vec3(0, 1, 0));
  const gs::scene::UserOffset offset = gs::scene::userOffset(user, defined);
  CHECK(offset.translation.x == Approx(1.0f));
  CHECK(offset.translation.z == Approx(-2.0f));
  // The same viewpoint: the user's camera again.
  const Camera back = gs::scene::withUserOffset(defined, offset);
  CHECK(glm::length(back.position - user.position) < 1e-5f);
  CHECK(std::abs(glm::dot(back.orientation, user.orientation)) == Approx(1.0f));
  // The viewpoint moved to x = 5 and turned a quarter left: the step right is now a step
  // towards -Z, and the turn adds to its own.
  Camera turned = defined;
  turned.position = {5, 0, 0};
  turned.orientation = glm::angleAxis(1.5707963f, glm::vec3(0, 1, 0));
  turned.fieldOfView = 0.5f;
  const Camera moved = gs::scene::withUserOffset(turned, offset);
  CHECK(moved.position.x == Approx(5.0f - 2.0f).margin(1e-5));
  CHECK(moved.position.z == Approx(-1.0f).margin(1e-5));
  const glm::quat expected = glm::angleAxis(1.5707963f + 0.5f, glm::vec3(0, 1, 0));
  CHECK(std::abs(glm::dot(moved.orientation, expected)) == Approx(1.0f));
  CHECK(moved.fieldOfView == 0.5f);
}
