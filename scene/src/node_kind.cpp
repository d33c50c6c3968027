#include "scene/node_kind.hpp"

namespace gs::scene {

NodeKind nodeKind(const vrml::Node& node) {
  if (node.unresolved) return NodeKind::other;
  using vrml::NodeTypeId;
  switch (node.typeId()) {
    case NodeTypeId::Anchor:
      return NodeKind::Anchor;
    case NodeTypeId::Billboard:
      return NodeKind::Billboard;
    case NodeTypeId::Collision:
      return NodeKind::Collision;
    case NodeTypeId::Group:
    // X3D's StaticGroup (clause 10.4.3) is no X3DGroupingNode (its children cannot
    // change), and ViewpointGroup (23.4.6) groups viewpoints: both walk their children.
    case NodeTypeId::StaticGroup:
    case NodeTypeId::ViewpointGroup:
      return NodeKind::Group;
    case NodeTypeId::Transform:
    case NodeTypeId::CADPart:  // Transform's fields (X3D 4.0 clause 32.4.4)
    // H-Anim's joints and sites (X3D 4.0 clauses 26.3.2, 26.3.4) transform their children
    // as a Transform does, with the same fields; a segment too with castle-engine's
    // translation, rotation and scale (vrml/gen/gen_node_model.py, castle extensions).
    case NodeTypeId::HAnimJoint:
    case NodeTypeId::HAnimSegment:
    case NodeTypeId::HAnimSite:
    // X3D Geospatial (clause 25): their frames are vrml::transformMatrix's too.
    case NodeTypeId::GeoLocation:
    case NodeTypeId::GeoTransform:
    // X3D DIS (clause 28.4.3): a Transform its PDUs move (runtime/src/dis_nodes.cpp).
    case NodeTypeId::EspduTransform:
      return NodeKind::Transform;
    case NodeTypeId::HAnimHumanoid:
      return NodeKind::HAnimHumanoid;
    case NodeTypeId::ScreenGroup:
      return NodeKind::ScreenGroup;
    case NodeTypeId::LayoutGroup:
      return NodeKind::LayoutGroup;
    case NodeTypeId::LayoutLayer:
      return NodeKind::LayoutLayer;
    case NodeTypeId::CADFace:  // one shape (or LOD, Transform) in `shape` (32.4.2)
      return NodeKind::CADFace;
    case NodeTypeId::LayerSet:
      return NodeKind::LayerSet;
    case NodeTypeId::Layer:
      return NodeKind::Layer;
    case NodeTypeId::Switch:
      return NodeKind::Switch;
    case NodeTypeId::LOD:
      return NodeKind::LOD;
    case NodeTypeId::Inline:
      return NodeKind::Inline;
    case NodeTypeId::Shape:
      return NodeKind::Shape;
    case NodeTypeId::ParticleSystem:
      return NodeKind::ParticleSystem;
    case NodeTypeId::GeoLOD:
      return NodeKind::GeoLOD;
    case NodeTypeId::CollidableShape:
    case NodeTypeId::CollidableOffset:
      return NodeKind::Collidable;
    case NodeTypeId::DirectionalLight:
      return NodeKind::DirectionalLight;
    case NodeTypeId::PointLight:
      return NodeKind::PointLight;
    case NodeTypeId::SpotLight:
      return NodeKind::SpotLight;
    case NodeTypeId::EnvironmentLight:
      return NodeKind::EnvironmentLight;
    case NodeTypeId::ClipPlane:
      return NodeKind::ClipPlane;
    case NodeTypeId::TextureProjector:
    case NodeTypeId::TextureProjectorParallel:
      return NodeKind::TextureProjector;
    case NodeTypeId::Viewpoint:
    case NodeTypeId::OrthoViewpoint:  // Camera::orthographic (X3D 4.0 clause 23.4.5)
    case NodeTypeId::GeoViewpoint:    // geo position, orientation in its up frame (25.4.10)
      return NodeKind::Viewpoint;
    case NodeTypeId::NavigationInfo:
      return NodeKind::NavigationInfo;
    case NodeTypeId::Background:
    case NodeTypeId::TextureBackground:  // its faces are textures (X3D 4.0 clause 24.4.3)
      return NodeKind::Background;
    case NodeTypeId::Fog:
      return NodeKind::Fog;
    case NodeTypeId::LocalFog:
      return NodeKind::LocalFog;
    case NodeTypeId::OutlineGroup:
      return NodeKind::OutlineGroup;
    case NodeTypeId::QuantizedNormalVectors:
    // A 3D Gaussian splatting cloud (X_ITE's GaussianSplats node; render/src/scene_splats.cpp).
    case NodeTypeId::GaussianSplats:
    // X3D's volume data nodes are drawn as QNV vectors of their voxels
    // (render/src/volume_data.hpp).
    case NodeTypeId::VolumeData:
    case NodeTypeId::IsoSurfaceVolumeData:
    case NodeTypeId::SegmentedVolumeData:
      return NodeKind::QuantizedNormalVectors;
    default:
      // Any other grouping node (X3DGroupingNode) is drawn as a Group: its children.
      return node.is(vrml::AbstractType::X3DGroupingNode) ? NodeKind::Group : NodeKind::other;
  }
}

}  // namespace gs::scene
