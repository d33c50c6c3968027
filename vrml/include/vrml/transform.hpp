// The coordinate systems of grouping nodes as matrices (clause 4.4.5 "Standard units and
// coordinate system", 6.52 Transform). Units: metres and radians; glm's column-major
// matrices, local to parent.
#pragma once

#include "vrml/field.hpp"
#include "vrml/node.hpp"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gs::vrml {

/// A rotation matrix from an SFRotation (axis x, y, z, any length, and angle in radians);
/// identity for a zero axis or angle.
glm::mat4 rotationMatrix(const Rotation& rotation);

/// The SFRotation of quaternion `q` (any length; normalised first): a unit axis and an
/// angle in [0, pi] radians; 0 0 1 0 for no rotation (or a zero or non-finite `q`).
Rotation rotationFromQuaternion(glm::dquat q);

/// The matrix of a Transform node (6.52): T x C x R x SR x S x -SR x -C, from its
/// translation, center, rotation, scale and scaleOrientation fields (defaults for
/// fields it lacks). X3D's GeoLocation (clause 25.4.5): its location frame at geoCoords
/// (vrml/geo_nodes.hpp); GeoTransform (25.4.12): L x T x R x SR x S x -SR x L^-1, L the
/// location frame at geoCenter (as X_ITE).
glm::mat4 transformMatrix(const Node& transform);

/// True for the node types whose children are placed by transformMatrix: Transform
/// (6.52), X3D's CADPart (X3D 4.0 clause 32.4.4, the same five transform fields),
/// GeoLocation and GeoTransform (clause 25),
/// HAnimJoint and HAnimSite (26.3.2, 26.3.4), and HAnimSegment with castle-engine's
/// translation, rotation and scale (an X3D world's HAnimSegment has them; defaults
/// otherwise).
constexpr bool placesChildren(NodeTypeId id) {
  return id == NodeTypeId::Transform || id == NodeTypeId::CADPart || id == NodeTypeId::HAnimJoint ||
         id == NodeTypeId::HAnimSegment || id == NodeTypeId::HAnimSite ||
         id == NodeTypeId::GeoLocation || id == NodeTypeId::GeoTransform;
}

}  // namespace gs::vrml
