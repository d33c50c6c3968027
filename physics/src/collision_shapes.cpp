// The collision shape of a RigidBody (X3D 4.0 clauses 37.4.3, 37.4.4): one child of the
// body's compound per collidable geometry, as X_ITE 15 makes them (docs/x3d.md "Rigid body
// physics"): Box, Sphere, closed Cylinder and Cone as Bullet's own shapes, other surfaces
// as triangles.
#include "world_impl.hpp"

#include "geometry/geometry.hpp"

#include <BulletCollision/CollisionShapes/btConvexHullShape.h>

#include <cmath>

namespace gs::physics {

namespace {

using vrml::FieldType;

float positive(float v, float fallback) {
  return std::isfinite(v) && v > 0.0f ? v : fallback;
}

/// A shape of Bullet's own for the primitives it has, else null.
std::unique_ptr<btCollisionShape> primitiveShape(const vrml::Node& g) {
  switch (g.typeId()) {
    case vrml::NodeTypeId::Box: {
      const glm::vec3 size = g.get<FieldType::SFVec3f>("size", glm::vec3(2.0f));
      return std::make_unique<btBoxShape>(
          btVector3(positive(size.x, 0.0f), positive(size.y, 0.0f), positive(size.z, 0.0f)) * 0.5f);
    }
    case vrml::NodeTypeId::Sphere:
      return std::make_unique<btSphereShape>(
          positive(g.get<FieldType::SFFloat>("radius", 1.0f), 0.0f));
    case vrml::NodeTypeId::Cylinder:
      if (g.get<FieldType::SFBool>("side", true) && g.get<FieldType::SFBool>("top", true) &&
          g.get<FieldType::SFBool>("bottom", true)) {
        const float r = positive(g.get<FieldType::SFFloat>("radius", 1.0f), 0.0f);
        const float h = positive(g.get<FieldType::SFFloat>("height", 2.0f), 0.0f);
        return std::make_unique<btCylinderShape>(btVector3(r, h * 0.5f, r));
      }
      return nullptr;
    case vrml::NodeTypeId::Cone:
      if (g.get<FieldType::SFBool>("side", true) && g.get<FieldType::SFBool>("bottom", true))
        return std::make_unique<btConeShape>(
            positive(g.get<FieldType::SFFloat>("bottomRadius", 1.0f), 0.0f),
            positive(g.get<FieldType::SFFloat>("height", 2.0f), 0.0f));
      return nullptr;
    default:
      return nullptr;
  }
}

void addGeometry(PhysicsBody& b, const vrml::Node& geometry, const btTransform& local,
                 std::vector<std::string>& warnings) {
  std::unique_ptr<btCollisionShape> shape = primitiveShape(geometry);
  if (!shape) {
    const vrml::Mesh mesh = vrml::tessellate(geometry);
    if (mesh.primitive != vrml::Primitive::triangles || mesh.triangleCount() == 0) return;
    if (mesh.triangleCount() > RigidBodyWorld::kMaxTriangles) {
      warnings.push_back(geometry.typeName() + " of more than " +
                         std::to_string(RigidBodyWorld::kMaxTriangles) +
                         " triangles: no collision shape");
      return;
    }
    if (b.fixed || !(b.node->get<FieldType::SFFloat>("mass", 1.0f) > 0.0f)) {
      // A body that does not move: the triangles themselves.
      auto triangles = std::make_unique<btTriangleMesh>();
      for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
        triangles->addTriangle(toBt(mesh.positions[mesh.indices[i]]),
                               toBt(mesh.positions[mesh.indices[i + 1]]),
                               toBt(mesh.positions[mesh.indices[i + 2]]));
      shape = std::make_unique<btBvhTriangleMeshShape>(triangles.get(), false);
      b.meshes.push_back(std::move(triangles));
    } else {
      // A moving body: Bullet collides moving triangle meshes with nothing; their convex
      // hull collides with every shape.
      auto hull = std::make_unique<btConvexHullShape>();
      for (const glm::vec3& p : mesh.positions) hull->addPoint(toBt(p), false);
      hull->recalcLocalAabb();
      shape = std::move(hull);
    }
  }
  b.compound->addChildShape(local, shape.get());
  b.shapes.push_back(std::move(shape));
}

/// `collidable` placed at `local` in the body (identity for one directly in the body's
/// geometry, whose own translation and rotation are the body's).
void addCollidable(PhysicsBody& b, const vrml::Node& collidable, const btTransform& local,
                   int depth, std::vector<std::string>& warnings) {
  if (depth > 32 || !collidable.get<FieldType::SFBool>("enabled", true)) return;
  if (collidable.typeId() == vrml::NodeTypeId::CollidableShape) {
    const vrml::NodePtr& shape = collidable.sfnode("shape");
    if (!shape) return;
    const vrml::NodePtr& geometry = shape->sfnode("geometry");
    if (geometry && !geometry->unresolved) addGeometry(b, *geometry, local, warnings);
  } else if (collidable.typeId() == vrml::NodeTypeId::CollidableOffset) {
    const vrml::NodePtr& inner = collidable.sfnode("collidable");
    if (!inner) return;
    const btTransform own =
        toTransform(inner->get<FieldType::SFVec3f>("translation", glm::vec3(0.0f)),
                    inner->get<FieldType::SFRotation>("rotation", vrml::Rotation(0, 0, 1, 0)));
    addCollidable(b, *inner, local * own, depth + 1, warnings);
  }
}

}  // namespace

void buildCollisionShape(PhysicsBody& b, std::vector<std::string>& warnings) {
  btTransform identity;
  identity.setIdentity();
  for (const vrml::Node* c : b.collidables) addCollidable(b, *c, identity, 0, warnings);
}

}  // namespace gs::physics
