// The node kinds that traversal and the renderer act on, from the node model
// (Node::typeId, Node::is), looked up once per NodeType.
#pragma once

#include "vrml/node.hpp"

#include <cstdint>

namespace gs::scene {

enum class NodeKind : std::uint8_t {
  other,  // not rendered (sensors, interpolators, Script, unknown types...)
  Anchor,
  Billboard,
  Collision,
  Group,
  Transform,
  Switch,
  LOD,
  Inline,
  Shape,
  DirectionalLight,
  PointLight,
  SpotLight,
  EnvironmentLight,  // X3D 4.1: image-based lighting of physical materials
  ClipPlane,         // X3D Rendering: clips its siblings and their descendants
  TextureProjector,  // X3D TextureProjection (clause 42): projects onto shapes, like a light
  Viewpoint,
  NavigationInfo,
  Background,
  Fog,
  LocalFog,        // X3D EnvironmentalEffects: fogs its siblings and their descendants
  CADFace,         // X3D CADGeometry: its `shape` field is drawn
  LayerSet,        // X3D Layering (clause 35): drawn at the world's root only
  Layer,           // X3D Layering: one of a LayerSet's `layers`
  HAnimHumanoid,   // X3D H-Anim (clause 26): its `skeleton` and `skin` in its own coordinates
  ScreenGroup,     // X3D Layout (clause 36): children in pixels of the view
  LayoutGroup,     // X3D Layout: children placed by its Layout in the enclosing rectangle
  LayoutLayer,     // X3D Layout: a layer of a LayerSet, seen by its own orthographic view
  Collidable,      // X3D RigidBodyPhysics' CollidableShape / CollidableOffset: placed shape
  GeoLOD,          // X3D Geospatial (clause 25.4.4): root or four children by range
  ParticleSystem,  // X3D ParticleSystems (clause 40): a shape whose geometry is its particles
  OutlineGroup,    // GhostSpace extensions (docs/vrml-extensions.md)
  QuantizedNormalVectors,
};

/// The kind of `node`: `other` for unresolved EXTERNPROTO instances and unknown types.
NodeKind nodeKind(const vrml::Node& node);

/// True for the grouping nodes whose `children` field is traversed.
inline bool hasChildren(NodeKind k) {
  return k == NodeKind::Anchor || k == NodeKind::Billboard || k == NodeKind::Collision ||
         k == NodeKind::Group || k == NodeKind::Transform || k == NodeKind::OutlineGroup;
}

}  // namespace gs::scene
