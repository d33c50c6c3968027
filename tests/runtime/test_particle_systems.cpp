// X3D particle systems (X3D 4.0 clause 40) in the execution model: emission, lifetimes,
// emitters, physics models and isActive, as X_ITE 15 runs them (particles/), on the
// runtime's clock and the same on every machine.
#include "../test_support.hpp"
#include "runtime_fixture.hpp"

#include "particles/particle_mesh.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using gs::particles::Particle;
using gs::test::RunningWorld;
using gs::test::x3dWorld;
using gs::vrml::FieldType;
using gs::vrml::FieldValue;

namespace {

const std::vector<Particle>& particlesOf(const RunningWorld& w, const std::string& name = "PS") {
  const gs::particles::ParticleSimulation* s = w.model->particleSimulation(w.node(name));
  REQUIRE(s != nullptr);
  return s->particles();
}

std::size_t visibleCount(const std::vector<Particle>& ps) {
  return static_cast<std::size_t>(
      std::count_if(ps.begin(), ps.end(), [](const Particle& p) { return p.visible; }));
}

/// Advances in steps of 1/60 s to `t`, as --time-step does.
void runTo(RunningWorld& w, double t) {
  w.model->advanceBy(t - w.model->now(), 1.0 / 60.0);
}

bool sawParticleEvent(const std::vector<std::string>& events, const std::string& e) {
  return std::find(events.begin(), events.end(), e) != events.end();
}

}  // namespace

TEST_CASE("particles: slots join at maxParticles / particleLifetime per second and move",
          "[runtime][x3d][particles]") {
  RunningWorld w(x3dWorld(R"(
DEF PS ParticleSystem {
  maxParticles 100 particleLifetime 10 lifetimeVariation 0
  emitter PointEmitter { position 1 2 3 direction 0 2 0 speed 0.5 variation 0 }
}
)"),
                 0.0);
  runTo(w, 1.0);
  const auto& ps = particlesOf(w);
  // 10 a second, the remainder of each step dropped (a slot per 6 or 7 steps of 1/60 s,
  // as X_ITE drops it): 8 to 10 after one second.
  CHECK(ps.size() >= 8);
  CHECK(ps.size() <= 10);
  CHECK(visibleCount(ps) == ps.size());
  for (const Particle& p : ps) {
    CHECK(p.lifetime == Approx(10.0f));
    CHECK(p.velocity.y == Approx(0.5f));  // along the unit direction at `speed`
    CHECK(p.position.x == Approx(1.0f));
    CHECK(p.position.y == Approx(2.0f + 0.5f * p.elapsed).margin(1e-3));
  }
  runTo(w, 20.0);  // full: no more than maxParticles, each reborn after its life
  CHECK(particlesOf(w).size() == 100);
  for (const Particle& p : particlesOf(w)) CHECK(p.elapsed <= 10.0f + 1e-3f);
}

TEST_CASE("particles: the same world gives the same particles", "[runtime][x3d][particles]") {
  const auto world = x3dWorld(R"(
DEF PS ParticleSystem {
  maxParticles 50 particleLifetime 1
  emitter ConeEmitter { speed 2 angle 0.5 mass 1 surfaceArea 1 }
  physics [ WindPhysicsModel { speed 3 gustiness 0.5 turbulence 0.4 } ForcePhysicsModel {} ]
}
)");
  RunningWorld a(world, 0.0), b(world, 0.0);
  runTo(a, 2.5);
  runTo(b, 2.5);
  const auto& pa = particlesOf(a);
  const auto& pb = particlesOf(b);
  REQUIRE(pa.size() == pb.size());
  REQUIRE(pa.size() == 50);
  for (std::size_t i = 0; i < pa.size(); ++i) {
    CHECK(pa[i].position == pb[i].position);
    CHECK(pa[i].velocity == pb[i].velocity);
  }
}

TEST_CASE("particles: isActive, enabled and createParticles", "[runtime][x3d][particles]") {
  RunningWorld w(x3dWorld(R"(
DEF PS ParticleSystem { maxParticles 20 particleLifetime 1 lifetimeVariation 0 }
)"),
                 0.0);
  runTo(w, 0.5);
  CHECK(sawParticleEvent(w.take(), "PS.isActive=TRUE"));
  CHECK(particlesOf(w).size() >= 7);  // 20 a second less the dropped remainders
  CHECK(particlesOf(w).size() <= 10);
  // createParticles FALSE: the living live on, the reborn are hidden.
  w.send("PS", "createParticles", FieldValue::make<FieldType::SFBool>(false));
  runTo(w, 0.9);
  CHECK(visibleCount(particlesOf(w)) > 0);
  runTo(w, 2.0);
  CHECK(visibleCount(particlesOf(w)) == 0);
  w.send("PS", "createParticles", FieldValue::make<FieldType::SFBool>(true));
  runTo(w, 3.5);
  CHECK(visibleCount(particlesOf(w)) == 20);
  // enabled FALSE: every particle goes at once, isActive FALSE.
  w.take();
  w.send("PS", "enabled", FieldValue::make<FieldType::SFBool>(false));
  runTo(w, 3.6);
  CHECK(particlesOf(w).empty());
  CHECK(sawParticleEvent(w.take(), "PS.isActive=FALSE"));
  // Enabled again: emission starts from none.
  w.send("PS", "enabled", FieldValue::make<FieldType::SFBool>(true));
  runTo(w, 3.8);
  CHECK(particlesOf(w).size() <= 4);
  CHECK(sawParticleEvent(w.take(), "PS.isActive=TRUE"));
}

TEST_CASE("particles: an ExplosionEmitter gives every particle at once, again after a life",
          "[runtime][x3d][particles]") {
  RunningWorld w(x3dWorld(R"(
DEF PS ParticleSystem {
  maxParticles 64 particleLifetime 2 lifetimeVariation 0.5
  emitter ExplosionEmitter { position 0 1 0 speed 3 variation 0 }
}
)"),
                 0.0);
  runTo(w, 1.0 / 60.0);
  const auto& ps = particlesOf(w);
  REQUIRE(ps.size() == 64);
  for (const Particle& p : ps) {
    CHECK(glm::length(p.velocity) == Approx(3.0f));
    CHECK(p.position == glm::vec3(0, 1, 0));  // not moved in its birth step
  }
  runTo(w, 2.9);  // lives of 1 to 3 s: some are gone and stay hidden until the next burst
  const std::size_t left = visibleCount(particlesOf(w));
  CHECK(left < 64);
  CHECK(left > 0);
  runTo(w, 3.1);  // 3 s = particleLifetime (1 + lifetimeVariation): the second burst
  CHECK(visibleCount(particlesOf(w)) == 64);
}

TEST_CASE("particles: forces need a mass; a bounded model bounces", "[runtime][x3d][particles]") {
  RunningWorld w(x3dWorld(R"(
DEF PS ParticleSystem {
  maxParticles 10 particleLifetime 100 lifetimeVariation 0
  emitter ExplosionEmitter { position 0 1 0 speed 0 mass 2 }
  physics [
    ForcePhysicsModel { force 0 -4 0 }
    BoundedPhysicsModel { damping 0.5 geometry IndexedFaceSet {
      coord Coordinate { point [ -5 0 -5, 5 0 -5, 5 0 5, -5 0 5 ] } coordIndex [ 0 1 2 3 -1 ] } }
  ]
}
DEF FREE ParticleSystem {
  maxParticles 10 particleLifetime 100
  emitter ExplosionEmitter { speed 0 }
  physics ForcePhysicsModel { force 0 -4 0 }
}
)"),
                 0.0);
  runTo(w, 0.5);
  // Acceleration force / mass = -2 m/s^2 (semi-implicit Euler steps of 1/60 s).
  const Particle first = particlesOf(w).front();
  CHECK(first.velocity.y == Approx(-2.0f * first.elapsed).epsilon(0.05));
  // Without a mass nothing moves (X_ITE applies no force then).
  for (const Particle& p : particlesOf(w, "FREE")) CHECK(p.velocity == glm::vec3(0.0f));
  runTo(w, 3.0);  // fallen 1 m and bounced off y = 0: never below it
  bool bounced = false;
  for (const Particle& p : particlesOf(w)) {
    CHECK(p.position.y >= -1e-3f);
    bounced = bounced || p.velocity.y > 0.0f;
  }
  CHECK(bounced);
}

TEST_CASE("particles: polyline, surface and volume emitters place particles on and in them",
          "[runtime][x3d][particles]") {
  RunningWorld w(x3dWorld(R"(
DEF LINE ParticleSystem {
  maxParticles 200 particleLifetime 10
  emitter PolylineEmitter {
    coord Coordinate { point [ 0 0 0, 2 0 0, 2 3 0 ] } coordIndex [ 0 1 2 ] speed 0 }
}
DEF SURFACE ParticleSystem {
  maxParticles 200 particleLifetime 10
  emitter SurfaceEmitter { surface Box { size 2 2 2 } speed 0 }
}
DEF VOLUME ParticleSystem {
  maxParticles 200 particleLifetime 10
  emitter VolumeEmitter {
    coord Coordinate { point [ -1 -1 -1, 1 -1 -1, 1 1 -1, -1 1 -1, -1 -1 1, 1 -1 1, 1 1 1, -1 1 1 ] }
    coordIndex [ 0 3 2 1 -1, 4 5 6 7 -1, 0 1 5 4 -1, 2 3 7 6 -1, 1 2 6 5 -1, 0 4 7 3 -1 ]
    speed 0 }
}
)"),
                 0.0);
  runTo(w, 13.0);
  REQUIRE(particlesOf(w, "LINE").size() == 200);
  std::size_t onSecond = 0;
  for (const Particle& p : particlesOf(w, "LINE")) {
    const bool first =
        std::abs(p.position.y) < 1e-5f && p.position.x >= -1e-5f && p.position.x <= 2.0001f;
    const bool second = std::abs(p.position.x - 2.0f) < 1e-5f && p.position.y >= -1e-5f;
    CHECK((first || second));
    onSecond += second && !first ? 1 : 0;
  }
  // Uniform by length: 3 of the 5 metres are on the second segment.
  CHECK(onSecond > 90);
  CHECK(onSecond < 150);
  for (const Particle& p : particlesOf(w, "SURFACE")) {
    const glm::vec3 a = glm::abs(p.position);
    CHECK(std::max({a.x, a.y, a.z}) == Approx(1.0f).margin(1e-4));
  }
  glm::vec3 mean(0.0f);
  for (const Particle& p : particlesOf(w, "VOLUME")) {
    const glm::vec3 a = glm::abs(p.position);
    CHECK(std::max({a.x, a.y, a.z}) <= 1.0001f);
    mean += p.position / 200.0f;
  }
  CHECK(glm::length(mean) < 0.3f);  // spread through the box
}

TEST_CASE("particles: ramps and meshes of each geometry type", "[runtime][x3d][particles]") {
  using gs::particles::GeometryType;
  using gs::particles::rampColor;
  using gs::particles::rampTexCoordSet;
  const std::vector<float> keys{0.0f, 0.5f, 1.0f};
  const std::vector<glm::vec4> colors{{1, 0, 0, 1}, {0, 1, 0, 0.5f}, {0, 0, 1, 0}};
  CHECK(rampColor(keys, colors, 0.25f) == glm::vec4(0.5f, 0.5f, 0.0f, 0.75f));
  CHECK(rampColor(keys, colors, 2.0f) == colors[2]);
  CHECK(rampTexCoordSet(keys, 0.0f) == 0);
  CHECK(rampTexCoordSet(keys, 0.7f) == 1);
  CHECK(rampTexCoordSet(keys, 1.0f) == 1);  // X_ITE never uses the last key's set

  RunningWorld w(x3dWorld(R"(
DEF PS ParticleSystem {
  maxParticles 1 particleLifetime 0.5 lifetimeVariation 0 particleSize 2 4
  emitter PointEmitter { position 0 0 5 direction 1 0 0 speed 1 variation 0 }
  colorKey [ 0 1 ] color ColorRGBA { color [ 1 0 0 1, 0 0 1 1 ] }
}
)"),
                 0.0);
  runTo(w, 0.75);  // joined at 0.5 s
  const auto& ps = particlesOf(w);
  REQUIRE(ps.size() == 1);
  const gs::vrml::Node& system = w.node("PS");
  const glm::vec3 at = ps[0].position;
  const gs::vrml::Mesh quad =
      gs::particles::particleMesh(system, GeometryType::quad, ps, glm::mat3(1.0f));
  REQUIRE(quad.positions.size() == 4);
  CHECK(quad.indices.size() == 6);
  CHECK(quad.positions[0] == at + glm::vec3(-1, -2, 0));
  CHECK(quad.positions[2] == at + glm::vec3(1, 2, 0));
  CHECK(quad.normals[0] == glm::vec3(0, 0, 1));
  CHECK(quad.texCoords[2] == glm::vec2(1, 1));
  REQUIRE(quad.colors.size() == 4);
  CHECK(quad.colors[0].r == Approx(1.0f - ps[0].ageFraction()));
  // A sprite is turned to the viewer: a viewer looking along -X sees it in the YZ plane.
  const glm::mat3 eyeToLocal(glm::vec3(0, 0, -1), glm::vec3(0, 1, 0), glm::vec3(1, 0, 0));
  const gs::vrml::Mesh sprite =
      gs::particles::particleMesh(system, GeometryType::sprite, ps, eyeToLocal);
  REQUIRE(sprite.positions.size() == 4);
  for (const glm::vec3& p : sprite.positions) CHECK(p.x == Approx(at.x));
  CHECK(sprite.normals[0].x == Approx(1.0f));
  // A line along the velocity, particleSize.y long, centred on the particle.
  const gs::vrml::Mesh line =
      gs::particles::particleMesh(system, GeometryType::line, ps, glm::mat3(1.0f));
  REQUIRE(line.positions.size() == 2);
  CHECK(line.primitive == gs::vrml::Primitive::lines);
  CHECK(line.positions[1] - line.positions[0] == glm::vec3(4, 0, 0));
  const gs::vrml::Mesh points =
      gs::particles::particleMesh(system, GeometryType::point, ps, glm::mat3(1.0f));
  CHECK(points.primitive == gs::vrml::Primitive::points);
  CHECK(points.positions == std::vector<glm::vec3>{at});
  CHECK(gs::particles::geometryTypeOf("SOMETHING") == GeometryType::quad);
}

TEST_CASE("particles: X3D 3's colorRamp and WindPhysicsModel default are read",
          "[runtime][x3d][particles]") {
  RunningWorld w(gs::test::WorldText{R"(#X3D V3.3 utf8
DEF PS ParticleSystem { colorKey 0 colorRamp Color { color 1 0 0 }
  physics DEF W WindPhysicsModel {} }
)",
                                     "old.x3dv"},
                 0.0);
  REQUIRE(w.scene->diagnostics.items.empty());
  CHECK(w.node("PS").sfnode("color") != nullptr);
  CHECK(w.node("W").field("direction")->get<FieldType::SFVec3f>() == glm::vec3(0.0f));
  RunningWorld w4(x3dWorld("DEF W WindPhysicsModel {}"), 0.0);
  CHECK(w4.node("W").field("direction")->get<FieldType::SFVec3f>() == glm::vec3(1, 0, 0));
}
