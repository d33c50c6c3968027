// ParticleSystems' meshes for the traversal (X3D 4.0 clause 40): the particles the execution
// model moved (runtime/src/particle_systems.cpp) drawn as their geometryType
// (particles/particle_mesh.hpp), cached under a geometry node of their own so that the
// renderer uploads them like any tessellation when they change.
#include "encodings/node_types.hpp"
#include "particles/particle_mesh.hpp"
#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

namespace gs::scene {

const vrml::Node* SceneTraversal::particleGeometry(const vrml::Node& system,
                                                   const particles::ParticleSimulation& simulation,
                                                   const glm::mat4& localToEye) {
  const particles::GeometryType type = particles::geometryTypeOf(sfString(system, "geometryType"));
  ParticleDraw& draw = particleDraws_[&system];
  if (!draw.geometry || draw.type != static_cast<int>(type)) {
    // A node of the kind of geometry it stands for (points, lines or triangles): what the
    // renderer reads of the geometry node itself (texCoord: none) fits.
    const char* kind = type == particles::GeometryType::point  ? "PointSet"
                       : type == particles::GeometryType::line ? "LineSet"
                                                               : "TriangleSet";
    auto nodeType = vrml::x3dNodeType(kind);
    if (!nodeType) return nullptr;
    draw = ParticleDraw{};
    draw.geometry = std::make_shared<vrml::Node>(nodeType);
    draw.geometry->location = system.location;
    draw.type = static_cast<int>(type);
  }
  const glm::mat3 eyeToLocal = glm::inverse(glm::mat3(localToEye));
  const bool facesViewer = type == particles::GeometryType::sprite;
  if (draw.simulationRevision != simulation.revision() ||
      (facesViewer && eyeToLocal != draw.eyeToLocal)) {
    draw.simulationRevision = simulation.revision();
    draw.eyeToLocal = eyeToLocal;
    draw.geometry->markChanged();
    CachedMesh& cached = meshes_[draw.geometry.get()];
    cached.mesh = particles::particleMesh(system, type, simulation.particles(), eyeToLocal);
    cached.arraysDropped = false;
    cached.rotatedUse = false;
    cached.boundsPositions.clear();
    cached.revision = vrml::revisionWithFields(*draw.geometry);
  }
  return draw.geometry.get();
}

}  // namespace gs::scene
