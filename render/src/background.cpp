// The Background pass (clause 6.5): sky and ground colour gradients as a full-screen
// triangle (or a plain clear for a single sky colour), then the panorama cube, whose faces
// are image files (Background) or texture nodes (X3D's TextureBackground).
#include "gl_program.hpp"
#include "gpu_resources.hpp"
#include "scene/node_access.hpp"

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>

namespace gs::render::detail {
namespace {

/// One face of the panorama cube in the Background's coordinate system: the centre of
/// the face of the cube [-1, 1]^3 and the directions of the image's +s (right) and +t
/// (up) as a viewer inside sees it. Clause 6.5: front, back, left and right are seen
/// upright with +Y up; the top looking up +Y with +Z up; the bottom looking down -Y with
/// -Z up (castle-model-viewer agrees: docs/background-and-images.md).
struct Face {
  vrml::FieldName field;    // Background's MFString
  vrml::FieldName texture;  // TextureBackground's SFNode (X3D 4.0 clause 24.4.3)
  glm::vec3 center, right, up;
};

constexpr Face kFaceTable[BackgroundPass::kFaces] = {
    {"backUrl", "backTexture", {0, 0, 1}, {-1, 0, 0}, {0, 1, 0}},
    {"bottomUrl", "bottomTexture", {0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
    {"frontUrl", "frontTexture", {0, 0, -1}, {1, 0, 0}, {0, 1, 0}},
    {"leftUrl", "leftTexture", {-1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
    {"rightUrl", "rightTexture", {1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
    {"topUrl", "topTexture", {0, 1, 0}, {1, 0, 0}, {0, 0, 1}},
};

}  // namespace

void BackgroundPass::draw(const scene::BackgroundSettings& background, const glm::mat4& view,
                          const glm::mat4& projection, scene::SceneTraversal& traversal,
                          base::Fetcher* fetcher, TextureCache& textures) {
  const glm::mat4 rotationOnly = glm::mat4(glm::mat3(view));
  GLboolean depthTest = glIsEnabled(GL_DEPTH_TEST);
  glDisable(GL_DEPTH_TEST);
  glDepthMask(GL_FALSE);
  glDisable(GL_CULL_FACE);
  drawGradient(background, rotationOnly, projection);
  if (background.node != nullptr)
    drawPanorama(background, rotationOnly, projection, traversal, fetcher, textures);
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  if (depthTest) glEnable(GL_DEPTH_TEST);
}

void BackgroundPass::drawGradient(const scene::BackgroundSettings& background,
                                  const glm::mat4& rotationOnly, const glm::mat4& projection) {
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
  glDisable(GL_BLEND);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
}

void BackgroundPass::drawPanorama(const scene::BackgroundSettings& background,
                                  const glm::mat4& rotationOnly, const glm::mat4& projection,
                                  scene::SceneTraversal& traversal, base::Fetcher* fetcher,
                                  TextureCache& textures) {
  const vrml::Node& node = *background.node;
  const std::uint64_t revision = vrml::revisionWithFields(node);
  if (&node != facesNode_ || revision != facesRevision_) {
    releaseFaces();
    facesNode_ = &node;
    facesRevision_ = revision;
  }
  bool any = false;
  faceIds_ = {};
  for (int f = 0; f < kFaces; ++f) {
    const auto i = static_cast<std::size_t>(f);
    // A TextureBackground: its texture nodes, from the shapes' texture cache.
    if (const vrml::FieldValue* t = node.field(kFaceTable[i].texture);
        t != nullptr && t->type() == vrml::FieldType::SFNode) {
      const vrml::NodePtr& texture = t->get<vrml::FieldType::SFNode>();
      if (texture && !texture->unresolved) {
        const GpuTexture& gpu = textures.get(*texture, background.baseUrl, traversal, fetcher);
        if (gpu.components > 0 && !gpu.volume && !gpu.cube) faceIds_[i] = gpu.id;
      }
      any = any || faceIds_[i] != 0;
      continue;
    }
    if (!faceDone_[i]) {
      const std::vector<std::string>& urls = scene::mfString(node, kFaceTable[i].field);
      if (urls.empty()) {
        faceDone_[i] = true;
        continue;
      }
      LoadedImage loaded = loadFirstImage(urls, node.urlBaseOr(background.baseUrl), fetcher);
      if (loaded.pending) continue;  // the colours show until it arrives
      faceDone_[i] = true;
      if (loaded.components > 0)
        faces_[i] = uploadImage(loaded, false, false);
      else
        traversal.report(vrml::Severity::warning, node.location,
                         "cannot load Background " + std::string(kFaceTable[i].field.name()) +
                             " (" + loaded.failures + "): the colours show there");
    }
    faceIds_[i] = faces_[i].id;
    any = any || faces_[i].id != 0;
  }
  if (!any) return;
  if (faceProgram_ == 0) {
    faceProgram_ =
        buildProgram("Background panorama", kPanoramaVertexShader, kPanoramaFragmentShader);
    locFaceMatrix_ = uniform(faceProgram_, "u_matrix");
    locFaceCenter_ = uniform(faceProgram_, "u_center");
    locFaceRight_ = uniform(faceProgram_, "u_right");
    locFaceUp_ = uniform(faceProgram_, "u_up");
    locFaceTexture_ = uniform(faceProgram_, "u_texture");
  }
  if (vao_ == 0) glGenVertexArrays(1, &vao_);
  // Background coordinates -> clip: the Background's rotation, then the view's rotation.
  const glm::mat4 matrix = projection * rotationOnly * glm::mat4(background.rotation);
  glUseProgram(faceProgram_);
  glUniformMatrix4fv(locFaceMatrix_, 1, GL_FALSE, glm::value_ptr(matrix));
  glUniform1i(locFaceTexture_, 0);
  glActiveTexture(GL_TEXTURE0);
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glBindVertexArray(vao_);
  for (int f = 0; f < kFaces; ++f) {
    const auto i = static_cast<std::size_t>(f);
    if (faceIds_[i] == 0) continue;
    glUniform3fv(locFaceCenter_, 1, glm::value_ptr(kFaceTable[i].center));
    glUniform3fv(locFaceRight_, 1, glm::value_ptr(kFaceTable[i].right));
    glUniform3fv(locFaceUp_, 1, glm::value_ptr(kFaceTable[i].up));
    glBindTexture(GL_TEXTURE_2D, faceIds_[i]);
    glDrawArrays(GL_TRIANGLES, 0, 6);
  }
  glBindVertexArray(0);
  glBindTexture(GL_TEXTURE_2D, 0);
}

void BackgroundPass::releaseFaces() {
  for (GpuTexture& t : faces_)
    if (t.id != 0) glDeleteTextures(1, &t.id);
  faces_ = {};
  faceDone_ = {};
  facesNode_ = nullptr;
}

void BackgroundPass::release() {
  if (program_ != 0) glDeleteProgram(program_);
  if (vao_ != 0) glDeleteVertexArrays(1, &vao_);
  if (faceProgram_ != 0) glDeleteProgram(faceProgram_);
  program_ = vao_ = faceProgram_ = 0;
  releaseFaces();
}

}  // namespace gs::render::detail
