// The float layer of the GL splat paths (see splat_layer_gl.hpp).
#include "splat_layer_gl.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "gl_program.hpp"

namespace gs::render::detail {

namespace {

const char* const kLayerVertexShader = R"glsl(#version 330 core
void main() {
  vec2 p = vec2((gl_VertexID & 1) == 0 ? -1.0 : 1.0, (gl_VertexID & 2) == 0 ? -1.0 : 1.0);
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

// Texel (x, y) of the layer is the pixel u_origin + (x, y) of the framebuffer.
const char* const kLayerFragmentShader = R"glsl(#version 330 core
uniform sampler2D u_layer;
uniform ivec2 u_origin;
out vec4 o_color;
void main() { o_color = texelFetch(u_layer, ivec2(gl_FragCoord.xy) - u_origin, 0); }
)glsl";

}  // namespace

GLenum splatLayerFormat() {
  static const GLenum format = [] {
    const char* name = std::getenv("GHOSTSPACE_SPLAT_LAYER");
    if (name == nullptr || std::strcmp(name, "float16") == 0)
      return static_cast<GLenum>(GL_RGBA16F);
    if (std::strcmp(name, "off") == 0) return static_cast<GLenum>(GL_NONE);
    if (std::strcmp(name, "float32") == 0) return static_cast<GLenum>(GL_RGBA32F);
    std::fprintf(stderr,
                 "GHOSTSPACE_SPLAT_LAYER: expected off, float16 or float32, got \"%s\"; "
                 "float16 used\n",
                 name);
    return static_cast<GLenum>(GL_RGBA16F);
  }();
  return format;
}

GLuint buildLayerProgram() {
  return buildProgram("splat layer", kLayerVertexShader, kLayerFragmentShader);
}

bool FloatSplatLayer::begin(const int viewport[4]) {
  const int width = viewport[2], height = viewport[3];
  const GLenum format = splatLayerFormat();
  if (width <= 0 || height <= 0 || format == GL_NONE || refused_) return false;
  while (glGetError() != GL_NO_ERROR) {
  }
  if (framebuffer_ == 0) {
    glGenFramebuffers(1, &framebuffer_);
    glGenTextures(1, &color_);
    glGenRenderbuffers(1, &depth_);
  }
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawFramebuffer_);
  glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &readFramebuffer_);
  if (width > width_ || height > height_) {
    // Grown to the largest viewport seen, never shrunk: viewports of several sizes side by
    // side use its lower left corner each.
    const int w = std::max(width, width_), h = std::max(height, height_);
    glBindTexture(GL_TEXTURE_2D, color_);
    glTexImage2D(GL_TEXTURE_2D, 0, static_cast<GLint>(format), w, h, 0, GL_RGBA, GL_FLOAT, nullptr);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);
    glBindRenderbuffer(GL_RENDERBUFFER, depth_);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH24_STENCIL8, w, h);
    glBindRenderbuffer(GL_RENDERBUFFER, 0);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture2D(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, color_, 0);
    glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_DEPTH_STENCIL_ATTACHMENT, GL_RENDERBUFFER,
                              depth_);
    const bool complete = glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
    if (!complete || glGetError() != GL_NO_ERROR) {
      // Not tried again each frame: the splats blend into the framebuffer from now on.
      width_ = height_ = 0;
      refused_ = true;
      std::fprintf(stderr,
                   "the splat layer (%d x %d pixels, float) could not be made: splats blend "
                   "straight into the framebuffer, 8 bits a channel\n",
                   w, h);
      return false;
    }
    width_ = w;
    height_ = h;
  }
  scissored_ = glIsEnabled(GL_SCISSOR_TEST);
  glDisable(GL_SCISSOR_TEST);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, framebuffer_);
  // Only the viewport's corner of the layer is cleared and drawn.
  glEnable(GL_SCISSOR_TEST);
  GLint box[4];
  glGetIntegerv(GL_SCISSOR_BOX, box);
  glScissor(0, 0, width, height);
  const GLfloat transparent[4] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearBufferfv(GL_COLOR, 0, transparent);
  glClearBufferfi(GL_DEPTH_STENCIL, 0, 1.0f, 0);
  glScissor(box[0], box[1], box[2], box[3]);
  glDisable(GL_SCISSOR_TEST);
  glBlitFramebuffer(viewport[0], viewport[1], viewport[0] + width, viewport[1] + height, 0, 0,
                    width, height, GL_DEPTH_BUFFER_BIT, GL_NEAREST);
  if (glGetError() != GL_NO_ERROR) {
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer_));
    if (scissored_) glEnable(GL_SCISSOR_TEST);
    return false;
  }
  for (int i = 0; i < 4; ++i) viewport_[i] = viewport[i];
  glViewport(0, 0, width, height);
  return true;
}

void FloatSplatLayer::end() {
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, static_cast<GLuint>(drawFramebuffer_));
  glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(readFramebuffer_));
  glViewport(viewport_[0], viewport_[1], viewport_[2], viewport_[3]);
  if (scissored_) glEnable(GL_SCISSOR_TEST);
  if (program_ == 0) {
    program_ = buildLayerProgram();
    glGenVertexArrays(1, &vao_);
  }
  glUseProgram(program_);
  glActiveTexture(GL_TEXTURE0);
  glBindTexture(GL_TEXTURE_2D, color_);
  glUniform1i(uniform(program_, "u_layer"), 0);
  glUniform2i(uniform(program_, "u_origin"), viewport_[0], viewport_[1]);
  glEnable(GL_BLEND);
  glBlendFunc(GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glEnable(GL_DEPTH_TEST);
  glUseProgram(0);
}

void FloatSplatLayer::release() {
  if (framebuffer_ != 0) {
    glDeleteFramebuffers(1, &framebuffer_);
    glDeleteTextures(1, &color_);
    glDeleteRenderbuffers(1, &depth_);
  }
  if (program_ != 0) {
    glDeleteProgram(program_);
    glDeleteVertexArrays(1, &vao_);
  }
  framebuffer_ = color_ = depth_ = program_ = vao_ = 0;
  width_ = height_ = 0;
  refused_ = false;
}

}  // namespace gs::render::detail
