// The Background pass: sky and ground colour gradients (clause 6.5) as a full-screen
// triangle, or a plain clear for a single sky colour.
#include "gl_program.hpp"
#include "gpu_resources.hpp"

#include <algorithm>

namespace gs::render::detail {

void BackgroundPass::draw(const BackgroundSettings& background, const glm::mat4& view,
                          const glm::mat4& projection) {
  const int skyCount =
      std::min<int>(static_cast<int>(background.skyColor.size()), kMaxBackgroundColors);
  const int skyAngles = std::min<int>(static_cast<int>(background.skyAngle.size()), skyCount - 1);
  const int groundCount =
      std::min<int>(static_cast<int>(background.groundColor.size()), kMaxBackgroundColors);
  const int groundAngles =
      std::min<int>(static_cast<int>(background.groundAngle.size()), groundCount - 1);
  const glm::vec3 zenith = skyCount > 0 ? background.skyColor[0] : glm::vec3(0.0f);
  // Clear to the zenith colour; that is the whole background for a single sky colour.
  glClearColor(zenith.r, zenith.g, zenith.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  if (skyAngles <= 0 && groundAngles <= 0) return;

  if (program_ == 0) {
    program_ = buildProgram("Background", kBackgroundVertexShader, kBackgroundFragmentShader);
    glGenVertexArrays(1, &vao_);
    locInverse_ = uniform(program_, "u_inverseViewProjection");
    locWorldToBackground_ = uniform(program_, "u_worldToBackground");
    locSkyCount_ = uniform(program_, "u_skyCount");
    locSkyColor_ = uniform(program_, "u_skyColor");
    locSkyAngle_ = uniform(program_, "u_skyAngle");
    locGroundCount_ = uniform(program_, "u_groundCount");
    locGroundColor_ = uniform(program_, "u_groundColor");
    locGroundAngle_ = uniform(program_, "u_groundAngle");
  }
  const glm::mat4 rotationOnly = glm::mat4(glm::mat3(view));
  const glm::mat4 inverse = glm::inverse(projection * rotationOnly);
  const glm::mat3 worldToBackground = glm::transpose(background.rotation);
  glUseProgram(program_);
  glUniformMatrix4fv(locInverse_, 1, GL_FALSE, &inverse[0][0]);
  glUniformMatrix3fv(locWorldToBackground_, 1, GL_FALSE, &worldToBackground[0][0]);
  // Counts passed are "angles + 1" so colours without an angle are ignored.
  glUniform1i(locSkyCount_, skyAngles + 1);
  glUniform3fv(locSkyColor_, skyAngles + 1, &background.skyColor[0].x);
  if (skyAngles > 0) glUniform1fv(locSkyAngle_, skyAngles, background.skyAngle.data());
  glUniform1i(locGroundCount_, groundAngles > 0 ? groundAngles + 1 : 0);
  if (groundAngles > 0) {
    glUniform3fv(locGroundColor_, groundAngles + 1, &background.groundColor[0].x);
    glUniform1fv(locGroundAngle_, groundAngles, background.groundAngle.data());
  }
  GLboolean depthTest = glIsEnabled(GL_DEPTH_TEST);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  glDepthMask(GL_TRUE);
  if (depthTest) glEnable(GL_DEPTH_TEST);
}

void BackgroundPass::release() {
  if (program_ != 0) glDeleteProgram(program_);
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  program_ = vao_ = 0;
}

}  // namespace gs::render::detail
