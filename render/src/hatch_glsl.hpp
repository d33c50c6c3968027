// Private to render/: X3D FillProperties' hatches (clause 12.4.3, line_fill_properties.hpp)
// in the surface programs: the GLSL both the Phong program (shaders.cpp) and the physical
// one (shaders_physical.cpp) share.
#pragma once

/// The shared GLSL: `bool hatchOn(vec2 pixel)`, whether window pixel `pixel`
/// (gl_FragCoord.xy) lies on a hatch line of style HATCH_STYLE (1 horizontal, 2 vertical,
/// 3 positive slope, 4 negative slope, 5 cross, 6 diagonal cross; X_ITE 15's styles), the
/// lines one pixel wide every 8 pixels of the window. Needs HATCH_STYLE defined before it.
#define GS_HATCH_GLSL                                        \
  "bool hatchOn(vec2 pixel) {\n"                             \
  "  bool horizontal = mod(pixel.y, 8.0) < 1.0;\n"           \
  "  bool vertical = mod(pixel.x, 8.0) < 1.0;\n"             \
  "  bool positive = mod(pixel.x - pixel.y, 8.0) < 1.0;\n"   \
  "  bool negative = mod(pixel.x + pixel.y, 8.0) < 1.0;\n"   \
  "  if (HATCH_STYLE == 1) return horizontal;\n"             \
  "  if (HATCH_STYLE == 2) return vertical;\n"               \
  "  if (HATCH_STYLE == 3) return positive;\n"               \
  "  if (HATCH_STYLE == 4) return negative;\n"               \
  "  if (HATCH_STYLE == 5) return horizontal || vertical;\n" \
  "  return positive || negative;\n"                         \
  "}\n"
