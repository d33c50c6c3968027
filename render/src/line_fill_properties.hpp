// Private to render/: X3D's LineProperties, FillProperties and PointProperties (ISO/IEC
// 19775-1 X3D 4.0 clauses 12.4.6, 12.4.3 and 12.4.9, the Shape component), read from an
// Appearance for the surface program, which draws line patterns and hatching in its
// fragment shader (shaders.cpp: linePatternOn, hatchOn) and sizes points in its vertex
// shader.
#pragma once

#include "geometry/geometry.hpp"
#include "vrml/node.hpp"

#include <glm/vec3.hpp>

#include <string>

namespace gs::render::detail {

struct SurfaceUniforms;
struct SurfaceVariant;

/// The line and fill styles of one Appearance; the defaults draw as VRML97 does.
struct LineFillStyle {
  /// LineProperties.linetype when applied: 1 solid, 2 dashed, 3 dotted, 4 dash-dot,
  /// 5 dash-dot-dot (ISO/IEC 9973's first five); other values draw solid (the clause's
  /// rule for unsupported types).
  int lineType = 1;
  /// Line width in pixels: the nominal width 1 times linewidthScaleFactor when that is
  /// above 0 and LineProperties is applied, else 1. At most 64.
  float lineWidth = 1.0f;
  /// FillProperties.filled: FALSE leaves polygons' insides undrawn but for the hatches.
  bool filled = true;
  /// The hatch pattern drawn over polygons (FillProperties.hatched): 0 none, 1 horizontal,
  /// 2 vertical, 3 positive slope, 4 negative slope, 5 horizontal/vertical cross-hatch,
  /// 6 diagonal cross-hatch (ISO/IEC 9973's first six; styles 7-19 draw as 6).
  int hatchStyle = 0;
  glm::vec3 hatchColor{1.0f};  // FillProperties.hatchColor, components in [0, 1]
  /// PointProperties: a point's size in pixels is the nominal size (the renderer's
  /// pointSize option) times pointScale / (a[0] + a[1] r + a[2] r^2), r its distance from
  /// the viewer in metres, clamped to [pointMin, pointMax] times the nominal size. The
  /// defaults keep the nominal size.
  float pointScale = 1.0f, pointMin = 1.0f, pointMax = 1.0f;
  glm::vec3 pointAttenuation{1.0f, 0.0f, 0.0f};
  /// A value drawn as another one (for a warning at the node), else empty.
  std::string problem;
  const vrml::Node* problemNode = nullptr;

  /// Whether a polygon with this style shows nothing at all (filled and hatched FALSE).
  bool invisible() const { return !filled && hatchStyle == 0; }
  /// Fixes the line type (lines only), hatch style and filling (polygons only) in `v`.
  void specialize(SurfaceVariant& v, vrml::Primitive primitive) const;
  /// Sets the program's line, point and fill uniforms for a mesh of `primitive`, and for
  /// lines the GL line width (which the caller puts back to 1 after drawing).
  void setUniforms(const SurfaceUniforms& u, vrml::Primitive primitive) const;
};

/// Reads `appearance`'s lineProperties and fillProperties fields (either may be absent,
/// NULL or of another type: the defaults then).
LineFillStyle readLineFillStyle(const vrml::Node& appearance);

/// Pixels between hatch lines, and the period of the line patterns' dashes at width 1.
inline constexpr float kHatchSpacing = 8.0f;

}  // namespace gs::render::detail
