// The avatar against the world (scene/collision.hpp): walls stop WALK and FLY at
// avatarSize[0], WALK falls to avatarSize[1] above the ground and climbs steps up to
// avatarSize[2]; Collision.collide FALSE lets the avatar through, a proxy blocks in place
// of the children (ISO/IEC 14772-1:1997 6.8, 6.29).
#include "encodings/parser.hpp"
#include "scene/collision.hpp"
#include "scene/picking.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using gs::scene::Camera;
using gs::scene::NavigationMode;
using gs::scene::SceneTraversal;
using gs::scene::WalkOptions;
using gs::scene::walkStep;

namespace {

/// A floor whose top is at y = 0 (40 m square) and `more`.
std::shared_ptr<gs::vrml::Scene> world(const std::string& more) {
  return std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#VRML V2.0 utf8\n"
      "Transform { translation 0 -0.05 0 children Shape { geometry Box { size 40 0.1 40 } } }\n" +
          more,
      "collision.wrl"));
}

/// A wall 10 m high across the way, its near face at z = -4.9.
const std::string kWall =
    "Transform { translation 0 5 -5 children Shape { geometry Box { size 20 10 0.2 } } }\n";

Camera standingAt(float x, float y, float z) {
  Camera c;
  c.position = {x, y, z};
  return c;  // looking along -Z
}

/// Walks `motion` from `from` in `mode` through `scene`.
gs::scene::WalkResult walk(const std::shared_ptr<gs::vrml::Scene>& scene, const Camera& from,
                           glm::vec3 motion, NavigationMode mode = NavigationMode::walk,
                           float maxFall = std::numeric_limits<float>::infinity()) {
  SceneTraversal traversal(scene);
  WalkOptions options;
  options.mode = mode;
  options.maxFall = maxFall;
  return walkStep(traversal, from, motion, traversal.navigation(), options);
}

}  // namespace

TEST_CASE("walking into a wall stops avatarSize[0] before it", "[collision]") {
  const auto scene = world(kWall);
  const auto r = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -10});
  CHECK(r.blocked);
  CHECK(r.grounded);
  CHECK(r.camera.position.z == Approx(-4.9f + 0.25f).margin(1e-4));
  CHECK(r.camera.position.y == Approx(1.6f).margin(1e-4));
  CHECK(r.collided.empty());  // no Collision node around the wall
  // A short move that stays clear is not cut; moving away from the wall is free.
  const auto clear = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -1});
  CHECK_FALSE(clear.blocked);
  CHECK(clear.camera.position.z == Approx(-1.0f).margin(1e-4));
  const auto away = walk(scene, r.camera, {0, 0, 3});
  CHECK_FALSE(away.blocked);
  CHECK(away.camera.position.z == Approx(-4.65f + 3.0f).margin(1e-4));
}

TEST_CASE("NavigationInfo avatarSize sets the distance kept from walls", "[collision]") {
  const auto scene = world("NavigationInfo { avatarSize [ 1 1.6 0.75 ] }\n" + kWall);
  const auto r = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -10});
  CHECK(r.blocked);
  CHECK(r.camera.position.z == Approx(-3.9f).margin(1e-4));
}

TEST_CASE("FLY stops at walls without gravity", "[collision]") {
  const auto scene = world(kWall);
  const auto r = walk(scene, standingAt(0, 5, 0), {0, 0, -10}, NavigationMode::fly);
  CHECK(r.blocked);
  CHECK(r.camera.position == glm::vec3(0, 5, r.camera.position.z));
  CHECK(r.camera.position.z == Approx(-4.65f).margin(1e-4));
  // Flying up and down is not pulled back to the ground.
  const auto up = walk(scene, standingAt(0, 5, 0), {0, 2, 0}, NavigationMode::fly);
  CHECK(up.camera.position.y == Approx(7.0f));
  // EXAMINE checks nothing.
  const auto through = walk(scene, standingAt(0, 5, 0), {0, 0, -10}, NavigationMode::examine);
  CHECK(through.camera.position.z == Approx(-10.0f));
}

TEST_CASE("stepping off a ledge falls to eye height above the ground", "[collision]") {
  // A platform 1 m high, 4 m square around the origin.
  const auto scene =
      world("Transform { translation 0 0.5 0 children Shape { geometry Box { size 4 1 4 } } }\n");
  const Camera onTop = standingAt(0, 2.6f, 0);
  const auto r = walk(scene, onTop, {0, 0, -3});
  CHECK_FALSE(r.blocked);
  CHECK(r.grounded);
  CHECK(r.camera.position.z == Approx(-3.0f).margin(1e-4));
  CHECK(r.camera.position.y == Approx(1.6f).margin(1e-4));
  // Gravity frame by frame: at most maxFall a step, until the ground is reached.
  auto fall = walk(scene, onTop, {0, 0, -3}, NavigationMode::walk, 0.4f);
  CHECK_FALSE(fall.grounded);
  CHECK(fall.camera.position.y == Approx(2.2f).margin(1e-4));
  int steps = 1;
  while (!fall.grounded && steps < 10) {
    fall = walk(scene, fall.camera, {0, 0, 0}, NavigationMode::walk, 0.4f);
    ++steps;
  }
  CHECK(steps == 3);  // 2.6 -> 2.2 -> 1.8 -> 1.6
  CHECK(fall.camera.position.y == Approx(1.6f).margin(1e-4));
  // Standing on the platform nothing moves.
  const auto still = walk(scene, onTop, {0, 0, 0});
  CHECK(still.grounded);
  CHECK(still.camera.position == onTop.position);
  // Nothing below: the avatar stays where it is.
  const auto void_ = walk(scene, standingAt(100, 5, 0), {0, 0, -1});
  CHECK(void_.camera.position.y == Approx(5.0f));
}

TEST_CASE("WALK follows the terrain up a gentle slope", "[collision]") {
  // A ramp rising 1 m over 10 m towards -Z (a 5.7 degree slope).
  const auto scene = world(
      "Shape { geometry IndexedFaceSet { coord Coordinate { point [ -5 0 0, 5 0 0, 5 1 -10, "
      "-5 1 -10 ] } coordIndex [ 0 1 2 3 -1 ] solid FALSE } }\n");
  const auto r = walk(scene, standingAt(0, 1.6f, 0.5f), {0, 0, -5.5f});
  CHECK_FALSE(r.blocked);
  CHECK(r.camera.position.z == Approx(-5.0f).margin(1e-4));
  CHECK(r.camera.position.y == Approx(2.1f).margin(1e-3));
}

TEST_CASE("a step lower than avatarSize[2] is climbed, a higher one blocks", "[collision]") {
  // A 0.5 m step (avatarSize[2] is 0.75 by default) whose near face is at z = -2.
  const auto low =
      world("Transform { translation 0 0.25 -4 children Shape { geometry Box { size 4 0.5 4 } } }");
  const auto up = walk(low, standingAt(0, 1.6f, 0), {0, 0, -3});
  CHECK_FALSE(up.blocked);
  CHECK(up.camera.position.z == Approx(-3.0f).margin(1e-4));
  CHECK(up.camera.position.y == Approx(2.1f).margin(1e-4));
  // A 1 m step blocks at the knees: the avatar stops avatarSize[0] before its face.
  const auto high =
      world("Transform { translation 0 0.5 -4 children Shape { geometry Box { size 4 1 4 } } }");
  const auto blocked = walk(high, standingAt(0, 1.6f, 0), {0, 0, -3});
  CHECK(blocked.blocked);
  CHECK(blocked.camera.position.z == Approx(-1.75f).margin(1e-4));
  CHECK(blocked.camera.position.y == Approx(1.6f).margin(1e-4));
  // A larger avatarSize[2] climbs it.
  const auto climber = world(
      "NavigationInfo { avatarSize [ 0.25 1.6 1.2 ] }\n"
      "Transform { translation 0 0.5 -4 children Shape { geometry Box { size 4 1 4 } } }");
  const auto climbed = walk(climber, standingAt(0, 1.6f, 0), {0, 0, -3});
  CHECK_FALSE(climbed.blocked);
  CHECK(climbed.camera.position.y == Approx(2.6f).margin(1e-4));
}

TEST_CASE("Collision collide FALSE lets the avatar through", "[collision]") {
  const auto scene = world("DEF C Collision { collide FALSE children [ " + kWall + " ] }");
  const auto r = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -10});
  CHECK_FALSE(r.blocked);
  CHECK(r.camera.position.z == Approx(-10.0f).margin(1e-4));
  CHECK(r.collided.empty());
  // The wall is still drawn and picked.
  SceneTraversal traversal(scene);
  CHECK(gs::scene::pick(traversal, standingAt(0, 1.6f, 0), {{0, 1.6f, 0}, {0, 0, -1}}));
}

TEST_CASE("a Collision reports itself when its children block", "[collision]") {
  const auto scene =
      world("DEF OUTER Collision { children DEF C Collision { children [ " + kWall + " ] } }");
  const auto r = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -10});
  CHECK(r.blocked);
  REQUIRE(r.collided.size() == 2);
  CHECK(r.collided[0]->defName == "OUTER");
  CHECK(r.collided[1]->defName == "C");
  // Walking along the floor touches no Collision (the floor is outside them).
  CHECK(walk(scene, standingAt(0, 1.6f, 0), {0, 0, -1}).collided.empty());
}

TEST_CASE("a Collision proxy blocks where the children would not", "[collision]") {
  // Children: a small sphere off to the side; proxy: the wall (never drawn).
  const auto scene = world(
      "DEF C Collision { proxy " + kWall +
      " children Transform { translation 8 1 0 children Shape { geometry Sphere { radius 0.5 } } "
      "} }");
  const auto r = walk(scene, standingAt(0, 1.6f, 0), {0, 0, -10});
  CHECK(r.blocked);
  CHECK(r.camera.position.z == Approx(-4.65f).margin(1e-4));
  REQUIRE(r.collided.size() == 1);
  CHECK(r.collided[0]->defName == "C");
  // The proxy is not drawn, so it is not picked; the children are not collided with.
  SceneTraversal traversal(scene);
  CHECK_FALSE(gs::scene::pick(traversal, standingAt(0, 1.6f, 0), {{0, 1.6f, 0}, {0, 0, -1}}));
  const auto sideways = walk(scene, standingAt(5, 1.6f, 0), {5, 0, 0});
  CHECK_FALSE(sideways.blocked);
  CHECK(sideways.camera.position.x == Approx(10.0f).margin(1e-4));
}

TEST_CASE("WALK moves on the horizontal plane whatever the pitch", "[collision]") {
  gs::scene::ExamineNavigator nav;
  nav.setMode(NavigationMode::walk);
  Camera c = standingAt(0, 1.6f, 0);
  c.orientation = glm::angleAxis(0.5f, glm::vec3(1, 0, 0));  // looking up
  nav.setHome(c, {0, 0, 0});
  const glm::vec3 m = nav.motion(2.0f, 0.0f, 0.0f);
  CHECK(m.y == 0.0f);
  CHECK(glm::length(m) == Approx(2.0f));
  nav.setMode(NavigationMode::fly);
  CHECK(nav.motion(2.0f, 0.0f, 0.0f).y > 0.5f);
}
