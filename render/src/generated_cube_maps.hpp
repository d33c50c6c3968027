// GeneratedCubeMapTexture (X3D 4.0 clause 34.4.1): a cube map the renderer draws itself,
// the world seen from the shape that uses it, one face at a time into a framebuffer
// (SceneRenderer::draw generates the due ones before the frame that shows them). Internal
// to gs_render.
#pragma once

#include <glad/gl.h>
#include "gpu_resources.hpp"
#include "scene/camera.hpp"
#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <cstdint>

namespace gs::render::detail {

class GeneratedCubeMaps {
 public:
  /// Texels a face side has at most (the node's `size` is clamped to 1..this).
  static constexpr int kMaxSize = 2048;

  /// The cube map of `node` (a GeneratedCubeMapTexture), made at its `size` texels a side
  /// on first use: RGBA8, mipmapped, black until its faces are first drawn. Needs a
  /// current GL context.
  const GpuTexture* texture(const vrml::Node& node);
  /// Whether `node`'s faces are to be drawn for this frame, by its `update` field: "ALWAYS"
  /// every frame, "NEXT_FRAME_ONLY" once (and again after any field of the node changes),
  /// "NONE" (the default) never, the texture staying as it was.
  bool due(const vrml::Node& node) const;
  /// Makes face `face` (GL order: +X, -X, +Y, -Y, +Z, -Z) of `node`'s cube map, with a
  /// depth buffer, the draw framebuffer. Returns its side in texels.
  int bindFace(const vrml::Node& node, int face);
  /// The six faces were drawn: mipmaps made, the node's revision noted for due().
  void finish(const vrml::Node& node);
  void release();

  /// The camera that draws face `face` (GL order) from `position` (world, metres): a
  /// 90-degree square view along the face's axis, up as GL's cube map layout has it
  /// (OpenGL 4.5 core, table 8.19), so that a lookup by a world direction finds what lies
  /// that way.
  static scene::Camera faceCamera(glm::vec3 position, int face, float nearClip, float farClip);

 private:
  struct Entry {
    GpuTexture texture;
    GLuint framebuffer = 0, depth = 0;
    int size = 0;
    bool drawn = false;
    std::uint64_t drawnRevision = 0;
  };
  vrml::NodeMap<Entry> entries_;
};

}  // namespace gs::render::detail
