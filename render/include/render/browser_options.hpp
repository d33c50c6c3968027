// The X3D browser options that change how a world is drawn (ISO/IEC 19775-1, the browser
// options of the Networking component, which X_ITE sets with Browser.setBrowserOption):
// TextureQuality and Shading. `--texture-quality` and `--shading` on the command line.
#pragma once

#include <string_view>

namespace gs::render {

/// The X3D browser option TextureQuality (ISO/IEC 19775-1, the browser options of the
/// Networking component; X_ITE's `setBrowserOption("TextureQuality", ...)`): how a texture
/// without TextureProperties is filtered. high: trilinear (GL_LINEAR_MIPMAP_LINEAR), as
/// castle-model-viewer draws; medium: nearest texels of the two nearest mipmap levels
/// (GL_NEAREST_MIPMAP_LINEAR), X_ITE 15's default; low: bilinear, no mipmaps. Magnified
/// texels are bilinear in all three.
enum class TextureQuality { low, medium, high };

/// The X3D browser option Shading (the same table; a Script sets it with
/// Browser.setBrowserOption("Shading", ...), ISO/IEC 19777-1 clause 7.2.3), as X_ITE 15 draws
/// each value:
/// - phong: a texture colours the diffuse term before lighting; every pixel lit.
/// - gouraud: for Material (Phong) shapes of VRML97 and X3D 3.x worlds, the texture
///   multiplies the lit colour, emissive and specular included, as fixed-function Gouraud
///   shading with a modulating texture did and as X_ITE 15's default GOURAUD draws those
///   worlds; every pixel still lit (X_ITE's GOURAUD is too). X3D 4 worlds are drawn phong:
///   clause 17.2.2.4 fixes the texture's place in the lighting equation (X_ITE 15 likewise).
/// - flat: phong with each triangle's own normal (from the screen derivatives of the
///   position) in place of the geometry's normals: facets show.
/// - wireframe: polygons drawn as their edges (glPolygonMode GL_LINE), lit as phong.
/// - point: polygons drawn as their vertices (glPolygonMode GL_POINT), lit as phong.
/// Lines and points are drawn as they are in every mode (docs/rendering.md, "Browser
/// options").
enum class ShadingOption { point, wireframe, flat, gouraud, phong };

/// Reads "low" / "medium" / "high", and "point" (or X_ITE's "pointset") / "wireframe" /
/// "flat" / "gouraud" / "phong", in any case into `out`; false (`out` unchanged) for
/// anything else.
bool parseTextureQuality(std::string_view name, TextureQuality& out);
bool parseShadingOption(std::string_view name, ShadingOption& out);

/// The X3D name of a Shading value, as Browser.getBrowserOption("Shading") gives it:
/// "POINT", "WIREFRAME", "FLAT", "GOURAUD" or "PHONG".
std::string_view shadingName(ShadingOption shading);

/// Whether `shading` makes a Material shape's texture multiply the lit colour in a world of
/// header version `x3dVersion` ("3.3", "4.0" ...; empty for VRML97): true for gouraud in
/// VRML97 and X3D 3.x worlds, false otherwise (see ShadingOption).
bool textureAfterLighting(ShadingOption shading, std::string_view x3dVersion);

/// The renderer's fixed limits, as a Script reads them with Browser.getRenderingProperty
/// (ISO/IEC 19775-2 clause 6.3.13): the same in the window and in --snapshot.
struct RenderingLimits {
  int maxTextureSize = 0;  // pixels per side of the largest image a texture reads (kMaxImageSide)
  int textureUnits = 0;    // textures one MultiTexture combines; the rest are left out
  int maxLights = 0;       // lights that light one shape; the first met are kept
};
RenderingLimits renderingLimits();

}  // namespace gs::render
