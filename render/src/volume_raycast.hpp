// Private to render/: X3D volume data nodes whose render styles (ISO/IEC 19775-1 X3D 4.0
// clause 41) are defined per sample along the view ray: Boundary, Edge and Silhouette
// enhancement, Cartoon, Shaded, ToneMapped, Projection, Composed and Blended styles,
// SegmentedVolumeData's segments and IsoSurfaceVolumeData's surfaces with styles. They
// depend on the view direction at every sample (and Projection on the order along the ray),
// which the paper's splats, shaded once per vector, cannot give: they are drawn by a ray
// caster on the GPU (docs/x3d.md "Volume render styles: a ray caster").
//
// The ray caster samples where X_ITE 15 draws its slices: 400 planes perpendicular to the
// view axis, centred at the volume's origin, spanning the box's diagonal |dimensions|
// (X3DVolumeDataNode.getPoints); each sample inside the box takes X_ITE's style code
// (volume_style_glsl.hpp) and is composited front to back, which is X_ITE's back-to-front
// blending of the same slices. The box `dimensions` (metres) is centred at the node's
// origin; texture coordinates are position / dimensions + 0.5.
#pragma once

#include "gpu_resources.hpp"
#include "render/splat_model.hpp"
#include "scene/camera.hpp"
#include "scene/traversal.hpp"

#include <glad/gl.h>

#include <map>
#include <span>
#include <string>

namespace gs::render::detail {

/// What else acts on a volume's samples, as on a shape's fragments: the ClipPlanes in
/// scope (world coordinates, (a, b, c, d) keeping a p.x + b p.y + c p.z + d >= 0; at most
/// 8 are used) and the fog (the bound Fog or the innermost LocalFog).
struct VolumeSurroundings {
  std::span<const glm::vec4> clipPlanes;
  const SplatFog& fog;
};

/// The fog of `fog` (a Fog or LocalFog's settings) seen through `view` (world to eye), as
/// the splats and the ray caster apply it: a volumetric fog's plane in eye coordinates.
SplatFog splatFogOf(const scene::FogSettings& fog, const glm::mat4& view);

/// The ray caster's GL objects: the box and one program per generated style code.
class VolumeRaycaster {
 public:
  VolumeRaycaster() = default;
  VolumeRaycaster(const VolumeRaycaster&) = delete;
  VolumeRaycaster& operator=(const VolumeRaycaster&) = delete;
  ~VolumeRaycaster() = default;  // release() deletes the GL objects (context current)

  /// Draws volume data node `node` (VolumeData, SegmentedVolumeData, IsoSurfaceVolumeData)
  /// with `model` (local to world) over the framebuffer, blended, depth-tested against it
  /// and not writing depth. Its textures come from `textures` (their urls resolve against
  /// `baseUrl`; a texture still loading draws nothing this frame). `lights` are the
  /// frame's lights in world coordinates; `headlight` adds X_ITE's (directional, along
  /// the view). Samples outside a clip plane of `around` are skipped, and each sample's
  /// colour is fogged by its eye distance as a shape's fragment is (X_ITE 15 clips and
  /// fogs each slice's fragments). An opaque surface the framebuffer's depth holds ends
  /// the rays there, inside the box too (X_ITE depth-tests each of its slices). A style
  /// program that does not compile is reported to
  /// `traversal` once and the node is not drawn. Returns whether anything was drawn.
  bool draw(const vrml::Node& node, const std::string& baseUrl, const glm::mat4& model,
            const scene::Camera& camera, float aspect, std::span<const scene::LightInstance> lights,
            bool headlight, const VolumeSurroundings& around, TextureCache& textures,
            scene::SceneTraversal& traversal, base::Fetcher* fetcher);
  /// Deletes the GL objects (the context must be current).
  void release();

 private:
  /// Copies the depth of the framebuffer being drawn, in `viewport` (x, y, width, height;
  /// pixels), to depthTexture_ at the same pixels (resolving a multisampled one). False,
  /// and nothing copied, when its depth is not 24 bits with 8 of stencil (a blit needs
  /// equal formats) or the copy's framebuffer is incomplete: the rays then run through.
  bool copySceneDepth(const GLint viewport[4]);

  GLuint vao_ = 0, vbo_ = 0;
  GLuint depthFbo_ = 0, depthTexture_ = 0;  // the opaque scene's depth (copySceneDepth)
  int depthWidth_ = 0, depthHeight_ = 0;
  GLuint linearSampler_ = 0, nearestSampler_ = 0;  // sampler objects: no mipmaps
  std::map<std::string, GLuint> programs_;         // by fragment source; 0: did not compile
};

}  // namespace gs::render::detail
