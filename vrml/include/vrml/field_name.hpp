// Field names known at compile time: a name the traversal, the renderer or the runtime reads
// often (`node.field("children")`) is a FieldKey, and a NodeType answers its index from a
// per-type table filled on first use, so reading a field by such a name costs one load
// instead of a scan of the type's interface with string compares (owners issue: "field
// access in hot paths is by index"). Any other name still works: it is looked up by name.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace gs::vrml {

// The listed names: field, exposedField and event names of the VRML97 and X3D node types
// (ISO/IEC 14772-1 clause 6, ISO/IEC 19775-1) that modules read by name. Adding one costs
// two bytes per node type.
// clang-format off
#define GS_FIELD_KEYS(X) \
    X(addChildren) X(alphaCutoff) X(alphaMode) X(ambientIntensity) X(angle) X(appearance) \
    X(attenuation) X(autoOffset) X(avatarSize) X(axisOfRotation) X(backUrl) X(baseColor) \
    X(baseTexture) X(beamWidth) X(beginCap) X(bindTime) X(bottom) X(bottomRadius) X(bottomUrl) \
    X(boundaryModeS) X(boundaryModeT) X(ccw) X(center) X(children) X(closureType) X(collideTime) \
    X(color) X(colorIndex) X(colorPerVertex) X(convex) X(coord) X(coordIndex) X(count) \
    X(creaseAngle) X(crossSection) X(cutOffAngle) X(cycleInterval) X(cycleTime) X(description) \
    X(diffuseColor) X(directOutput) X(direction) X(diskAngle) X(duration_changed) \
    X(emissiveColor) X(emissiveTexture) X(enabled) X(endAngle) X(endCap) X(enterTime) \
    X(exitTime) X(family) X(fanCount) X(fieldOfView) X(fogType) X(fontStyle) X(fraction) \
    X(fraction_changed) X(frontUrl) X(geometry) X(global) X(groundAngle) X(groundColor) \
    X(groupId) X(headlight) X(height) X(hitNormal_changed) X(hitPoint_changed) \
    X(hitTexCoord_changed) X(horizontal) X(image) X(index) X(innerRadius) X(inputFalse) \
    X(inputNegate) X(inputTrue) X(integerKey) X(intensity) X(inverseBindMatrices) X(isActive) \
    X(isBound) X(isOver) X(joints) X(justify) X(key) X(keyValue) X(language) X(leftToRight) \
    X(leftUrl) X(length) X(lineSegments) X(location) X(loop) X(magnificationFilter) X(magnitude) \
    X(material) X(maxAngle) X(maxExtent) X(maxPosition) X(metallic) X(metallicRoughnessTexture) \
    X(minAngle) X(minPosition) X(minificationFilter) X(mode) X(mustEvaluate) X(next) X(normal) \
    X(normalIndex) X(normalPerVertex) X(normalScale) X(normalTexture) X(occlusionStrength) \
    X(occlusionTexture) X(offset) X(on) X(opacityScale) X(orientation) X(orientation_changed) \
    X(outerRadius) X(outline) X(outlineLengths) X(parameter) X(pitch) X(point) X(pointerEvents) \
    X(position) X(position_changed) X(previous) X(proxy) X(radius) X(range) X(removeChildren) X(repeatS) \
    X(repeatT) X(restNormal) X(restPoint) X(rightUrl) X(rotation) X(rotation_changed) \
    X(roughness) X(scale) X(scaleOrientation) X(set_bind) X(set_boolean) X(set_fraction) \
    X(set_triggerTime) X(shininess) X(side) X(size) X(skeleton) X(skinnedTransform) X(skyAngle) \
    X(skyColor) X(solid) X(spacing) X(specularColor) X(speed) X(spine) X(startAngle) \
    X(startTime) X(stopTime) X(string) X(stripCount) X(style) X(surface) X(texCoord) \
    X(texCoordIndex) X(texture) X(textureProperties) X(textureTransform) X(time) X(toggle) \
    X(top) X(topToBottom) X(topUrl) X(touchTime) X(trackPoint_changed) X(translation) \
    X(translation_changed) X(transparency) X(triggerTime) X(triggerTrue) X(triggerValue) X(type) \
    X(url) X(value_changed) X(vector) X(vertexCount) X(vertexJoints) X(vertexWeights) \
    X(vertices) X(visibilityLimit) X(visibilityRange) X(visible) X(whichChoice) X(xDimension) \
    X(xSpacing) \
    X(zDimension) X(zSpacing)
// clang-format on

/// One of the listed field names, or `none` for any other.
enum class FieldKey : std::uint16_t {
#define GS_FIELD_KEY(n) n,
  GS_FIELD_KEYS(GS_FIELD_KEY)
#undef GS_FIELD_KEY
      none
};

/// How many names are listed (FieldKey::none's value).
inline constexpr std::size_t kFieldKeyCount = static_cast<std::size_t>(FieldKey::none);

/// The listed names, indexed by FieldKey.
inline constexpr std::string_view kFieldKeyNames[kFieldKeyCount] = {
#define GS_FIELD_KEY(n) #n,
    GS_FIELD_KEYS(GS_FIELD_KEY)
#undef GS_FIELD_KEY
};

/// The key of `name` (exact, case-sensitive), FieldKey::none when it is not listed.
constexpr FieldKey fieldKeyOf(std::string_view name) {
  for (std::size_t i = 0; i < kFieldKeyCount; ++i)
    if (kFieldKeyNames[i] == name) return static_cast<FieldKey>(i);
  return FieldKey::none;
}

/// A field name as the node accessors take it. A string literal is resolved to its
/// FieldKey at compile time (consteval); a runtime string (a Script's or a ROUTE's field
/// name) keeps FieldKey::none and is looked up by name.
class FieldName {
 public:
  template <std::size_t N>
  consteval FieldName(const char (&literal)[N])  // NOLINT: implicit on purpose
      : name_(literal, N - 1), key_(fieldKeyOf(name_)) {}
  constexpr FieldName(std::string_view name) : name_(name) {}  // NOLINT: implicit
  FieldName(const std::string& name) : name_(name) {}          // NOLINT: implicit
  /// A name with its key found at run time: `key` must be fieldKeyOf(name) (tables of
  /// names built at start-up, tests).
  constexpr FieldName(std::string_view name, FieldKey key) : name_(name), key_(key) {}

  constexpr std::string_view name() const { return name_; }
  constexpr FieldKey key() const { return key_; }

 private:
  std::string_view name_;
  FieldKey key_ = FieldKey::none;
};

}  // namespace gs::vrml
