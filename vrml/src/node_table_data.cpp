// The declarative node table: the interfaces of the 54 VRML97 nodes of ISO/IEC 14772-1:1997
// clause 6 ("Node reference"), written as PROTO interface declarations, one per line, in the
// order and with the defaults the standard's node synopses give. Range comments of the
// synopses are left out. builtInNodeType() (node_table.cpp) parses this text once.
#include "vrml/node_table.hpp"

#include <array>

namespace gs::vrml {
namespace {

// The 54 VRML97 nodes come first, in clause 6 (alphabetical) order; GhostSpace's extension
// nodes (extension = true) go after them, at the end of the array.
constexpr std::array kEntries = {
    NodeTableEntry{"Anchor", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField MFNode children []
exposedField SFString description ""
exposedField MFString parameter []
exposedField MFString url []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)"},

    NodeTableEntry{"Appearance", R"(exposedField SFNode material NULL
exposedField SFNode texture NULL
exposedField SFNode textureTransform NULL)"},

    NodeTableEntry{"AudioClip", R"(exposedField SFString description ""
exposedField SFBool loop FALSE
exposedField SFFloat pitch 1.0
exposedField SFTime startTime 0
exposedField SFTime stopTime 0
exposedField MFString url []
eventOut SFTime duration_changed
eventOut SFBool isActive)"},

    NodeTableEntry{"Background", R"(eventIn SFBool set_bind
exposedField MFFloat groundAngle []
exposedField MFColor groundColor []
exposedField MFString backUrl []
exposedField MFString bottomUrl []
exposedField MFString frontUrl []
exposedField MFString leftUrl []
exposedField MFString rightUrl []
exposedField MFString topUrl []
exposedField MFFloat skyAngle []
exposedField MFColor skyColor 0 0 0
eventOut SFBool isBound)"},

    NodeTableEntry{"Billboard", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField SFVec3f axisOfRotation 0 1 0
exposedField MFNode children []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)"},

    NodeTableEntry{"Box", R"(field SFVec3f size 2 2 2)"},

    NodeTableEntry{"Collision", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField MFNode children []
exposedField SFBool collide TRUE
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1
field SFNode proxy NULL
eventOut SFTime collideTime)"},

    NodeTableEntry{"Color", R"(exposedField MFColor color [])"},

    NodeTableEntry{"ColorInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFColor keyValue []
eventOut SFColor value_changed)"},

    NodeTableEntry{"Cone", R"(field SFFloat bottomRadius 1
field SFFloat height 2
field SFBool side TRUE
field SFBool bottom TRUE)"},

    NodeTableEntry{"Coordinate", R"(exposedField MFVec3f point [])"},

    NodeTableEntry{"CoordinateInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFVec3f keyValue []
eventOut MFVec3f value_changed)"},

    NodeTableEntry{"Cylinder", R"(field SFBool bottom TRUE
field SFFloat height 2
field SFFloat radius 1
field SFBool side TRUE
field SFBool top TRUE)"},

    NodeTableEntry{"CylinderSensor", R"(exposedField SFBool autoOffset TRUE
exposedField SFFloat diskAngle 0.262
exposedField SFBool enabled TRUE
exposedField SFFloat maxAngle -1
exposedField SFFloat minAngle 0
exposedField SFFloat offset 0
eventOut SFBool isActive
eventOut SFRotation rotation_changed
eventOut SFVec3f trackPoint_changed)"},

    NodeTableEntry{"DirectionalLight", R"(exposedField SFFloat ambientIntensity 0
exposedField SFColor color 1 1 1
exposedField SFVec3f direction 0 0 -1
exposedField SFFloat intensity 1
exposedField SFBool on TRUE)"},

    NodeTableEntry{"ElevationGrid", R"(eventIn MFFloat set_height
exposedField SFNode color NULL
exposedField SFNode normal NULL
exposedField SFNode texCoord NULL
field MFFloat height []
field SFBool ccw TRUE
field SFBool colorPerVertex TRUE
field SFFloat creaseAngle 0
field SFBool normalPerVertex TRUE
field SFBool solid TRUE
field SFInt32 xDimension 0
field SFFloat xSpacing 1.0
field SFInt32 zDimension 0
field SFFloat zSpacing 1.0)"},

    NodeTableEntry{"Extrusion", R"(eventIn MFVec2f set_crossSection
eventIn MFRotation set_orientation
eventIn MFVec2f set_scale
eventIn MFVec3f set_spine
field SFBool beginCap TRUE
field SFBool ccw TRUE
field SFBool convex TRUE
field SFFloat creaseAngle 0
field MFVec2f crossSection [1 1, 1 -1, -1 -1, -1 1, 1 1]
field SFBool endCap TRUE
field MFRotation orientation 0 0 1 0
field MFVec2f scale 1 1
field SFBool solid TRUE
field MFVec3f spine [0 0 0, 0 1 0])"},

    NodeTableEntry{"Fog", R"(exposedField SFColor color 1 1 1
exposedField SFString fogType "LINEAR"
exposedField SFFloat visibilityRange 0
eventIn SFBool set_bind
eventOut SFBool isBound)"},

    NodeTableEntry{"FontStyle", R"(field MFString family "SERIF"
field SFBool horizontal TRUE
field MFString justify "BEGIN"
field SFString language ""
field SFBool leftToRight TRUE
field SFFloat size 1.0
field SFFloat spacing 1.0
field SFString style "PLAIN"
field SFBool topToBottom TRUE)"},

    NodeTableEntry{"Group", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField MFNode children []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)"},

    NodeTableEntry{"ImageTexture", R"(exposedField MFString url []
field SFBool repeatS TRUE
field SFBool repeatT TRUE)"},

    NodeTableEntry{"IndexedFaceSet", R"(eventIn MFInt32 set_colorIndex
eventIn MFInt32 set_coordIndex
eventIn MFInt32 set_normalIndex
eventIn MFInt32 set_texCoordIndex
exposedField SFNode color NULL
exposedField SFNode coord NULL
exposedField SFNode normal NULL
exposedField SFNode texCoord NULL
field SFBool ccw TRUE
field MFInt32 colorIndex []
field SFBool colorPerVertex TRUE
field SFBool convex TRUE
field MFInt32 coordIndex []
field SFFloat creaseAngle 0
field MFInt32 normalIndex []
field SFBool normalPerVertex TRUE
field SFBool solid TRUE
field MFInt32 texCoordIndex [])"},

    NodeTableEntry{"IndexedLineSet", R"(eventIn MFInt32 set_colorIndex
eventIn MFInt32 set_coordIndex
exposedField SFNode color NULL
exposedField SFNode coord NULL
field MFInt32 colorIndex []
field SFBool colorPerVertex TRUE
field MFInt32 coordIndex [])"},

    NodeTableEntry{"Inline", R"(exposedField MFString url []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)"},

    NodeTableEntry{"LOD", R"(exposedField MFNode level []
field SFVec3f center 0 0 0
field MFFloat range [])"},

    NodeTableEntry{"Material", R"(exposedField SFFloat ambientIntensity 0.2
exposedField SFColor diffuseColor 0.8 0.8 0.8
exposedField SFColor emissiveColor 0 0 0
exposedField SFFloat shininess 0.2
exposedField SFColor specularColor 0 0 0
exposedField SFFloat transparency 0)"},

    NodeTableEntry{"MovieTexture", R"(exposedField SFBool loop FALSE
exposedField SFFloat speed 1.0
exposedField SFTime startTime 0
exposedField SFTime stopTime 0
exposedField MFString url []
field SFBool repeatS TRUE
field SFBool repeatT TRUE
eventOut SFTime duration_changed
eventOut SFBool isActive)"},

    NodeTableEntry{"NavigationInfo", R"(eventIn SFBool set_bind
exposedField MFFloat avatarSize [0.25, 1.6, 0.75]
exposedField SFBool headlight TRUE
exposedField SFFloat speed 1.0
exposedField MFString type ["WALK", "ANY"]
exposedField SFFloat visibilityLimit 0.0
eventOut SFBool isBound)"},

    NodeTableEntry{"Normal", R"(exposedField MFVec3f vector [])"},

    NodeTableEntry{"NormalInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFVec3f keyValue []
eventOut MFVec3f value_changed)"},

    NodeTableEntry{"OrientationInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFRotation keyValue []
eventOut SFRotation value_changed)"},

    NodeTableEntry{"PixelTexture", R"(exposedField SFImage image 0 0 0
field SFBool repeatS TRUE
field SFBool repeatT TRUE)"},

    NodeTableEntry{"PlaneSensor", R"(exposedField SFBool autoOffset TRUE
exposedField SFBool enabled TRUE
exposedField SFVec2f maxPosition -1 -1
exposedField SFVec2f minPosition 0 0
exposedField SFVec3f offset 0 0 0
eventOut SFBool isActive
eventOut SFVec3f trackPoint_changed
eventOut SFVec3f translation_changed)"},

    NodeTableEntry{"PointLight", R"(exposedField SFFloat ambientIntensity 0
exposedField SFVec3f attenuation 1 0 0
exposedField SFColor color 1 1 1
exposedField SFFloat intensity 1
exposedField SFVec3f location 0 0 0
exposedField SFBool on TRUE
exposedField SFFloat radius 100)"},

    NodeTableEntry{"PointSet", R"(exposedField SFNode color NULL
exposedField SFNode coord NULL)"},

    NodeTableEntry{"PositionInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFVec3f keyValue []
eventOut SFVec3f value_changed)"},

    NodeTableEntry{"ProximitySensor", R"(exposedField SFVec3f center 0 0 0
exposedField SFVec3f size 0 0 0
exposedField SFBool enabled TRUE
eventOut SFBool isActive
eventOut SFVec3f position_changed
eventOut SFRotation orientation_changed
eventOut SFTime enterTime
eventOut SFTime exitTime)"},

    NodeTableEntry{"ScalarInterpolator", R"(eventIn SFFloat set_fraction
exposedField MFFloat key []
exposedField MFFloat keyValue []
eventOut SFFloat value_changed)"},

    // The user-defined fields and events of a Script are declared per instance (6.40).
    NodeTableEntry{"Script", R"(exposedField MFString url []
field SFBool directOutput FALSE
field SFBool mustEvaluate FALSE)"},

    NodeTableEntry{"Shape", R"(exposedField SFNode appearance NULL
exposedField SFNode geometry NULL)"},

    NodeTableEntry{"Sound", R"(exposedField SFVec3f direction 0 0 1
exposedField SFFloat intensity 1
exposedField SFVec3f location 0 0 0
exposedField SFFloat maxBack 10
exposedField SFFloat maxFront 10
exposedField SFFloat minBack 1
exposedField SFFloat minFront 1
exposedField SFFloat priority 0
exposedField SFNode source NULL
field SFBool spatialize TRUE)"},

    NodeTableEntry{"Sphere", R"(field SFFloat radius 1)"},

    NodeTableEntry{"SphereSensor", R"(exposedField SFBool autoOffset TRUE
exposedField SFBool enabled TRUE
exposedField SFRotation offset 0 1 0 0
eventOut SFBool isActive
eventOut SFRotation rotation_changed
eventOut SFVec3f trackPoint_changed)"},

    NodeTableEntry{"SpotLight", R"(exposedField SFFloat ambientIntensity 0
exposedField SFVec3f attenuation 1 0 0
exposedField SFFloat beamWidth 1.570796
exposedField SFColor color 1 1 1
exposedField SFFloat cutOffAngle 0.785398
exposedField SFVec3f direction 0 0 -1
exposedField SFFloat intensity 1
exposedField SFVec3f location 0 0 0
exposedField SFBool on TRUE
exposedField SFFloat radius 100)"},

    NodeTableEntry{"Switch", R"(exposedField MFNode choice []
exposedField SFInt32 whichChoice -1)"},

    NodeTableEntry{"Text", R"(exposedField MFString string []
exposedField SFNode fontStyle NULL
exposedField MFFloat length []
exposedField SFFloat maxExtent 0.0)"},

    NodeTableEntry{"TextureCoordinate", R"(exposedField MFVec2f point [])"},

    NodeTableEntry{"TextureTransform", R"(exposedField SFVec2f center 0 0
exposedField SFFloat rotation 0
exposedField SFVec2f scale 1 1
exposedField SFVec2f translation 0 0)"},

    NodeTableEntry{"TimeSensor", R"(exposedField SFTime cycleInterval 1
exposedField SFBool enabled TRUE
exposedField SFBool loop FALSE
exposedField SFTime startTime 0
exposedField SFTime stopTime 0
eventOut SFTime cycleTime
eventOut SFFloat fraction_changed
eventOut SFBool isActive
eventOut SFTime time)"},

    NodeTableEntry{"TouchSensor", R"(exposedField SFBool enabled TRUE
eventOut SFVec3f hitNormal_changed
eventOut SFVec3f hitPoint_changed
eventOut SFVec2f hitTexCoord_changed
eventOut SFBool isActive
eventOut SFBool isOver
eventOut SFTime touchTime)"},

    NodeTableEntry{"Transform", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField SFVec3f center 0 0 0
exposedField MFNode children []
exposedField SFRotation rotation 0 0 1 0
exposedField SFVec3f scale 1 1 1
exposedField SFRotation scaleOrientation 0 0 1 0
exposedField SFVec3f translation 0 0 0
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)"},

    NodeTableEntry{"Viewpoint", R"(eventIn SFBool set_bind
exposedField SFFloat fieldOfView 0.785398
exposedField SFBool jump TRUE
exposedField SFRotation orientation 0 0 1 0
exposedField SFVec3f position 0 0 10
field SFString description ""
eventOut SFTime bindTime
eventOut SFBool isBound)"},

    NodeTableEntry{"VisibilitySensor", R"(exposedField SFVec3f center 0 0 0
exposedField SFBool enabled TRUE
exposedField SFVec3f size 0 0 0
eventOut SFTime enterTime
eventOut SFTime exitTime
eventOut SFBool isActive)"},

    NodeTableEntry{"WorldInfo", R"(field MFString info []
field SFString title "")"},

    // GhostSpace extensions (docs/vrml-extensions.md).
    NodeTableEntry{"OutlineGroup", R"(eventIn MFNode addChildren
eventIn MFNode removeChildren
exposedField MFNode children []
exposedField SFNode appearance NULL
field SFInt32 groupId -1
field MFVec3f outline []
field MFInt32 outlineLengths []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)",
                   true},

    NodeTableEntry{"QuantizedNormalVectors", R"(exposedField MFString url []
exposedField SFFloat fraction 1
exposedField SFInt32 count -1
exposedField SFFloat opacityScale 1
exposedField SFString mode ""
field MFVec3f position []
field MFVec3f direction []
field MFFloat magnitude []
field MFColor color []
field SFVec3f bboxCenter 0 0 0
field SFVec3f bboxSize -1 -1 -1)",
                   true},

    NodeTableEntry{"Skin", R"(exposedField MFNode skeleton []
exposedField MFNode joints []
field MFFloat inverseBindMatrices []
exposedField SFNode skinnedTransform NULL
exposedField SFNode coord NULL
exposedField SFNode normal NULL
exposedField MFVec3f restPoint []
exposedField MFVec3f restNormal []
field MFInt32 vertexJoints []
field MFFloat vertexWeights [])",
                   true},
};

constexpr std::size_t countVrml97Entries() {
  std::size_t n = 0;
  while (n < kEntries.size() && !kEntries[n].extension) ++n;
  return n;
}

constexpr std::size_t kVrml97Count = countVrml97Entries();
static_assert(kVrml97Count == 54, "ISO/IEC 14772-1:1997 clause 6 defines 54 nodes");

}  // namespace

std::span<const NodeTableEntry> nodeTableEntries() {
  return kEntries;
}

std::size_t vrml97NodeTypeCount() {
  return kVrml97Count;
}

bool inNodeTable(std::string_view name) {
  for (const NodeTableEntry& e : kEntries)
    if (e.name == name) return true;
  return false;
}

}  // namespace gs::vrml
