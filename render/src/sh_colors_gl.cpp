// The GPU's evaluation of a cloud's spherical harmonics (see sh_colors_gl.hpp).
#include "sh_colors_gl.hpp"

#include <algorithm>
#include <string>

#include "gl_program.hpp"
#include "gpu_sort.hpp"

namespace gs::render::detail {

namespace {

constexpr GLuint kShGroup = 256;  // threads per workgroup (the shader's local_size_x)

// splats::shBasis and shColor, term by term in the same order.
const char* const kShShader = R"glsl(#version 430 core
layout(local_size_x = 256) in;
uniform samplerBuffer u_splats;
uniform vec3 u_eye;
uniform uint u_count;
uniform int u_degree;
uniform uint u_stride;  // floats per splat: 3 (degree + 1)^2
uniform bool u_linear;
layout(std430, binding = 0) readonly buffer Coefficients { float sh[]; };
layout(std430, binding = 1) writeonly buffer Colors { uint colors[]; };
vec3 coefficient(uint base, uint k) {
  uint at = base + 3u * k;
  return vec3(sh[at], sh[at + 1u], sh[at + 2u]);
}
float toSrgb(float c) {
  if (!(c > 0.0)) return 0.0;
  return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}
void main() {
  uint i = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * 256u +
           gl_LocalInvocationID.x;
  if (i >= u_count) return;
  vec3 toward = texelFetch(u_splats, int(3u * i)).xyz - u_eye;
  float len = length(toward);
  vec3 d = len > 0.0 ? toward / len : vec3(0.0, 0.0, -1.0);
  uint b = i * u_stride;
  vec3 c = 0.28209479177387814 * coefficient(b, 0u);
  if (u_degree >= 1) {
    float x = d.x, y = d.y, z = d.z;
    c += (-0.4886025119029199 * y) * coefficient(b, 1u);
    c += (0.4886025119029199 * z) * coefficient(b, 2u);
    c += (-0.4886025119029199 * x) * coefficient(b, 3u);
    if (u_degree >= 2) {
      float xx = x * x, yy = y * y, zz = z * z, xy = x * y, yz = y * z, xz = x * z;
      c += (1.0925484305920792 * xy) * coefficient(b, 4u);
      c += (-1.0925484305920792 * yz) * coefficient(b, 5u);
      c += (0.31539156525252005 * (2.0 * zz - xx - yy)) * coefficient(b, 6u);
      c += (-1.0925484305920792 * xz) * coefficient(b, 7u);
      c += (0.5462742152960396 * (xx - yy)) * coefficient(b, 8u);
      if (u_degree >= 3) {
        c += (-0.5900435899266435 * y * (3.0 * xx - yy)) * coefficient(b, 9u);
        c += (2.890611442640554 * xy * z) * coefficient(b, 10u);
        c += (-0.4570457994644658 * y * (4.0 * zz - xx - yy)) * coefficient(b, 11u);
        c += (0.3731763325901154 * z * (2.0 * zz - 3.0 * xx - 3.0 * yy)) * coefficient(b, 12u);
        c += (-0.4570457994644658 * x * (4.0 * zz - xx - yy)) * coefficient(b, 13u);
        c += (1.445305721320277 * z * (xx - yy)) * coefficient(b, 14u);
        c += (-0.5900435899266435 * x * (xx - 3.0 * yy)) * coefficient(b, 15u);
      }
    }
  }
  c = max(c + 0.5, vec3(0.0));
  if (u_linear) c = vec3(toSrgb(c.r), toSrgb(c.g), toSrgb(c.b));
  colors[i] = packUnorm4x8(vec4(clamp(c, 0.0, 1.0), 1.0));
}
)glsl";

}  // namespace

void GpuShColors::upload(const splats::GaussianCloud& cloud) {
  if (program_ == 0) {
    program_ = buildComputeProgram("spherical harmonics colours", kShShader);
    glGenBuffers(1, &coefficients_);
  }
  const std::size_t n = cloud.size();
  const int rest = cloud.shRestPerSplat();
  const std::size_t stride = 3 * static_cast<std::size_t>(rest + 1);
  staging_.resize(n * stride);
  for (std::size_t i = 0; i < n; ++i) {
    float* out = &staging_[i * stride];
    for (int c = 0; c < 3; ++c) out[c] = cloud.shDc[i][c];
    for (int k = 0; k < rest; ++k)
      for (int c = 0; c < 3; ++c)
        out[3 * (k + 1) + c] =
            cloud.shRest[i * static_cast<std::size_t>(rest) + static_cast<std::size_t>(k)][c];
  }
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, coefficients_);
  glBufferData(GL_SHADER_STORAGE_BUFFER,
               static_cast<GLsizeiptr>(std::max<std::size_t>(staging_.size(), 1) * sizeof(float)),
               staging_.empty() ? nullptr : staging_.data(), GL_STATIC_DRAW);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, 0);
  staging_ = {};
  size_ = n;
  degree_ = cloud.shDegree;
  linear_ = cloud.colorSpace == splats::ColorSpace::linear;
}

void GpuShColors::evaluate(GLuint splatTexture, GLuint colorBuffer, std::size_t count,
                           const glm::vec3& eye) {
  count = std::min(count, size_);
  if (program_ == 0 || count == 0) return;
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_BUFFER, splatTexture);
  glUniform1i(uniform(program_, "u_splats"), 0);
  glUniform3f(uniform(program_, "u_eye"), eye.x, eye.y, eye.z);
  glUniform1ui(uniform(program_, "u_count"), static_cast<GLuint>(count));
  glUniform1i(uniform(program_, "u_degree"), degree_);
  glUniform1ui(uniform(program_, "u_stride"),
               static_cast<GLuint>(3 * splats::shCoefficients(degree_)));
  glUniform1i(uniform(program_, "u_linear"), linear_ ? 1 : 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, coefficients_);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, colorBuffer);
  dispatch(static_cast<GLuint>((count + kShGroup - 1) / kShGroup));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, 0);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, 0);
  glUseProgram(0);
  glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void GpuShColors::release() {
  if (program_ == 0) return;
  glDeleteProgram(program_);
  glDeleteBuffers(1, &coefficients_);
  program_ = coefficients_ = 0;
  size_ = 0;
}

}  // namespace gs::render::detail
