#include "particles/particle_system.hpp"

#include "random.hpp"
#include "triangles.hpp"

#include "encodings/node_types.hpp"
#include "geometry/geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace gs::particles {

using vrml::FieldType;

GeometryType geometryTypeOf(std::string_view name) {
  if (name == "LINE") return GeometryType::line;
  if (name == "POINT") return GeometryType::point;
  if (name == "SPRITE") return GeometryType::sprite;
  if (name == "TRIANGLE") return GeometryType::triangle;
  if (name == "GEOMETRY") return GeometryType::geometry;
  return GeometryType::quad;
}

namespace {

float sfFloat(const vrml::Node& n, vrml::FieldName name, float fallback) {
  const float v = n.get<FieldType::SFFloat>(name, fallback);
  return std::isfinite(v) ? v : fallback;
}
glm::vec3 sfVec3(const vrml::Node& n, vrml::FieldName name, glm::vec3 fallback) {
  const glm::vec3 v = n.get<FieldType::SFVec3f>(name, fallback);
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) ? v : fallback;
}
bool sfBool(const vrml::Node& n, vrml::FieldName name, bool fallback) {
  return n.get<FieldType::SFBool>(name, fallback);
}
const vrml::Node* usable(const vrml::NodePtr& p) {
  return p && !p->unresolved ? p.get() : nullptr;
}

/// A cache key of a node and what it is made of (its revision and its SFNode fields').
struct Key {
  std::uint64_t serial = ~std::uint64_t{0}, revision = 0;
  bool operator==(const Key&) const = default;
};
Key keyOf(const vrml::Node* n) {
  return n ? Key{n->serial(), vrml::revisionWithFields(*n)} : Key{};
}

/// An IndexedFaceSet or IndexedLineSet of an emitter's coord and coordIndex, tessellated.
vrml::Mesh indexedMesh(const vrml::Node& emitter, std::string_view type) {
  auto t = vrml::x3dNodeType(type);
  if (!t) return {};
  vrml::Node n(t);
  for (std::string_view name : {"coord", "coordIndex"}) {
    vrml::FieldValue* to = n.field(name);
    const vrml::FieldValue* from = emitter.field(name);
    if (to && from && to->type() == from->type()) *to = *from;
  }
  if (vrml::FieldValue* convex = n.field("convex"))
    *convex = vrml::FieldValue::make<FieldType::SFBool>(false);
  if (vrml::FieldValue* crease = n.field("creaseAngle"))
    *crease = vrml::FieldValue::make<FieldType::SFFloat>(3.14159265f);
  return vrml::tessellate(n);
}

}  // namespace

/// What the emitter and the physics models are made of, and the random sequence.
struct ParticleSimulation::Emitters {
  explicit Emitters(std::uint64_t seed) : random(seed) {}
  Random random;
  // SurfaceEmitter's surface, VolumeEmitter's faces: triangles; PolylineEmitter: segments.
  Key emitterKey, surfaceKey;
  Triangles triangles;
  bool surfaceSolid = true;
  std::vector<glm::vec3> segments;  // pairs
  std::vector<float> cumulativeLength;
  // The BoundedPhysicsModels' geometry (normals times damping).
  std::vector<Key> boundedKeys;
  Triangles bounds;
  bool tooLarge = false;

  /// The emitter's geometry, made again when it changed.
  void prepare(const vrml::Node* emitter) {
    const Key key = keyOf(emitter);
    const vrml::Node* surface = emitter && emitter->typeId() == vrml::NodeTypeId::SurfaceEmitter
                                    ? usable(emitter->sfnode("surface"))
                                    : nullptr;
    const Key sKey = keyOf(surface);
    if (key == emitterKey && sKey == surfaceKey) return;
    emitterKey = key;
    surfaceKey = sKey;
    triangles = {};
    segments.clear();
    cumulativeLength.clear();
    tooLarge = false;
    if (!emitter) return;
    switch (emitter->typeId()) {
      case vrml::NodeTypeId::SurfaceEmitter:
        if (surface) {
          const vrml::Mesh mesh = vrml::tessellate(*surface);
          surfaceSolid = mesh.solid;
          tooLarge = !triangles.assign(mesh, 1.0f, kMaxTriangles);
        }
        break;
      case vrml::NodeTypeId::VolumeEmitter:
        tooLarge = !triangles.assign(indexedMesh(*emitter, "IndexedFaceSet"), 1.0f, kMaxTriangles);
        break;
      case vrml::NodeTypeId::PolylineEmitter: {
        const vrml::Mesh mesh = indexedMesh(*emitter, "IndexedLineSet");
        if (mesh.primitive != vrml::Primitive::lines || mesh.indices.size() / 2 > kMaxTriangles) {
          tooLarge = mesh.indices.size() / 2 > kMaxTriangles;
          break;
        }
        float sum = 0.0f;
        for (std::size_t i = 0; i + 1 < mesh.indices.size(); i += 2) {
          if (mesh.indices[i] >= mesh.positions.size() ||
              mesh.indices[i + 1] >= mesh.positions.size())
            continue;
          const glm::vec3 a = mesh.positions[mesh.indices[i]],
                          b = mesh.positions[mesh.indices[i + 1]];
          const float length = glm::length(b - a);
          sum += std::isfinite(length) ? length : 0.0f;
          segments.push_back(a);
          segments.push_back(b);
          cumulativeLength.push_back(sum);
        }
        break;
      }
      default:
        break;
    }
  }

  /// The enabled BoundedPhysicsModels' triangles, made again when one changed.
  void prepareBounds(const std::vector<vrml::NodePtr>& physics) {
    std::vector<Key> keys;
    for (const vrml::NodePtr& p : physics)
      if (const vrml::Node* m = usable(p); m &&
                                           m->typeId() == vrml::NodeTypeId::BoundedPhysicsModel &&
                                           sfBool(*m, "enabled", true)) {
        keys.push_back(keyOf(m));
        keys.push_back(keyOf(usable(m->sfnode("geometry"))));
      }
    if (keys == boundedKeys) return;
    boundedKeys = keys;
    bounds = {};
    for (const vrml::NodePtr& p : physics) {
      const vrml::Node* m = usable(p);
      if (!m || m->typeId() != vrml::NodeTypeId::BoundedPhysicsModel ||
          !sfBool(*m, "enabled", true))
        continue;
      const vrml::Node* g = usable(m->sfnode("geometry"));
      if (!g) continue;
      Triangles t;
      if (!t.assign(vrml::tessellate(*g), sfFloat(*m, "damping", 1.0f), kMaxTriangles) ||
          bounds.size() + t.size() > kMaxTriangles) {
        tooLarge = true;
        continue;
      }
      bounds.append(t);
    }
  }

  float speed(const vrml::Node& e) {
    const float s = std::max(0.0f, sfFloat(e, "speed", 0.0f));
    const float v = std::max(0.0f, sfFloat(e, "variation", 0.25f));
    return random.uniform(std::max(0.0f, s - s * v), s + s * v);
  }

  /// Velocity along `direction` (field "direction"), or in every direction when it is 0.
  glm::vec3 directedVelocity(const vrml::Node& e, glm::vec3 fallbackDirection) {
    const glm::vec3 d = sfVec3(e, "direction", fallbackDirection);
    const float l = glm::length(d);
    // (Each draw in its own statement: the operands of one expression are evaluated in an
    // order that differs between compilers, and so would the sequence of draws.)
    const float s = speed(e);
    if (!(l > 0.0f)) return random.unitVector() * s;
    return d / l * s;
  }

  /// A newborn particle's position and velocity from `emitter` (null: X_ITE's default
  /// PointEmitter, at the origin at speed 0). False: nowhere to be born (hidden).
  bool birth(const vrml::Node* emitter, glm::vec3& p, glm::vec3& v) {
    if (!emitter) {
      p = glm::vec3(0.0f);
      v = glm::vec3(0.0f);
      return true;
    }
    switch (emitter->typeId()) {
      case vrml::NodeTypeId::ConeEmitter: {
        const glm::vec3 d = sfVec3(*emitter, "direction", {0, 1, 0});
        const float s = speed(*emitter);  // (drawn first: see directedVelocity)
        if (glm::length(d) > 0.0f)
          v = random.unitVectorInCone(d, sfFloat(*emitter, "angle", 0.785398f)) * s;
        else
          v = random.unitVector() * s;
        p = sfVec3(*emitter, "position", glm::vec3(0.0f));
        return true;
      }
      case vrml::NodeTypeId::ExplosionEmitter: {
        const float s = speed(*emitter);  // (drawn first: see directedVelocity)
        v = random.unitVector() * s;
        p = sfVec3(*emitter, "position", glm::vec3(0.0f));
        return true;
      }
      case vrml::NodeTypeId::PolylineEmitter: {
        v = directedVelocity(*emitter, {0, 1, 0});
        if (cumulativeLength.empty() || !(cumulativeLength.back() > 0.0f)) return false;
        const float f = random.uniform() * cumulativeLength.back();
        auto it = std::lower_bound(cumulativeLength.begin(), cumulativeLength.end(), f);
        if (it == cumulativeLength.end()) --it;
        const auto k = static_cast<std::size_t>(it - cumulativeLength.begin());
        const float start = k == 0 ? 0.0f : cumulativeLength[k - 1];
        const float length = cumulativeLength[k] - start;
        const float w = length > 0.0f ? std::clamp((f - start) / length, 0.0f, 1.0f) : 0.0f;
        p = glm::mix(segments[2 * k], segments[2 * k + 1], w);
        return true;
      }
      case vrml::NodeTypeId::SurfaceEmitter: {
        glm::vec3 n;
        if (!triangles.sample(random, p, n)) return false;
        if (!surfaceSolid && random.uniform() > 0.5f) n = -n;
        v = n * speed(*emitter);
        return true;
      }
      case vrml::NodeTypeId::VolumeEmitter:
        v = directedVelocity(*emitter, {0, 1, 0});
        p = insidePoint();
        return true;
      default:  // PointEmitter (and anything else in the emitter field)
        v = directedVelocity(*emitter, {0, 1, 0});
        p = sfVec3(*emitter, "position", glm::vec3(0.0f));
        return true;
    }
  }

  /// X_ITE's VolumeEmitter: a line through a random surface point, its direction biased
  /// towards the normal; a random point between a random pair of its crossings of the
  /// surface (inside for a closed surface; not uniform by volume). The origin when the
  /// line crosses fewer than twice.
  glm::vec3 insidePoint() {
    glm::vec3 q, n;
    if (!triangles.sample(random, q, n)) return glm::vec3(0.0f);
    // A direction in the hemisphere around n, cos(polar) = U^(1/3).
    const float c = std::cbrt(random.uniform());
    const float theta = random.uniform(-3.14159265f, 3.14159265f);
    const float r = std::sqrt(std::max(0.0f, 1.0f - c * c));
    const glm::vec3 local{std::sin(theta) * r, std::cos(theta) * r, c};
    const glm::vec3 helper = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    const glm::vec3 u = glm::normalize(glm::cross(helper, n)), w = glm::cross(n, u);
    const glm::vec3 dir = local.x * u + local.y * w + local.z * n;
    hits.clear();
    triangles.intersectLine(q, dir, budget, [this](float t, const glm::vec3&, const glm::vec3&) {
      if (hits.size() < 4096) hits.push_back(t);
    });
    const std::size_t k = hits.size() - hits.size() % 2;
    if (k == 0) return glm::vec3(0.0f);
    std::sort(hits.begin(), hits.end());
    auto pair = static_cast<std::size_t>(random.uniform() * static_cast<float>(k / 2)) * 2;
    pair = std::min(pair, k - 2);
    return q + dir * glm::mix(hits[pair], hits[pair + 1], random.uniform());
  }
  std::vector<float> hits;
  /// Triangle tests left in this step (VolumeEmitter births, bounces): past them the step
  /// places and bounces no more by geometry (kMaxTestsPerStep).
  std::size_t budget = 0;

  /// X_ITE's bounce: the first crossing ahead of `from` along the velocity; when the step
  /// from `from` to `p` crossed its plane, the velocity is reflected (times the damping)
  /// and the particle put just off the surface.
  void bounce(const glm::vec3& from, glm::vec3& p, glm::vec3& v) {
    const float speed2 = glm::dot(v, v);
    if (bounds.empty() || !(speed2 > 0.0f)) return;
    const glm::vec3 dir = v / std::sqrt(speed2);
    float best = std::numeric_limits<float>::infinity();
    glm::vec3 hitPoint{0.0f}, hitNormal{0.0f};
    bounds.intersectLine(from, dir, budget,
                         [&](float t, const glm::vec3& point, const glm::vec3& normal) {
                           if (t >= 0.0f && t < best) {
                             best = t;
                             hitPoint = point;
                             hitNormal = normal;
                           }
                         });
    const float damping = glm::length(hitNormal);
    if (!std::isfinite(best) || !(damping > 0.0f)) return;
    const glm::vec3 nn = hitNormal / damping;
    const float before = glm::dot(from - hitPoint, nn), after = glm::dot(p - hitPoint, nn);
    if ((before >= 0.0f) == (after >= 0.0f)) return;  // not crossed this step
    glm::vec3 reflected = v - 2.0f * glm::dot(v, nn) * nn;
    p = hitPoint + glm::normalize(reflected) * 0.0001f;
    v = reflected * damping;
  }
};

ParticleSimulation::ParticleSimulation(std::uint64_t seed, double loadTime)
    : emitters_(std::make_unique<Emitters>(seed)), lastTime_(loadTime) {}
ParticleSimulation::~ParticleSimulation() = default;
ParticleSimulation::ParticleSimulation(ParticleSimulation&&) noexcept = default;
ParticleSimulation& ParticleSimulation::operator=(ParticleSimulation&&) noexcept = default;

void ParticleSimulation::advance(const vrml::Node& system, double now) {
  if (!(now >= lastTime_)) return;
  const auto dt = static_cast<float>(now - lastTime_);
  lastTime_ = now;
  const int maxField = system.get<FieldType::SFInt32>("maxParticles", 200);
  const bool enabled = sfBool(system, "enabled", true);
  active_ = enabled && maxField > 0;
  if (!active_) {
    if (!particles_.empty()) ++revision_;
    particles_.clear();
    created_ = false;  // enabled again: emission starts anew
    return;
  }
  clamped_ = static_cast<std::size_t>(maxField) > kMaxParticles;
  const std::size_t maxParticles = std::min(static_cast<std::size_t>(maxField), kMaxParticles);
  if (particles_.size() > maxParticles) particles_.resize(maxParticles);
  const vrml::Node* emitter = usable(system.sfnode("emitter"));
  Emitters& e = *emitters_;
  e.budget = kMaxTestsPerStep;
  e.prepare(emitter);
  const std::vector<vrml::NodePtr>& physics = system.mfnode("physics");
  e.prepareBounds(physics);
  clamped_ = clamped_ || e.tooLarge;

  const float lifetime = std::max(0.0f, sfFloat(system, "particleLifetime", 5.0f));
  const float variation = std::max(0.0f, sfFloat(system, "lifetimeVariation", 0.25f));
  bool create =
      sfBool(system, "createParticles", true) && (!emitter || sfBool(*emitter, "on", true));
  bool rebirthAll = false;
  if (!created_) {
    created_ = true;
    creationTime_ = now;
    if (emitter && emitter->typeId() == vrml::NodeTypeId::ExplosionEmitter)
      creationTime_ = -std::numeric_limits<double>::infinity();  // the first burst now
  }
  if (emitter && emitter->typeId() == vrml::NodeTypeId::ExplosionEmitter) {
    // All at once, again every L (1 + v) seconds; between bursts the dead stay hidden.
    if (now - creationTime_ > static_cast<double>(lifetime) * (1.0 + variation)) {
      creationTime_ = now;
      particles_.resize(maxParticles);
      rebirthAll = true;
    } else {
      create = false;
    }
  } else if (particles_.size() < maxParticles) {
    const double rate = lifetime > 0.0f ? static_cast<double>(maxParticles) / lifetime
                                        : std::numeric_limits<double>::infinity();
    const double joining = std::floor((now - creationTime_) * rate);
    if (joining > 0.0) {
      creationTime_ = now;
      const double room = static_cast<double>(maxParticles - particles_.size());
      const auto n = static_cast<std::size_t>(std::min(room, joining));  // (joining may be inf)
      Particle newborn;
      newborn.lifetime = -1.0f;  // born at the first step below
      particles_.resize(particles_.size() + n, newborn);
    }
  }

  // This step's velocity increments (X_ITE: once per frame, only with a mass).
  struct Push {
    glm::vec3 dv;
    float coneAngle;
  };
  std::vector<Push> pushes;
  const float mass = emitter ? std::max(0.0f, sfFloat(*emitter, "mass", 0.0f)) : 0.0f;
  if (mass > 0.0f) {
    const float timeByMass = dt / mass;
    for (const vrml::NodePtr& p : physics) {
      const vrml::Node* m = usable(p);
      if (!m || !sfBool(*m, "enabled", true)) continue;
      if (m->typeId() == vrml::NodeTypeId::ForcePhysicsModel) {
        pushes.push_back({sfVec3(*m, "force", {0, -9.8f, 0}) * timeByMass, 0.0f});
      } else if (m->typeId() == vrml::NodeTypeId::WindPhysicsModel) {
        const float s0 = std::max(0.0f, sfFloat(*m, "speed", 0.1f));
        const float g = std::max(0.0f, sfFloat(*m, "gustiness", 0.1f));
        const float s = e.random.uniform(std::max(0.0f, s0 - s0 * g), s0 + s0 * g);
        const float pressure = s > 0.0f ? std::pow(10.0f, 2.0f * std::log(s)) * 0.64615f : 0.0f;
        glm::vec3 d = sfVec3(*m, "direction", {1, 0, 0});
        d = glm::length(d) > 0.0f ? glm::normalize(d) : e.random.unitVector();
        const float area = emitter ? std::max(0.0f, sfFloat(*emitter, "surfaceArea", 0.0f)) : 0.0f;
        const float turbulence = std::clamp(sfFloat(*m, "turbulence", 0.0f), 0.0f, 1.0f);
        pushes.push_back({d * area * pressure * timeByMass, 3.14159265f * turbulence});
      }
    }
  }

  for (Particle& p : particles_) {
    p.elapsed += dt;
    if (rebirthAll || p.elapsed > p.lifetime) {
      p.lifetime = e.random.uniform(std::max(0.0f, lifetime - lifetime * variation),
                                    lifetime + lifetime * variation);
      p.elapsed = 0.0f;
      p.visible = create && e.birth(emitter, p.position, p.velocity);
      if (!p.visible) p.velocity = glm::vec3(0.0f);
      continue;
    }
    if (!p.visible) continue;
    for (const Push& push : pushes) {
      const float magnitude = glm::length(push.dv);
      if (!(magnitude > 0.0f) || !std::isfinite(magnitude)) continue;
      p.velocity += push.coneAngle > 0.0f
                        ? e.random.unitVectorInCone(push.dv, push.coneAngle) * magnitude
                        : push.dv;
    }
    const glm::vec3 from = p.position;
    p.position += p.velocity * dt;
    e.bounce(from, p.position, p.velocity);
    if (!std::isfinite(p.position.x + p.position.y + p.position.z)) p.visible = false;
  }
  clamped_ = clamped_ || e.budget == 0;
  ++revision_;
}

}  // namespace gs::particles
