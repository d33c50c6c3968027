#include "vrml/node_support.hpp"

#include "vrml/node_table.hpp"

#include <algorithm>
#include <array>

namespace gs::vrml {

namespace {

// X3D nodes beyond VRML97's that have their behaviour (geometry_x3d.cpp, geometry_2d.cpp,
// runtime/src/event_utilities.cpp, render's physical program and textures.cpp; metadata
// nodes have none
// to give). One name a line:
// docs/gen/gen_x3d_status.py reads this list.
constexpr std::array kImplementedX3d = {
    NodeTypeId::IndexedTriangleSet,
    NodeTypeId::IndexedTriangleFanSet,
    NodeTypeId::IndexedTriangleStripSet,
    NodeTypeId::TriangleSet,
    NodeTypeId::TriangleFanSet,
    NodeTypeId::TriangleStripSet,
    NodeTypeId::LineSet,
    NodeTypeId::CADAssembly,
    NodeTypeId::CADFace,
    NodeTypeId::CADLayer,
    NodeTypeId::CADPart,
    NodeTypeId::IndexedQuadSet,
    NodeTypeId::QuadSet,
    NodeTypeId::ColorRGBA,
    NodeTypeId::CoordinateDouble,
    NodeTypeId::MultiTextureCoordinate,
    NodeTypeId::MultiTexture,  // render/src/multi_texture.cpp
    NodeTypeId::MultiTextureTransform,
    NodeTypeId::TextureCoordinateGenerator,  // render/src/texture_generation.cpp
    NodeTypeId::StaticGroup,                 // scene/src/node_kind.cpp
    NodeTypeId::ComposedCubeMapTexture,      // render/src/textures.cpp, environment_maps.cpp
    NodeTypeId::ImageCubeMapTexture,         // the same; DDS files: render/src/dds_images.cpp
    NodeTypeId::GeneratedCubeMapTexture,     // render/src/generated_cube_maps.cpp
    NodeTypeId::HAnimHumanoid,  // scene/src/traversal.cpp: skeleton and skin (bind pose)
    NodeTypeId::HAnimJoint,     // scene/src/node_kind.cpp: as Transform
    NodeTypeId::HAnimSegment,
    NodeTypeId::HAnimSite,
    NodeTypeId::Layout,  // scene/src/layout.cpp, traversal.cpp
    NodeTypeId::LayoutGroup,
    NodeTypeId::LayoutLayer,
    NodeTypeId::ScreenGroup,
    NodeTypeId::ScreenFontStyle,  // scene/src/text_mesh.cpp: pointSize
    NodeTypeId::NurbsCurve,       // geometry/src/geometry_nurbs.cpp
    NodeTypeId::NurbsPatchSurface,
    NodeTypeId::NurbsTrimmedSurface,        // untrimmed
    NodeTypeId::NurbsTextureCoordinate,     // geometry/src/geometry_nurbs.cpp
    NodeTypeId::NurbsPositionInterpolator,  // runtime/src/interpolators_nurbs.cpp
    NodeTypeId::NurbsOrientationInterpolator,
    NodeTypeId::NurbsSurfaceInterpolator,
    NodeTypeId::PixelTexture3D,  // render/src/textures_3d.cpp; volume data too
    NodeTypeId::ComposedTexture3D,
    NodeTypeId::ImageTexture3D,
    NodeTypeId::TextureCoordinate3D,  // geometry/src/geometry.cpp (Mesh::texCoordsStrq)
    NodeTypeId::TextureCoordinate4D,
    NodeTypeId::VolumeData,  // render/src/volume_data.cpp: QNV splats
    NodeTypeId::IsoSurfaceVolumeData,
    NodeTypeId::SegmentedVolumeData,
    NodeTypeId::OpacityMapVolumeStyle,
    NodeTypeId::ViewpointGroup,
    NodeTypeId::TextureTransform3D,
    NodeTypeId::TextureTransformMatrix3D,
    NodeTypeId::OrthoViewpoint,
    NodeTypeId::Arc2D,
    NodeTypeId::ArcClose2D,
    NodeTypeId::Circle2D,
    NodeTypeId::Disk2D,
    NodeTypeId::Polyline2D,
    NodeTypeId::Polypoint2D,
    NodeTypeId::Rectangle2D,
    NodeTypeId::TriangleSet2D,
    NodeTypeId::MetadataBoolean,
    NodeTypeId::MetadataDouble,
    NodeTypeId::MetadataFloat,
    NodeTypeId::MetadataInteger,
    NodeTypeId::MetadataSet,
    NodeTypeId::MetadataString,
    NodeTypeId::BooleanFilter,
    NodeTypeId::BooleanSequencer,
    NodeTypeId::BooleanToggle,
    NodeTypeId::BooleanTrigger,
    NodeTypeId::IntegerSequencer,
    NodeTypeId::IntegerTrigger,
    NodeTypeId::TimeTrigger,
    NodeTypeId::PhysicalMaterial,
    NodeTypeId::UnlitMaterial,
    NodeTypeId::TwoSidedMaterial,
    NodeTypeId::ClipPlane,
    NodeTypeId::EnvironmentLight,  // X3D 4.1 (vrml/gen/gen_node_model.py)
    NodeTypeId::GaussianSplats,    // X_ITE's, X3D 4.1 draft (vrml/gen/gen_node_model.py)
    NodeTypeId::TextureProperties,
    NodeTypeId::TransformSensor,
    NodeTypeId::ColorChaser,
    NodeTypeId::ColorDamper,
    NodeTypeId::CoordinateChaser,
    NodeTypeId::CoordinateDamper,
    NodeTypeId::OrientationChaser,
    NodeTypeId::OrientationDamper,
    NodeTypeId::PositionChaser,
    NodeTypeId::PositionChaser2D,
    NodeTypeId::PositionDamper,
    NodeTypeId::PositionDamper2D,
    NodeTypeId::ScalarChaser,
    NodeTypeId::ScalarDamper,
    NodeTypeId::TexCoordChaser2D,
    NodeTypeId::TexCoordDamper2D,
    NodeTypeId::KeySensor,  // runtime/src/key_sensors.cpp
    NodeTypeId::StringSensor,
    NodeTypeId::LineProperties,  // render/src/line_fill_properties.cpp
    NodeTypeId::FillProperties,
    NodeTypeId::PointProperties,
    NodeTypeId::ProtoInstance,      // the XML encoding's PROTO instance (encodings/src/x3d_xml.cpp)
    NodeTypeId::TextureBackground,  // render/src/background.cpp
    NodeTypeId::LocalFog,           // scene/src/traversal.cpp (ShapeInstance::localFog)
    NodeTypeId::FogCoordinate,      // geometry/src/geometry.cpp (Mesh::fogDepths)
    NodeTypeId::ComposedShader,     // render/src/composed_shaders.cpp (GLSL)
    NodeTypeId::ShaderPart,
    NodeTypeId::ProgramShader,  // render/src/composed_shaders.cpp (GLSL)
    NodeTypeId::ShaderProgram,
    NodeTypeId::PackagedShader,          // passed over with a warning (31.2.2)
    NodeTypeId::FloatVertexAttribute,    // geometry/src/geometry_attributes.cpp (Mesh::attributes)
    NodeTypeId::Matrix3VertexAttribute,  // and GpuMesh::bindAttributes
    NodeTypeId::Matrix4VertexAttribute,
    NodeTypeId::LoadSensor,                // runtime/src/load_sensors.cpp
    NodeTypeId::CoordinateInterpolator2D,  // runtime/src/interpolators.cpp
    NodeTypeId::PositionInterpolator2D,
    NodeTypeId::EaseInEaseOut,  // runtime/src/interpolators_x3d.cpp
    NodeTypeId::SplinePositionInterpolator,
    NodeTypeId::SplinePositionInterpolator2D,
    NodeTypeId::SplineScalarInterpolator,
    NodeTypeId::SquadOrientationInterpolator,
    NodeTypeId::GeoCoordinate,  // geospatial/, vrml/geo_nodes.hpp: clause 25
    NodeTypeId::GeoElevationGrid,
    NodeTypeId::GeoLOD,  // scene/src/traversal.cpp
    NodeTypeId::GeoLocation,
    NodeTypeId::GeoMetadata,
    NodeTypeId::GeoOrigin,
    NodeTypeId::GeoPositionInterpolator,  // runtime/src/geo_interpolator.cpp
    NodeTypeId::GeoProximitySensor,
    NodeTypeId::GeoTouchSensor,
    NodeTypeId::GeoTransform,
    NodeTypeId::GeoViewpoint,
    NodeTypeId::PickableGroup,  // runtime/src/pick_sensors.cpp: X3D clause 38
    NodeTypeId::PointPickSensor,
    NodeTypeId::LinePickSensor,
    NodeTypeId::PrimitivePickSensor,
    NodeTypeId::VolumePickSensor,
    NodeTypeId::ParticleSystem,  // particles/, runtime/src/particle_systems.cpp, scene/
    NodeTypeId::ConeEmitter,
    NodeTypeId::ExplosionEmitter,
    NodeTypeId::PointEmitter,
    NodeTypeId::PolylineEmitter,
    NodeTypeId::SurfaceEmitter,
    NodeTypeId::VolumeEmitter,
    NodeTypeId::ForcePhysicsModel,
    NodeTypeId::WindPhysicsModel,
    NodeTypeId::BoundedPhysicsModel,
    NodeTypeId::RigidBodyCollection,  // physics/, runtime/src/rigid_body_physics.cpp
    NodeTypeId::RigidBody,
    NodeTypeId::CollidableShape,
    NodeTypeId::CollidableOffset,
    NodeTypeId::CollisionCollection,
    NodeTypeId::CollisionSensor,
    NodeTypeId::CollisionSpace,
    NodeTypeId::Contact,
    NodeTypeId::BallJoint,
    NodeTypeId::DoubleAxisHingeJoint,
    NodeTypeId::MotorJoint,
    NodeTypeId::SingleAxisHingeJoint,
    NodeTypeId::SliderJoint,
    NodeTypeId::UniversalJoint,
    NodeTypeId::HAnimDisplacer,  // runtime/src/skin.cpp
    NodeTypeId::HAnimMotion,     // runtime/src/hanim_motion.cpp
    NodeTypeId::EspduTransform,  // dis/, runtime/src/dis_nodes.cpp (networkReader)
    NodeTypeId::ReceiverPdu,
    NodeTypeId::SignalPdu,
    NodeTypeId::TransmitterPdu,
    NodeTypeId::DISEntityManager,
    NodeTypeId::DISEntityTypeMapping,
    NodeTypeId::NurbsSweptSurface,  // geometry/src/geometry_nurbs_swept.cpp
    NodeTypeId::NurbsSwungSurface,
    NodeTypeId::NurbsCurve2D,  // their control curves, and trimming contours' curves
    NodeTypeId::ContourPolyline2D,
    NodeTypeId::Contour2D,  // geometry/src/geometry_nurbs.cpp (NurbsTrimmedSurface's trimming)
    NodeTypeId::NurbsSet,   // scene/src/traversal_meshes.cpp (its tessellationScale)
    NodeTypeId::TextureProjector,  // scene/src/texture_projectors.cpp,
                                   // render/src/texture_projectors.cpp
    NodeTypeId::TextureProjectorParallel,
    NodeTypeId::LayerSet,  // scene/src/traversal.cpp, render/src/scene_renderer.cpp
    NodeTypeId::Layer,
    NodeTypeId::Viewport,
    NodeTypeId::BoundaryEnhancementVolumeStyle,  // render/src/volume_raycast.cpp,
                                                 // render/src/volume_style_glsl*.cpp
    NodeTypeId::EdgeEnhancementVolumeStyle,
    NodeTypeId::SilhouetteEnhancementVolumeStyle,
    NodeTypeId::ToneMappedVolumeStyle,
    NodeTypeId::CartoonVolumeStyle,
    NodeTypeId::ShadedVolumeStyle,
    NodeTypeId::ProjectionVolumeStyle,
    NodeTypeId::ComposedVolumeStyle,
    NodeTypeId::BlendedVolumeStyle,
    NodeTypeId::AudioDestination,  // audio/src/sound_graph_scene.cpp, audio/audio_graph.hpp,
                                   // runtime/src/media_nodes.cpp (time-dependent)
    NodeTypeId::SpatialSound,
    NodeTypeId::ListenerPointSource,
    NodeTypeId::OscillatorSource,
    NodeTypeId::MicrophoneSource,
    NodeTypeId::PeriodicWave,
    NodeTypeId::BufferAudioSource,
    NodeTypeId::Analyser,
    NodeTypeId::BiquadFilter,
    NodeTypeId::Convolver,
    NodeTypeId::Delay,
    NodeTypeId::DynamicsCompressor,
    NodeTypeId::Gain,
    NodeTypeId::WaveShaper,
    NodeTypeId::ChannelMerger,
    NodeTypeId::ChannelSelector,
    NodeTypeId::ChannelSplitter,
    // audio/acoustics.hpp: acoustic surfaces on the direct path
    NodeTypeId::AcousticProperties,
};

}  // namespace

bool nodeImplemented(NodeTypeId id) {
  const NodeModel* m = nodeModel(id);
  if (m == nullptr) return false;
  if (inNodeTable(m->name)) return true;  // VRML97's nodes and the extensions
  return std::find(kImplementedX3d.begin(), kImplementedX3d.end(), id) != kImplementedX3d.end();
}

std::vector<std::string_view> unimplementedNodes(std::string_view component, int level) {
  std::vector<std::string_view> out;
  for (const NodeModel& m : nodeModels())
    if (m.component == component && m.level <= level && !nodeImplemented(m.id))
      out.push_back(m.name);
  return out;
}

bool knownComponent(std::string_view component) {
  for (const NodeModel& m : nodeModels())
    if (m.component == component) return true;
  return false;
}

}  // namespace gs::vrml
