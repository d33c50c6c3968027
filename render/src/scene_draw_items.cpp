// SceneRenderer::collectDrawItems: the frame's shapes sorted into the opaque and
// transparent passes, each with its mesh uploaded, its shading read and its textures
// loaded (scene_renderer_gpu.hpp).
#include "scene_renderer_gpu.hpp"

#include "line_fill_properties.hpp"

#include <algorithm>

namespace gs::render {

using namespace detail;

void SceneRenderer::collectDrawItems(const scene::Camera& camera) {
  Gpu& g = *gpu_;
  g.opaque.clear();
  g.transparent.clear();
  const glm::vec3 forward = camera.forward();
  for (const scene::ShapeInstance& s : g.frame.shapes) {
    if (s.geometry == faceExcludes_) continue;  // (its own GeneratedCubeMapTexture's view)
    auto [meshIt, newMesh] = g.meshes.try_emplace(s.geometry);
    // The change contract (docs/runtime.md): a geometry whose fields or Coordinate /
    // Normal / Color / TextureCoordinate changed is tessellated and uploaded again.
    const std::uint64_t meshRevision = vrml::revisionWithFields(*s.geometry);
    if (newMesh || meshIt->second.revision != meshRevision) {
      if (!newMesh) meshIt->second.release();
      meshIt->second.upload(traversal_.mesh(*s.geometry));
      meshIt->second.revision = meshRevision;
      traversal_.dropMeshArrays(*s.geometry);
    }
    const GpuMesh& mesh = meshIt->second;
    if (mesh.count == 0) continue;
    auto [shadeIt, newShade] = g.shadings.try_emplace(s.appearance);
    const std::uint64_t shadeRevision = s.appearance ? vrml::revisionWithFields(*s.appearance) : 0;
    if (newShade || shadeIt->second.revision != shadeRevision) {
      shadeIt->second = readShading(s.appearance, !traversal_.scene().x3d.version.empty());
      shadeIt->second.revision = shadeRevision;
      for (const std::string& problem : shadeIt->second.multi.problems)
        traversal_.report(vrml::Severity::warning, shadeIt->second.multiTextureNode->location,
                          problem);
      if (const LineFillStyle& lf = shadeIt->second.lineFill; !lf.problem.empty())
        traversal_.report(vrml::Severity::warning, lf.problemNode->location, lf.problem);
    }
    const Shading& shading = shadeIt->second;
    if (mesh.primitive == vrml::Primitive::triangles && shading.lineFill.invisible()) continue;
    const GpuTexture* texture = nullptr;
    if (shading.texture != nullptr && mesh.primitive == vrml::Primitive::triangles) {
      if (shading.texture->typeId() == vrml::NodeTypeId::GeneratedCubeMapTexture) {
        texture = g.generatedCubes.texture(*shading.texture);
        generatedCubeMaps_ = true;
      } else {
        texture = &g.textures.get(*shading.texture, *s.baseUrl, traversal_, options_.fetcher);
      }
      if (texture->components == 0) texture = nullptr;
    }
    const glm::vec3 center = glm::vec3(s.model * glm::vec4(mesh.bounds.center(), 1.0f));
    std::array<const GpuTexture*, kPhysicalMaps> maps{};
    if (shading.model == ShadingModel::physical && mesh.primitive == vrml::Primitive::triangles)
      for (std::size_t i = 0; i < kPhysicalMaps; ++i)
        if (shading.maps[i] != nullptr) {
          maps[i] = &g.textures.get(*shading.maps[i], *s.baseUrl, traversal_, options_.fetcher);
          if (maps[i]->components == 0) maps[i] = nullptr;
        }
    DrawItem item{&s, &mesh, &shading, texture, maps, glm::dot(center - camera.position, forward)};
    if (shading.model == ShadingModel::physical && mesh.primitive == vrml::Primitive::triangles &&
        s.environmentLight >= 0) {
      item.environmentLight =
          &g.frame.environmentLights[static_cast<std::size_t>(s.environmentLight)];
      item.environment = g.environments.get(*item.environmentLight, traversal_, options_.fetcher);
    }
    bool stageAlpha = false;
    if (mesh.primitive == vrml::Primitive::triangles) {
      const std::vector<TextureStage>& stages = shading.multi.stages;
      item.stageCount = static_cast<int>(stages.size());
      for (std::size_t i = 0; i < stages.size(); ++i) {
        const GpuTexture* t =
            &g.textures.get(*stages[i].texture, *s.baseUrl, traversal_, options_.fetcher);
        item.stageTextures[i] = t->components > 0 ? t : nullptr;
        // Translucent texels, or an alpha combination that can fall below 1 however
        // opaque the textures are (SUBTRACT gives 1 - 1 = 0; DOTPRODUCT3).
        stageAlpha = stageAlpha || (t->components > 0 && t->hasAlpha) ||
                     stages[i].alphaMode == TextureMode::subtract ||
                     stages[i].alphaMode == TextureMode::dotProduct3;
        item.stageSets[i] = stageTexCoordSet(static_cast<int>(i), *s.geometry, mesh.hasTexCoords1);
      }
      stageAlpha = stageAlpha || (item.stageCount > 0 && shading.multi.factor.a < 1.0f);
    }
    if (texture != nullptr || item.stageCount > 0) {
      item.texGen = texGenOf(*s.geometry);
      if (!item.texGen.problem.empty())
        traversal_.report(vrml::Severity::warning, s.geometry->sfnode("texCoord")->location,
                          item.texGen.problem);
    }
    if (shading.hasShaders)
      item.user =
          g.userPrograms.find(*shading.appearance, *s.baseUrl, traversal_, options_.fetcher);
    if (shading.anyMapping && mesh.hasTexCoords1)
      for (std::size_t i = 0; i < item.texCoordSets.size(); ++i)
        item.texCoordSets[i] = texCoordSetOf(shading.mappings[i], *s.geometry);
    // Appearance.alphaMode (X3D 4.0 clause 12.4.2): OPAQUE and MASK never blend, BLEND
    // always does, AUTO when the material or the texture is translucent.
    const bool blended =
        shading.alphaMode == 3 ||
        (shading.alphaMode == 0 &&
         (shading.transparency > 0.0f || shading.backTransparency > 0.0f ||
          (texture != nullptr && texture->hasAlpha) || stageAlpha || mesh.colorAlpha));
    (blended ? g.transparent : g.opaque).push_back(item);
  }
  std::sort(g.transparent.begin(), g.transparent.end(),
            [](const DrawItem& a, const DrawItem& b) { return a.depth > b.depth; });
}

}  // namespace gs::render
