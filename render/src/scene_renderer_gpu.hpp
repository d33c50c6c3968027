// SceneRenderer's GL state kept from frame to frame (SceneRenderer::Gpu) and the draw list
// one frame sorts its shapes into (DrawItem): shared by scene_renderer.cpp, which draws the
// frame, and scene_draw_items.cpp, which makes the list.
#pragma once

#include "render/scene_renderer.hpp"

#include "composed_shaders.hpp"
#include "environment_maps.hpp"
#include "generated_cube_maps.hpp"
#include "gl_program.hpp"
#include "gpu_resources.hpp"
#include "multi_texture.hpp"
#include "shading.hpp"
#include "surface_programs.hpp"
#include "texture_generation.hpp"
#include "texture_projectors.hpp"

#include <array>
#include <vector>

namespace gs::render {

namespace detail {

/// One shape of the frame as it will be drawn: its mesh, shading and loaded textures.
struct DrawItem {
  const scene::ShapeInstance* shape;
  const GpuMesh* mesh;
  const Shading* shading;
  const GpuTexture* texture;                          // null: untextured
  std::array<const GpuTexture*, kPhysicalMaps> maps;  // PhysicalMaterial's other maps
  float depth;                                        // along the view direction, for sorting
  /// The EnvironmentLight of a PhysicalMaterial shape and its maps; null: none.
  const scene::EnvironmentLightInstance* environmentLight = nullptr;
  const GpuEnvironment* environment = nullptr;
  /// The set each texture reads: base colour, then the maps (texCoordSetOf).
  std::array<GLint, 1 + kPhysicalMaps> texCoordSets{};
  /// A MultiTexture's stage textures (null: not loaded; the stage is then OFF) and the
  /// texture coordinate set each reads.
  std::array<const GpuTexture*, kMaxTextureStages> stageTextures{};
  std::array<GLint, kMaxTextureStages> stageSets{};
  int stageCount = 0;
  TexGen texGen{};                    // the geometry's TextureCoordinateGenerator
  const UserProgram* user = nullptr;  // the Appearance's user shader, null: none
};

}  // namespace detail

/// The GL objects of a SceneRenderer (its context must be current), and the frame's
/// reused lists.
struct SceneRenderer::Gpu {
  detail::SurfacePrograms programs;
  vrml::NodeMap<detail::GpuMesh> meshes;
  vrml::NodeMap<detail::Shading> shadings;
  detail::TextureCache textures;
  detail::EnvironmentMaps environments;
  detail::BackgroundPass background;
  detail::UserPrograms userPrograms;
  detail::GeneratedCubeMaps generatedCubes;
  // Reused from frame to frame.
  scene::TraversalFrame frame;
  std::vector<scene::LightInstance> eyeLights;
  std::vector<detail::EyeProjector> eyeProjectors;  // frame.projectors, each with its texture
  std::vector<glm::vec4> eyeClipPlanes;
  std::vector<detail::DrawItem> opaque, transparent;
  /// Each TextureProjector's aspectRatio as last sent (X3D 4.0 clause 42.4.1: its
  /// texture's width over height), and the output events not taken yet.
  vrml::NodeMap<float> projectorAspects;
  vrml::DrawnOutputs outputs;

  void release() {
    for (auto& [node, mesh] : meshes) mesh.release();
    meshes.clear();
    textures.release();
    environments.release();
    background.release();
    userPrograms.release();
    generatedCubes.release();
    programs.release();
  }
};

}  // namespace gs::render
