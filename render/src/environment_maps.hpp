// Private to render/: the image-based light of X3D 4.1's EnvironmentLight (clause 17.4.2)
// for the physically based program (shaders_physical.cpp): a mipmapped GL cube map of the
// specular environment and the nine spherical-harmonic coefficients of its irradiance
// (R. Ramamoorthi, P. Hanrahan, "An Efficient Representation for Irradiance Environment
// Maps", SIGGRAPH 2001). docs/rendering.md, "Image-based lighting", says what is
// approximated.
#pragma once

#include <glad/gl.h>

#include "render/image.hpp"
#include "scene/traversal.hpp"

#include <glm/glm.hpp>

#include <array>
#include <string>
#include <vector>

namespace gs::base {
class Fetcher;
}

namespace gs::render::detail {

/// Spherical-harmonic coefficients (bands 0..2, order 00, 1-1, 10, 11, 2-2, 2-1, 20, 21,
/// 22; RGB) of E(n) / pi, E the irradiance: a Lambertian surface of albedo c reflects
/// c * sum_i sh[i] * Y_i(n). Y_i is the real SH basis in the environment's coordinates.
using IrradianceSh = std::array<glm::vec3, 9>;

/// The six faces of a cube map in linear RGB, each `size` x `size`, in GL's face order
/// (+X, -X, +Y, -Y, +Z, -Z) and GL's texel layout (OpenGL 4.5 core, table 8.19: row t,
/// column s).
struct CubeFaces {
  int size = 0;
  std::array<std::vector<glm::vec3>, 6> texels;
};

/// Resamples the six faces of an X3D cube map (ComposedCubeMapTexture, X3D 4.0 clause
/// 34.4.1; the same faces as Background, clause 6.5: back, bottom, front, left, right, top,
/// seen from inside the cube; images with rows top to bottom, sRGB) to GL's cube layout at
/// `size` texels a side (area averaging when a face is larger, nearest when smaller). A
/// face with no pixels is black.
CubeFaces resampleCubeFaces(const std::array<const Image*, 6>& x3dFaces, int size);

/// The six X3D faces (back, bottom, front, left, right, top, as resampleCubeFaces takes
/// them) of a cube map given as one 2D image (rows top to bottom), as X_ITE 15 reads an
/// ImageCubeMapTexture's PNG or JPEG (X3D 4.0 clause 34.4.2 leaves the layout to the
/// format):
/// - width 2 x height (within 1%): an equirectangular panorama, its centre column in the
///   direction +Z (the back face's centre: where X_ITE puts it), +X at 3/4 of its width, -X
///   at 1/4, its top row straight up; faces of height / 2 texels (at most 2048), sampled
///   bilinearly;
/// - width 4/3 x height: a horizontal cross, left, front, right and back in its middle row,
///   top above front, bottom below it, each face width / 4 texels;
/// empty (no faces) for any other shape.
std::vector<Image> cubeFacesOfImage(const Image& image);

/// Projects the radiance of `faces` on the SH basis and convolves it with the clamped
/// cosine (A0 = pi, A1 = 2 pi / 3, A2 = pi / 4), divided by pi.
IrradianceSh irradianceOf(const CubeFaces& faces);

/// The nine RGB coefficients of radiance an EnvironmentLight's `diffuseCoefficients` gives
/// (27 floats, the order of IrradianceSh), convolved as irradianceOf does; false when
/// fewer than 27 or a non-finite one.
bool irradianceFromCoefficients(const std::vector<float>& coefficients, IrradianceSh& out);

/// A ComposedCubeMapTexture (X3D 4.0 clause 34.4.1) as a texture of a shape (the Phong
/// program's samplerCube): its faces loaded through `fetcher` (null: local files) against
/// `baseUrl`, resampled to GL's cube layout at the largest face's side (at most 512 texels,
/// at least 1), kept in sRGB as the 2D textures are, mipmapped. `pending` when a face is
/// still on its way (ask again later); `problem` says why a face is missing (it is then
/// black). Returns id 0 when no face has pixels. Needs a current GL context.
struct CubeTexture {
  GLuint id = 0;
  bool pending = false;
  std::string problem;
};
CubeTexture loadCubeTexture(const vrml::Node& composed, const std::string& baseUrl,
                            base::Fetcher* fetcher);

/// The GPU side of one EnvironmentLight.
struct GpuEnvironment {
  GLuint cubeMap = 0;  // linear RGB, half floats, mipmapped; 0 when only SH light is given
  float maxLod = 0.0f;
  IrradianceSh irradiance{};
  bool usable = false;  // something to light with
};

/// EnvironmentLight nodes turned into GpuEnvironments once each (reloaded when the
/// light's or its textures' fields change). Faces load through the renderer's fetcher;
/// while one is on its way the light gives nothing and is asked for again at the next
/// draw. Unsupported or unreadable textures are reported once; the light then gives what
/// is left (diffuseCoefficients alone, or nothing).
class EnvironmentMaps {
 public:
  /// The environment of `light`, or null while loading or when it has nothing to light with.
  const GpuEnvironment* get(const scene::EnvironmentLightInstance& light,
                            scene::SceneTraversal& traversal, base::Fetcher* fetcher);
  void release();

 private:
  struct Entry {
    GpuEnvironment gpu;
    std::uint64_t revision = 0;
    bool done = false;
  };
  vrml::NodeMap<Entry> entries_;
};

}  // namespace gs::render::detail
