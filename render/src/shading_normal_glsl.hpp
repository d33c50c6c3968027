// Private to render/: the browser option Shading FLAT (browser_options.hpp) in the surface
// programs: the GLSL both the Phong program (shaders.cpp) and the physical one
// (shaders_physical.cpp) share.
#pragma once

/// The shared GLSL: `uniform bool u_flatShading` and `vec3 shadingNormal()`, the normal of the
/// side seen, eye coordinates, unit length: the interpolated v_normal (negated on back faces:
/// two-sided lighting), or with Shading FLAT the triangle's own, the cross product of the
/// screen derivatives of v_position (it faces the viewer on either side). Needs the inputs
/// v_position and v_normal (eye coordinates) declared before it.
#define GS_SHADING_NORMAL_GLSL                                                          \
  "uniform bool u_flatShading;  // the browser option Shading FLAT\n"                   \
  "vec3 shadingNormal() {\n"                                                            \
  "  if (u_flatShading) return normalize(cross(dFdx(v_position), dFdy(v_position)));\n" \
  "  vec3 n = normalize(v_normal);\n"                                                   \
  "  return gl_FrontFacing ? n : -n;\n"                                                 \
  "}\n"
