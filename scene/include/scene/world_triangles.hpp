// A VRML97 world flattened into the triangles the QNV surface encoder takes.
#pragma once

#include <memory>

#include "qnv/mesh.hpp"
#include "vrml/scene.hpp"

namespace gs::scene {

/// Every triangle drawn from the bound Viewpoint (the chosen Switch children and LOD
/// levels, Inlines included: scene::SceneTraversal), in world coordinates (each Shape's
/// transform applied; clause 4.4.3). Colours: per-vertex Color when the geometry has
/// one, else the Material's diffuseColor with alpha 1 - transparency, else white for a
/// Shape without Material (clause 6.3: unlit). Lines and points are skipped.
qnv::TriangleMesh worldTriangles(std::shared_ptr<const vrml::Scene> scene);

}  // namespace gs::scene
