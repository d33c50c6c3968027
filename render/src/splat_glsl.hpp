// Private to render/: the GLSL shared by the two splat paths' vertex shaders (the
// geometry path of splat_renderer.cpp and the point-sprite path of splat_points.cpp): the
// vertex attributes, the model's uniforms, and the splat model of splat_model.hpp
// (paper section 3.1: spread and peak of the Gaussian opacity profile) with its two-sided
// flat lighting, so both paths draw the same splats from one definition.
#pragma once

#include <string>

namespace gs::render::detail {

/// "#version 330 core", the shared attributes, uniforms and functions (splatRgba,
/// splatProfile, splatLit), then `body` (the path's own declarations and main()).
std::string splatVertexShader(const char* body);

}  // namespace gs::render::detail
