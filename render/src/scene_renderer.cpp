// SceneRenderer: per-frame drawing of a traversed scene.
#include "scene_renderer_gpu.hpp"

#include "base/url.hpp"
#include "line_fill_properties.hpp"
#include "scene/node_access.hpp"
#include "scene_splats.hpp"

#include <glm/gtc/matrix_inverse.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <unordered_map>

namespace gs::render {

using namespace detail;

namespace {

/// The 2D texture transform `m` (acting on (s, t, 1)) as a 4x4 on (s, t, r, 1).
glm::mat4 textureMatrix4(const glm::mat3& m) {
  glm::mat4 out(1.0f);
  out[0] = glm::vec4(m[0].x, m[0].y, 0.0f, 0.0f);
  out[1] = glm::vec4(m[1].x, m[1].y, 0.0f, 0.0f);
  out[3] = glm::vec4(m[2].x, m[2].y, 0.0f, 1.0f);
  return out;
}

/// Texture unit of an EnvironmentLight's specular cube map (units 0..4 are 2D maps).
constexpr GLint kEnvironmentUnit = 5;
/// Texture unit of a shape's ComposedCubeMapTexture (samplers of two types never share one).
constexpr GLint kCubeTextureUnit = 6;
/// Texture unit of a shape's X3D Texturing3D texture.
constexpr GLint kTexture3DUnit = 7;

/// The Phong program's CUBE_MAP for a shape: 0 without a cube map texture, else the
/// direction it is looked up by (shaders.cpp, cubeDirection), from the geometry's
/// TextureCoordinateGenerator, or its TextureCoordinate3D / 4D when it has those
/// (`texCoords3D`) and no generator (as X_ITE 15 reads them).
int cubeMapMode(const DrawItem& d, bool texCoords3D) {
  if (d.texture == nullptr || !d.texture->cube) return 0;
  if (d.texGen.mode == TexGenMode::none && texCoords3D) return 5;
  switch (d.texGen.mode) {
    case TexGenMode::cameraSpaceReflection:
      return 2;
    case TexGenMode::cameraSpaceNormal:
      return 3;
    case TexGenMode::worldSpaceNormal:
      return 4;
    default:
      return 1;
  }
}

/// ClipPlanes one shape takes (X3D 4.0 clause 11.4.1 asks for at least 6; the vertex
/// shader's kMaxClipPlanes). Further ones are reported once and not applied.
constexpr std::uint32_t kMaxClipPlanes = 6;

/// Uniform arrays of the lights of one shape.
struct LightArrays {
  int count = 0;
  std::array<GLint, kMaxLights> type{};
  std::array<glm::vec3, kMaxLights> color{}, position{}, direction{}, attenuation{};
  std::array<float, kMaxLights> intensity{}, ambient{}, radius{}, beamWidth{}, cutOff{};

  void add(const scene::LightInstance& l) {  // l in eye coordinates
    if (count >= kMaxLights) return;
    const auto i = static_cast<std::size_t>(count++);
    type[i] = static_cast<GLint>(l.type);
    color[i] = l.color;
    position[i] = l.location;
    direction[i] = l.direction;
    attenuation[i] = l.attenuation;
    intensity[i] = l.intensity;
    ambient[i] = l.ambientIntensity;
    radius[i] = l.radius;
    beamWidth[i] = l.beamWidth;
    cutOff[i] = l.cutOffAngle;
  }
  void upload(const SurfaceUniforms& u) const {
    glUniform1i(u.lightCount, count);
    if (count == 0) return;
    glUniform1iv(u.lightType, count, type.data());
    glUniform3fv(u.lightColor, count, glm::value_ptr(color[0]));
    glUniform3fv(u.lightPosition, count, glm::value_ptr(position[0]));
    glUniform3fv(u.lightDirection, count, glm::value_ptr(direction[0]));
    glUniform3fv(u.lightAttenuation, count, glm::value_ptr(attenuation[0]));
    glUniform1fv(u.lightIntensity, count, intensity.data());
    glUniform1fv(u.lightAmbientIntensity, count, ambient.data());
    glUniform1fv(u.lightRadius, count, radius.data());
    glUniform1fv(u.lightBeamWidth, count, beamWidth.data());
    glUniform1fv(u.lightCutOffAngle, count, cutOff.data());
  }
};

}  // namespace

SceneRenderer::SceneRenderer(std::shared_ptr<const vrml::Scene> scene, SceneRendererOptions options)
    : options_(std::move(options)),
      traversal_(std::move(scene),
                 [this] {
                   scene::TraversalOptions t = options_.traversal;
                   if (t.fetcher == nullptr) t.fetcher = options_.fetcher;
                   return t;
                 }()),
      gpu_(std::make_unique<Gpu>()),
      splats_(std::make_unique<detail::SceneSplats>(traversal_.sharedScene(), options_.splatLoader,
                                                    options_.lod, options_.traversal.mode,
                                                    options_.splatPath)),
      headlight_(traversal_.navigation().headlight) {
  gpu_->textures.movies.setPlayers(options_.movies);
  gpu_->textures.setQuality(options_.textureQuality);
  splats_->setFetcher(options_.fetcher);
}

SceneRenderer::~SceneRenderer() {
  // Without loaded GL functions there is nothing to free (and no way to).
  if (glad_glDeleteProgram != nullptr) {
    gpu_->release();
    splats_->release();
  }
}

const vrml::Bounds& SceneRenderer::bounds() {
  if (!haveBounds_) {
    bounds_ = traversal_.worldBounds();
    bounds_.extend(splats_->bounds(traversal_));
    haveBounds_ = true;
  }
  return bounds_;
}

void SceneRenderer::sceneChanged() {
  traversal_.sceneChanged();
  splats_->sceneChanged();
  haveBounds_ = false;
  // The NavigationInfo may have arrived just now.
  if (!headlightSet_) headlight_ = traversal_.navigation().headlight;
}

void SceneRenderer::setVectorBudget(std::uint64_t vectors) {
  splats_->setVectorBudget(vectors);
}

void SceneRenderer::setLod(double lod) {
  splats_->setLod(lod);
}

glm::quat SceneRenderer::defaultOrientation() {
  bounds();  // loads the QNV nodes
  return splats_->showsVolumesOnly() ? volumeFrontOrientation() : scene::Camera{}.orientation;
}

scene::Camera SceneRenderer::initialCamera(float aspect) {
  if (!viewpoints().empty() || bounds().empty()) return boundViewpointCamera();
  // A glTF asset starts where castle-model-viewer starts it (docs/gltf.md); other worlds
  // are fitted to the viewport.
  const bool gltf = traversal_.sharedScene()->x3d.encoding == "glTF";
  scene::Camera start;
  start.orientation = defaultOrientation();
  scene::Camera camera =
      gltf ? scene::wholeSceneCamera(bounds(), start) : scene::fitCamera(bounds(), aspect, start);
  if (navigation().visibilityLimit > 0.0f)
    camera.farClip = std::max(navigation().visibilityLimit, camera.nearClip * 2.0f);
  return camera;
}

void SceneRenderer::releaseGpuResources() {
  gpu_->release();
  splats_->release();
  gpu_->shadings.clear();
}

void SceneRenderer::generateCubeMaps(const scene::Camera& camera) {
  Gpu& g = *gpu_;
  g.frame.reportOutputs = false;
  traversal_.collect(camera, g.frame);
  struct Job {
    const vrml::Node* texture;
    const vrml::Node* geometry;
    glm::vec3 origin;
  };
  std::vector<Job> jobs;
  for (const scene::ShapeInstance& s : g.frame.shapes) {
    const auto it = s.appearance != nullptr ? g.shadings.find(s.appearance) : g.shadings.end();
    if (it == g.shadings.end() || it->second.texture == nullptr ||
        it->second.texture->typeId() != vrml::NodeTypeId::GeneratedCubeMapTexture ||
        !g.generatedCubes.due(*it->second.texture))
      continue;
    const vrml::Node* t = it->second.texture;
    if (std::none_of(jobs.begin(), jobs.end(), [t](const Job& j) { return j.texture == t; }))
      jobs.push_back({t, s.geometry, glm::vec3(s.model[3])});
  }
  if (jobs.empty()) return;
  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  generatingFace_ = true;
  for (const Job& job : jobs) {
    faceExcludes_ = job.geometry;
    for (int face = 0; face < 6; ++face) {
      const int size = g.generatedCubes.bindFace(*job.texture, face);
      draw(GeneratedCubeMaps::faceCamera(job.origin, face, camera.nearClip, camera.farClip), 0, 0,
           size, size);
    }
    g.generatedCubes.finish(*job.texture);
  }
  generatingFace_ = false;
  faceExcludes_ = nullptr;
  glBindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(framebuffer));
}

void SceneRenderer::draw(const scene::Camera& camera, int x, int y, int width, int height) {
  Gpu& g = *gpu_;
  if (width <= 0 || height <= 0) return;
  traversal_.setViewportSize(width, height);  // X3D Layout's pixel units
  if (generatedCubeMaps_ && !generatingFace_) generateCubeMaps(camera);
  const bool generatedBefore = generatedCubeMaps_;
  statistics_ = {};
  g.programs.enableVariants(options_.shaderVariants);
  g.programs.beginFrame();
  g.programs.generic();
  g.frame.reportOutputs = !generatingFace_;  // the user's view, not a cube map's face
  traversal_.collect(camera, g.frame);
  // Shading GOURAUD in a VRML97 or X3D 3.x world: textures multiply the lit colour. X3D 4's
  // lighting equation (clause 17.2.2.4) fixes where a texture enters it whatever the
  // browser's Shading; X_ITE 15 likewise shades only older worlds GOURAUD. (Read each frame:
  // a world still loading has no header yet when the renderer is made.)
  const bool afterLighting = textureAfterLighting(options_.shading, traversal_.scene().x3d.version);

  const float aspect = float(width) / float(height);
  const glm::mat4 view = scene::viewMatrix(camera);
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);

  glViewport(x, y, width, height);
  glScissor(x, y, width, height);
  glEnable(GL_SCISSOR_TEST);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  // With X3D layers (clause 35) the bound Background (the root layer's, or the active
  // layer's) is drawn under every layer; the default black when none is bound and the
  // LayerSet's order does not draw the root layer.
  if (g.frame.layerOrder.empty() || traversal_.background().node != nullptr ||
      std::any_of(g.frame.layerOrder.begin(), g.frame.layerOrder.end(),
                  [](const scene::LayerInstance& l) { return l.number == 0; })) {
    g.background.draw(traversal_.background(), view, projection, traversal_, options_.fetcher,
                      g.textures);
  } else {
    glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
  }

  // Lights in eye coordinates.
  g.eyeLights.resize(g.frame.lights.size());
  const glm::mat3 viewRotation(view);
  for (std::size_t i = 0; i < g.frame.lights.size(); ++i) {
    scene::LightInstance l = g.frame.lights[i];
    l.location = glm::vec3(view * glm::vec4(l.location, 1.0f));
    l.direction = glm::normalize(viewRotation * l.direction);
    g.eyeLights[i] = l;
  }
  // TextureProjectors in eye coordinates, their textures loaded (X3D 4.0 clause 42).
  g.eyeProjectors.resize(g.frame.projectors.size());
  for (std::size_t i = 0; i < g.frame.projectors.size(); ++i) {
    const scene::TextureProjectorInstance& p = g.frame.projectors[i];
    const vrml::NodePtr& texture = p.node->sfnode("texture");
    static const GpuTexture kNone;
    const GpuTexture& t =
        texture ? g.textures.get(*texture, *p.baseUrl, traversal_, options_.fetcher) : kNone;
    g.eyeProjectors[i] = eyeProjector(p, t, view);
    // aspectRatio: the texture's width over height, once it has loaded.
    if (g.frame.reportOutputs && t.id != 0 && t.width > 0 && t.height > 0) {
      const float ratio = static_cast<float>(t.width) / static_cast<float>(t.height);
      const auto [it, added] = g.projectorAspects.try_emplace(p.node, ratio);
      if (added || it->second != ratio) {
        it->second = ratio;
        g.outputs.push_back(
            {p.node, "aspectRatio", vrml::FieldValue::make<vrml::FieldType::SFFloat>(ratio)});
      }
    }
  }
  // ClipPlanes in eye coordinates (a plane maps by the inverse transpose of the view).
  const glm::mat4 planeToEye = glm::transpose(glm::inverse(view));
  g.eyeClipPlanes.resize(g.frame.scopedClipPlanes.size());
  for (std::size_t i = 0; i < g.frame.scopedClipPlanes.size(); ++i)
    g.eyeClipPlanes[i] = planeToEye * g.frame.scopedClipPlanes[i];
  std::uint32_t clipDistancesOn = 0;  // GL_CLIP_DISTANCEi enabled: i < clipDistancesOn

  scene::LightInstance headlight;  // directional along the view direction, intensity 1, ambient 0
  headlight.direction = glm::vec3(0.0f, 0.0f, -1.0f);
  // Whether the layer being drawn has the headlight (scene::LayerInstance::headlight).
  bool layerHeadlight = headlight_;

  collectDrawItems(camera);  // the shapes sorted into the opaque and transparent passes

  // Per-frame uniforms, set in each program the first time this frame uses it.
  // The bound Fog, or per shape its innermost X3D LocalFog (set with the shape's uniforms).
  const scene::FogSettings& boundFog = traversal_.fog();
  const auto fogOf = [&](const scene::ShapeInstance& s) -> const scene::FogSettings& {
    return s.localFog >= 0 ? g.frame.localFogs[static_cast<std::size_t>(s.localFog)] : boundFog;
  };
  const auto fogTypeOf = [](const scene::FogSettings& f) {
    return f.visibilityRange > 0.0f ? (f.exponential ? 2 : 1) : 0;
  };
  const SurfaceProgram* current = nullptr;
  auto use = [&](SurfaceProgram& p) {
    if (&p == current) return false;
    glUseProgram(p.id);
    current = &p;
    if (p.frameSet != g.programs.frame()) {
      const SurfaceUniforms& u = p.u;
      glUniformMatrix4fv(u.projection, 1, GL_FALSE, glm::value_ptr(projection));
      glUniform1f(u.pointSize, options_.pointSize > 0.0f                ? options_.pointSize
                               : traversal_.scene().x3d.version.empty() ? 2.0f
                                                                        : 1.0f);
      glUniform1i(u.texture, 0);
      for (std::size_t i = 0; i < kPhysicalMaps; ++i)
        glUniform1i(u.map[i], static_cast<GLint>(i + 1));
      glUniform1i(u.environmentMap, kEnvironmentUnit);
      glUniform1i(u.cubeTexture, kCubeTextureUnit);
      glUniform1i(u.texture3D, kTexture3DUnit);
      glUniform2f(u.viewportSize, static_cast<float>(width), static_cast<float>(height));
      glUniform1i(u.flatShading, options_.shading == ShadingOption::flat ? 1 : 0);
      p.frameSet = g.programs.frame();
    }
    return true;
  };
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glEnable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  glFrontFace(GL_CCW);
  glCullFace(GL_BACK);
  glActiveTexture(GL_TEXTURE0);

  const scene::ShapeInstance* lastLightsOf = nullptr;  // whose lights `lights` holds
  LightArrays lights;
  bool lightsUploaded = false;  // to the current program
  // An EnvironmentLight's uniforms (shaders_physical.cpp): eye directions turn into the
  // environment's through the view's rotation and the light's.
  const glm::mat3 eyeToWorld = glm::transpose(glm::mat3(view));
  auto setEnvironment = [&](const SurfaceUniforms& u, const DrawItem& d) {
    const GpuEnvironment* env = d.environment;
    glUniform1i(u.hasEnvironment, env != nullptr ? 1 : 0);
    if (env == nullptr) return;
    const scene::EnvironmentLightInstance& light = *d.environmentLight;
    glUniform1i(u.hasEnvironmentMap, env->cubeMap != 0 ? 1 : 0);
    glUniform3fv(u.environmentSh, 9, glm::value_ptr(env->irradiance[0]));
    glUniform3fv(u.environmentColor, 1, glm::value_ptr(light.color));
    glUniform1f(u.environmentAmbient, light.ambientIntensity);
    glUniform1f(u.environmentMaxLod, env->maxLod);
    const glm::mat3 eyeToEnvironment = glm::transpose(light.rotation) * eyeToWorld;
    glUniformMatrix3fv(u.eyeToEnvironment, 1, GL_FALSE, glm::value_ptr(eyeToEnvironment));
    if (env->cubeMap != 0) {
      glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kEnvironmentUnit));
      glBindTexture(GL_TEXTURE_CUBE_MAP, env->cubeMap);
    }
  };
  // A MultiTexture's stages: stage i's texture on unit i (stage 0 on u_texture's unit).
  auto setStages = [&](const SurfaceUniforms& u, const DrawItem& d, const MultiTextureStages& m) {
    std::array<GLint, 2 * kMaxTextureStages> modes{};
    std::array<GLint, kMaxTextureStages> sources{}, functions{};
    std::array<glm::mat3, kMaxTextureStages> matrices{};
    for (int i = 0; i < d.stageCount; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const TextureStage& st = m.stages[k];
      const bool loaded = d.stageTextures[k] != nullptr;
      modes[2 * k] = static_cast<GLint>(loaded ? st.rgbMode : TextureMode::off);
      modes[2 * k + 1] = static_cast<GLint>(loaded ? st.alphaMode : TextureMode::off);
      sources[k] = static_cast<GLint>(st.source);
      functions[k] = static_cast<GLint>(st.function);
      matrices[k] = st.matrix;
      if (!loaded) continue;
      if (i > 0) glUniform1i(u.stageTexture[k - 1], i);
      glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(i));
      glBindTexture(GL_TEXTURE_2D, d.stageTextures[k]->id);
    }
    glActiveTexture(GL_TEXTURE0);
    const auto n = static_cast<GLsizei>(d.stageCount);
    glUniform2iv(u.stageMode, n, modes.data());
    glUniform1iv(u.stageSource, n, sources.data());
    glUniform1iv(u.stageFunction, n, functions.data());
    glUniform1iv(u.stageTexCoord, n, d.stageSets.data());
    glUniformMatrix3fv(u.stageMatrix, n, GL_FALSE, glm::value_ptr(matrices[0]));
    glUniform4fv(u.stageFactor, 1, glm::value_ptr(m.factor));
  };
  // Back faces culled for solid polygons (the geometry's solid field), then the draw call,
  // counted.
  const auto drawMesh = [&](const GpuMesh& mesh) {
    if (mesh.primitive == vrml::Primitive::triangles && mesh.solid)
      glEnable(GL_CULL_FACE);
    else
      glDisable(GL_CULL_FACE);
    mesh.draw();
    statistics_.shapes += 1;
    statistics_.triangles += mesh.triangles;
  };
  auto drawItem = [&](const DrawItem& d) {
    const scene::ShapeInstance& s = *d.shape;
    const GpuMesh& mesh = *d.mesh;
    const Shading& sh = *d.shading;
    const bool triangles = mesh.primitive == vrml::Primitive::triangles;
    if (d.user != nullptr) {  // a user shader draws the shape (composed_shaders.hpp)
      const glm::mat4 textureMatrix = d.texture != nullptr && d.texture->volume
                                          ? sh.textureMatrix3D
                                          : textureMatrix4(sh.textureMatrix);
      g.userPrograms.use(*d.user, view * s.model, projection, d.texture, textureMatrix, g.textures,
                         *s.baseUrl, traversal_, options_.fetcher);
      mesh.bindAttributes(d.user->attributes);  // the vertex attribute nodes (31.4)
      current = nullptr;
      for (; clipDistancesOn > 0; --clipDistancesOn)
        glDisable(GL_CLIP_DISTANCE0 + clipDistancesOn - 1);
      drawMesh(mesh);
      return;
    }
    const bool lit = triangles && sh.hasMaterial;
    const bool physical = lit && sh.model == ShadingModel::physical;
    if (lit &&
        (lastLightsOf == nullptr || lastLightsOf->scopedLightBegin != s.scopedLightBegin ||
         lastLightsOf->scopedLightCount != s.scopedLightCount || lastLightsOf->layer != s.layer)) {
      lights = LightArrays{};
      if (layerHeadlight) lights.add(headlight);
      for (std::uint32_t i = 0; i < s.scopedLightCount; ++i)
        lights.add(g.eyeLights[g.frame.scopedLights[s.scopedLightBegin + i]]);
      for (std::uint32_t index : g.frame.globalLights)  // global in its own layer (35.2.1)
        if (g.eyeLights[index].layer == s.layer) lights.add(g.eyeLights[index]);
      lastLightsOf = &s;
      lightsUploaded = false;
    }
    SurfaceProgram* program = nullptr;
    if (physical) {
      program = &g.programs.physical();
    } else {
      SurfaceVariant v;
      v.lit = lit;
      v.hasColor = mesh.hasColors;
      v.textureComponents = d.texture != nullptr ? d.texture->components : 0;
      v.fogType = fogTypeOf(fogOf(s));
      v.separateBack = sh.separateBack;
      v.textureModulates = sh.textureModulates;
      v.clipPlanes = static_cast<int>(std::min(s.clipPlaneCount, kMaxClipPlanes));
      v.textureStages = d.stageCount;
      v.texGen = static_cast<int>(d.texGen.mode);
      v.cubeMap = cubeMapMode(d, mesh.hasTexCoordsStrq);
      v.texture3D = d.texture != nullptr && d.texture->volume;
      if (v.cubeMap != 0) v.texGen = 0;  // the fragment shader finds the direction
      sh.lineFill.specialize(v, mesh.primitive);
      if (lit) {
        v.lightCount = lights.count;
        for (int i = 0; i < lights.count; ++i)
          v.lightTypes[static_cast<std::size_t>(i)] =
              static_cast<std::uint8_t>(lights.type[static_cast<std::size_t>(i)]);
      }
      program = &g.programs.phong(v);
    }
    if (use(*program)) lightsUploaded = false;  // each program has its own light uniforms
    const SurfaceUniforms& u = program->u;
    const glm::mat4 modelView = view * s.model;
    const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(modelView));
    glUniformMatrix4fv(u.modelView, 1, GL_FALSE, glm::value_ptr(modelView));
    glUniformMatrix3fv(u.normalMatrix, 1, GL_FALSE, glm::value_ptr(normalMatrix));
    glUniformMatrix3fv(u.textureMatrix, 1, GL_FALSE, glm::value_ptr(sh.textureMatrix));
    glUniform1i(u.lit, lit ? 1 : 0);
    glUniform1i(u.hasColor, mesh.hasColors ? 1 : 0);
    glUniform1i(u.textureComponents, d.texture != nullptr ? d.texture->components : 0);
    const bool volumeTexture = d.texture != nullptr && d.texture->volume;
    glUniform1i(u.texture3DOn, volumeTexture ? 1 : 0);
    if (volumeTexture) {
      glUniformMatrix4fv(u.textureMatrix3D, 1, GL_FALSE, glm::value_ptr(sh.textureMatrix3D));
      glUniform3fv(u.texBoundsMin, 1, glm::value_ptr(mesh.bounds.min));
      glUniform3fv(u.texBoundsSize, 1, glm::value_ptr(mesh.bounds.size()));
      glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kTexture3DUnit));
      glBindTexture(GL_TEXTURE_3D, d.texture->id);
      glActiveTexture(GL_TEXTURE0);
    } else if (d.texture != nullptr && d.texture->cube) {
      glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kCubeTextureUnit));
      glBindTexture(GL_TEXTURE_CUBE_MAP, d.texture->id);
      glActiveTexture(GL_TEXTURE0);
    } else if (d.texture != nullptr) {
      glBindTexture(GL_TEXTURE_2D, d.texture->id);
    }
    glUniform3fv(u.diffuseColor, 1, glm::value_ptr(sh.diffuseColor));
    glUniform1f(u.ambientIntensity, sh.ambientIntensity);
    glUniform3fv(u.specularColor, 1, glm::value_ptr(sh.specularColor));
    glUniform3fv(u.emissiveColor, 1, glm::value_ptr(sh.emissiveColor));
    glUniform1f(u.shininess, sh.shininess);
    glUniform1f(u.transparency, sh.transparency);
    glUniform1i(u.textureModulates, sh.textureModulates ? 1 : 0);
    glUniform1i(u.textureAfterLighting, afterLighting ? 1 : 0);
    glUniform1i(u.separateBack, sh.separateBack ? 1 : 0);
    if (sh.separateBack) {
      glUniform3fv(u.backDiffuseColor, 1, glm::value_ptr(sh.backDiffuseColor));
      glUniform1f(u.backAmbientIntensity, sh.backAmbientIntensity);
      glUniform3fv(u.backSpecularColor, 1, glm::value_ptr(sh.backSpecularColor));
      glUniform3fv(u.backEmissiveColor, 1, glm::value_ptr(sh.backEmissiveColor));
      glUniform1f(u.backShininess, sh.backShininess);
      glUniform1f(u.backTransparency, sh.backTransparency);
    }
    glUniform1i(u.stageCount, d.stageCount);
    const int cube = cubeMapMode(d, mesh.hasTexCoordsStrq);
    glUniform1i(u.cubeMap, cube);
    glUniform1i(u.texGen, cube != 0 ? 0 : static_cast<GLint>(d.texGen.mode));
    if (d.texGen.mode == TexGenMode::sphereRefract)
      glUniform1f(u.texGenParameter, d.texGen.parameter);
    if (d.texGen.mode == TexGenMode::worldSpaceReflection ||
        d.texGen.mode == TexGenMode::worldSpaceNormal || cube == 1 || cube == 4)
      glUniformMatrix3fv(u.eyeToWorld, 1, GL_FALSE, glm::value_ptr(eyeToWorld));
    if (d.stageCount > 0) setStages(u, d, sh.multi);
    if (physical) {
      glUniform1f(u.metallic, sh.metallic);
      glUniform1f(u.roughness, sh.roughness);
      glUniform1f(u.normalScale, sh.normalScale);
      glUniform1f(u.occlusionStrength, sh.occlusionStrength);
      glUniform1i(u.alphaMode, sh.alphaMode == 3 ? 0 : sh.alphaMode);
      glUniform1f(u.alphaCutoff, sh.alphaCutoff);
      for (std::size_t i = 0; i < kPhysicalMaps; ++i) {
        glUniform1i(u.hasMap[i], d.maps[i] != nullptr ? 1 : 0);
        if (d.maps[i] == nullptr) continue;
        glActiveTexture(GL_TEXTURE1 + static_cast<GLenum>(i));
        glBindTexture(GL_TEXTURE_2D, d.maps[i]->id);
      }
      setEnvironment(u, d);
      glUniform1i(u.baseTexCoordSet, d.texCoordSets[0]);
      glUniform4i(u.mapTexCoordSet, d.texCoordSets[1], d.texCoordSets[2], d.texCoordSets[3],
                  d.texCoordSets[4]);
      glActiveTexture(GL_TEXTURE0);
    }
    // Lines and points are unlit: emissiveColor with a Material or a PhysicalMaterial (as
    // castle-model-viewer draws them; 6.24, 6.36), else white; an UnlitMaterial gives
    // emissiveColor.
    // X3D 4.0 clause 42: the TextureProjectors that reach the shape, global ones first (the
    // count is set for every draw: a program keeps the last one it was given).
    {
      ShapeProjectors projectors;
      auto addProjector = [&](std::uint32_t index) {
        if (g.eyeProjectors[index].layer == s.layer) projectors.add(g.eyeProjectors[index]);
      };
      for (std::uint32_t index : g.frame.globalProjectors) addProjector(index);
      for (std::uint32_t i = 0; i < s.projectorCount; ++i)
        addProjector(g.frame.scopedProjectors[s.projectorBegin + i]);
      uploadProjectors(u.projectors, projectors);
    }
    glm::vec3 unlit = (!triangles && sh.hasMaterial) ? sh.emissiveColor : glm::vec3(1.0f);
    if (sh.model == ShadingModel::unlit) unlit = sh.emissiveColor;
    glUniform3fv(u.unlitColor, 1, glm::value_ptr(unlit));
    sh.lineFill.setUniforms(u, mesh.primitive);
    const scene::FogSettings& fog = fogOf(s);
    glUniform1i(u.fogType, fogTypeOf(fog));
    glUniform3fv(u.fogColor, 1, glm::value_ptr(fog.color));
    glUniform1f(u.fogVisibilityRange, fog.visibilityRange);
    // Volumetric fog: the world plane (direction, -start) in eye coordinates, so that
    // dot(plane, (eye position, 1)) is the height along the direction above the start.
    const glm::vec4 fogPlane =
        fog.volumetric ? planeToEye * glm::vec4(fog.volumetricDirection, -fog.volumetricStart)
                       : glm::vec4(0.0f);
    glUniform4fv(u.fogPlane, 1, glm::value_ptr(fogPlane));
    if (lit && !lightsUploaded) {
      lights.upload(u);
      lightsUploaded = true;
    }
    const std::uint32_t clips = std::min(s.clipPlaneCount, kMaxClipPlanes);
    if (s.clipPlaneCount > kMaxClipPlanes)
      traversal_.report(vrml::Severity::warning, s.shape->location,
                        std::to_string(s.clipPlaneCount) +
                            " ClipPlanes clip this shape: only the innermost " +
                            std::to_string(kMaxClipPlanes) + " are applied");
    glUniform1i(u.clipPlaneCount, static_cast<GLint>(clips));
    if (clips > 0)
      glUniform4fv(u.clipPlanes, static_cast<GLsizei>(clips),
                   glm::value_ptr(g.eyeClipPlanes[s.clipPlaneBegin + s.clipPlaneCount - clips]));
    for (; clipDistancesOn < clips; ++clipDistancesOn)
      glEnable(GL_CLIP_DISTANCE0 + clipDistancesOn);
    for (; clipDistancesOn > clips; --clipDistancesOn)
      glDisable(GL_CLIP_DISTANCE0 + clipDistancesOn - 1);
    drawMesh(mesh);
    if (mesh.primitive == vrml::Primitive::lines && sh.lineFill.lineWidth != 1.0f)
      glLineWidth(1.0f);
  };

  if (splats_->mode() == scene::RenderMode::splats) {
    g.opaque.clear();  // the polygons are drawn as splats below
    g.transparent.clear();
  }
  // One layer's opaque then transparent shapes (layer < 0: every shape).
  const auto drawLayer = [&](std::int64_t layer) {
    const auto inLayer = [&](const DrawItem& d) { return layer < 0 || d.shape->layer == layer; };
    glDisable(GL_BLEND);
    for (const DrawItem& d : g.opaque)
      if (inLayer(d)) drawItem(d);
    if (g.transparent.empty()) return;
    glEnable(GL_BLEND);
    glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    for (const DrawItem& d : g.transparent) {
      if (!inLayer(d)) continue;
      drawItem(d);
      ++statistics_.transparent;
    }
    glDepthMask(GL_TRUE);
  };
  // The browser option Shading WIREFRAME and POINT: polygons as their edges or vertices
  // (lines and points stay as they are; X_ITE 15 likewise, for WIREFRAME).
  const GLenum polygonMode = options_.shading == ShadingOption::wireframe ? GL_LINE
                             : options_.shading == ShadingOption::point   ? GL_POINT
                                                                          : GL_FILL;
  glPolygonMode(GL_FRONT_AND_BACK, polygonMode);
  if (g.frame.layerOrder.empty()) drawLayer(-1);
  // X3D layers (clause 35.4.2): in the LayerSet's order, each over the previous (the depth
  // buffer cleared), a Layer's Viewport clipping it to its clipBoundary (scissor only: the
  // projection stays the window's; X_ITE 15 draws the layer into the rectangle with a
  // projection of its own, docs/xite-comparison.md). The active layer is seen by the
  // world's camera, the others from their own Viewpoint or the default one
  // (scene/src/traversal.cpp, Walk::layers).
  // Each layer's QNV and volume nodes are drawn after its shapes, against their depth and
  // inside its clipBoundary (the splat paths composite inside the scissor box set).
  const bool anySplats = !g.frame.splats.empty() || splats_->mode() == scene::RenderMode::splats;
  const auto drawSplats = [&](std::optional<std::uint32_t> layer) {
    if (!anySplats) return;
    const bool worldSplats = splats_->mode() == scene::RenderMode::splats;  // layer 0's
    if (layer && !(worldSplats && *layer == 0) &&
        std::none_of(g.frame.splats.begin(), g.frame.splats.end(),
                     [&](const scene::SplatInstance& s) { return s.layer == *layer; }))
      return;
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    for (; clipDistancesOn > 0; --clipDistancesOn)  // a ClipPlane clips its shapes only
      glDisable(GL_CLIP_DISTANCE0 + clipDistancesOn - 1);
    // Only opaque shapes write depth (transparent ones, the Background and the ray caster
    // do not): without them the splats need not be depth-tested.
    const bool depth = std::any_of(g.opaque.begin(), g.opaque.end(), [&](const DrawItem& d) {
      return !layer || d.shape->layer == *layer;
    });
    statistics_.splats += splats_->draw(g.frame, traversal_, camera, aspect, layerHeadlight,
                                        g.textures, height, depth, layer);
    // The shapes of a later layer start from the state drawItem expects: no program bound
    // as far as use() knows (the splat paths bound their own), the frame's GL state.
    glUseProgram(g.programs.generic().id);
    current = nullptr;
    glPolygonMode(GL_FRONT_AND_BACK, polygonMode);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LEQUAL);
    glDepthMask(GL_TRUE);
    glFrontFace(GL_CCW);
    glCullFace(GL_BACK);
    glActiveTexture(GL_TEXTURE0);
  };
  for (const scene::LayerInstance& l : g.frame.layerOrder) {
    const glm::ivec4 r = scene::layerRectangle(l.clipBoundary, x, y, width, height);
    glScissor(r.x, r.y, r.z, r.w);
    glDepthMask(GL_TRUE);
    glClear(GL_DEPTH_BUFFER_BIT);
    layerHeadlight = l.headlight < 0 ? headlight_ : l.headlight != 0;
    drawLayer(l.number);
    drawSplats(l.number);
  }
  layerHeadlight = headlight_;
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  glScissor(x, y, width, height);
  for (; clipDistancesOn > 0; --clipDistancesOn) glDisable(GL_CLIP_DISTANCE0 + clipDistancesOn - 1);
  statistics_.shaderVariants = g.programs.variantCount();
  statistics_.movieFrames = g.textures.movies.framesShown();
  statistics_.movieUploads = g.textures.movies.framesUploaded();

  if (g.frame.layerOrder.empty() && anySplats) {
    glDisable(GL_SCISSOR_TEST);
    drawSplats(std::nullopt);
    glEnable(GL_SCISSOR_TEST);
  }

  // Leave the state as other code (ImGui, the app) expects it.
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glDisable(GL_CULL_FACE);
  glDisable(GL_SCISSOR_TEST);
  glBindTexture(GL_TEXTURE_2D, 0);
  for (GLint unit : {kEnvironmentUnit, kCubeTextureUnit}) {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
    glBindTexture(GL_TEXTURE_CUBE_MAP, 0);
  }
  glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(kTexture3DUnit));
  glBindTexture(GL_TEXTURE_3D, 0);
  glActiveTexture(GL_TEXTURE0);
  glUseProgram(0);
  // The first frame to show a GeneratedCubeMapTexture drew it black: again, with its faces.
  if (!generatedBefore && generatedCubeMaps_ && !generatingFace_) draw(camera, x, y, width, height);
}

void SceneRenderer::setMediaClock(MediaClock clock, bool waitForFrames) {
  gpu_->textures.movies.setClock(std::move(clock), waitForFrames);
}

std::vector<std::pair<const vrml::Node*, double>> SceneRenderer::takeMediaDurations() {
  return gpu_->textures.movies.takeDurations();
}

std::vector<std::pair<const vrml::Node*, bool>> SceneRenderer::takeUrlObjectLoads() {
  return gpu_->textures.takeLoads();
}

vrml::DrawnOutputs SceneRenderer::takeDrawnOutputs() {
  vrml::DrawnOutputs out = traversal_.takeDrawnOutputs();
  for (vrml::DrawnOutput& o : gpu_->userPrograms.takeOutputs()) out.push_back(std::move(o));
  for (vrml::DrawnOutput& o : gpu_->outputs) out.push_back(std::move(o));
  gpu_->outputs.clear();
  return out;
}

}  // namespace gs::render
