// Private to render/: GPU-side objects of a SceneRenderer (meshes, textures, background).
// All need the renderer's context current.
#pragma once

#include <glad/gl.h>

#include "encodings/parser.hpp"
#include "formats/movie.hpp"
#include "geometry/geometry.hpp"
#include "render/image.hpp"
#include "render/movie_players.hpp"
#include "render/scene_renderer.hpp"
#include "scene/traversal.hpp"

#include <array>
#include <memory>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs::render::detail {

/// A vertex attribute a user program reads (X3D 4.0 clause 31.4): its GLSL name, its first
/// location and its shape (a vector: 1 column of 1 to 4 rows; a matN: N columns of N
/// rows, at N consecutive locations).
struct ProgramAttribute {
  std::string name;
  GLuint location = 0;
  int columns = 1, rows = 4;
};

/// One tessellated geometry in GPU buffers (a VAO, a vertex buffer holding the attribute
/// arrays one after another, an index buffer).
struct GpuMesh {
  GLuint vao = 0, vertexBuffer = 0, indexBuffer = 0;
  GLsizei count = 0;  // indices (or vertices when unindexed)
  bool indexed = false;
  vrml::Primitive primitive = vrml::Primitive::triangles;
  bool hasNormals = false, hasColors = false, hasTexCoords = false;
  bool colorAlpha = false;        // some colour is translucent (X3D ColorRGBA alpha < 1)
  bool hasTexCoords1 = false;     // the second texture coordinate set (vrml::Mesh::texCoords1)
  bool hasFogDepths = false;      // X3D FogCoordinate depths (vrml::Mesh::fogDepths)
  bool hasTexCoordsStrq = false;  // X3D TextureCoordinate3D/4D (vrml::Mesh::texCoordsStrq)
  bool solid = true;
  std::size_t triangles = 0;
  vrml::Bounds bounds;
  std::uint64_t revision = 0;  // vrml::revisionWithFields of the geometry uploaded
  /// The mesh's vertex attributes (vrml::Mesh::attributes) in the vertex buffer: floats,
  /// `components` per vertex, from byte `offset`; then "x3d_TexCoord0", X_ITE's name for
  /// the texture coordinates (the TextureCoordinate3D/4D array, else the 2D one).
  struct Attribute {
    std::string name;
    int components = 1;
    std::size_t offset = 0;
  };
  std::vector<Attribute> attributes;

  /// Uploads `mesh` (attribute locations: 0 position, 1 normal, 2 colour, 3 texCoord,
  /// 4 the second texCoord set, 5 the fog depth: -1 when the mesh has none, meaning the
  /// distance to the viewer, 6 the X3D TextureCoordinate3D/4D (s, t, r, q): (0, 0, 0, 0)
  /// when the mesh has none).
  void upload(const vrml::Mesh& mesh);
  /// Issues the draw call (the program and uniforms must be set).
  void draw() const;
  /// Feeds the attributes `wanted` of a user program from this mesh's vertex attributes
  /// of the same names (a float attribute of n components to a vector: n values, the
  /// others 0 and w 1; a matrix to a matrix of as many floats, column by column). One
  /// the mesh lacks, or of another size, reads the constant (0, 0, 0, 1) in each column.
  /// Call before draw() with that program; the arrays stay in the VAO until changed.
  void bindAttributes(const std::vector<ProgramAttribute>& wanted) const;
  void release();
};

/// A texture ready for sampling.
struct GpuTexture {
  GLuint id = 0;
  int components = 0;         // 1..4 as VRML97 counts them; 0 = no usable texture
  bool hasAlpha = false;      // some texel is not fully opaque
  bool cube = false;          // a GL_TEXTURE_CUBE_MAP (ComposedCubeMapTexture), else 2D
  bool volume = false;        // a GL_TEXTURE_3D (X3D Texturing3D)
  int width = 0, height = 0;  // pixels of a 2D image (0 when not known: movies)
};

/// The texels of an X3D Texturing3D texture (clause 33): RGBA8, s fastest, then t (rows
/// bottom to top), then r; components 1..4 as the file had them.
struct Texels3D {
  int width = 0, height = 0, depth = 0, components = 0;
  std::vector<std::uint8_t> rgba;
  bool pending = false;  // a file is still on its way: ask again at a later draw
  std::string problem;   // why there is no texture (for a warning); empty when fine
};

/// Decodes a PixelTexture3D (its image), a ComposedTexture3D (one slice per 2D
/// ImageTexture or PixelTexture, all of one size) or an ImageTexture3D (the first url that
/// loads: an uncompressed DDS volume, RGB, RGBA or luminance, or a raw/ascii NRRD with
/// attached data as grey stretched over its value range). At most 2^24 texels. Never
/// throws: a bad texture gives `problem`. Other nodes give an empty result.
Texels3D decodeTexture3D(const vrml::Node& node, const std::string& baseUrl,
                         base::Fetcher* fetcher);

/// The GL texture of a movie, shared by the renderers that share its player
/// (MoviePlayers): the frame in it, copied by the first renderer that drew it.
struct MovieGlTexture {
  GpuTexture texture;  // components 0 until the first frame
  int width = 0, height = 0;
  std::int64_t frame = -1;  // index of the frame in the texture
  MovieGlTexture() = default;
  MovieGlTexture(const MovieGlTexture&) = delete;
  MovieGlTexture& operator=(const MovieGlTexture&) = delete;
  ~MovieGlTexture();  // deletes the texture (its context must be current)
};

/// MovieTexture nodes (6.28, movie_textures.cpp): one formats::MoviePlayer each (decoding
/// on its worker thread), shared through MoviePlayers with the other renderers of the
/// world, and a GL texture of this renderer updated with the frame for the node's media
/// time whenever that frame changes (glTexSubImage2D, no mipmaps).
class MovieTextures {
 public:
  /// Where players are found and made (SceneRendererOptions::movies); before the first
  /// get(). Unset: a registry of this renderer's own.
  void setPlayers(std::shared_ptr<MoviePlayers> players);
  /// The texture of MovieTexture `node` for this frame; components 0 until its first
  /// frame is decoded (or when it cannot be read: a warning naming the url, once).
  const GpuTexture& get(const vrml::Node& node, const std::string& baseUrl,
                        scene::SceneTraversal& traversal, base::Fetcher* fetcher);
  /// With `waitForFrames`, also waits for the movies met so far to open, so that their
  /// durations are known before the next draw.
  void setClock(MediaClock clock, bool waitForFrames);
  /// Durations found since the last call (seconds; -1: unreadable).
  std::vector<std::pair<const vrml::Node*, double>> takeDurations();
  void release();
  /// New movie frames this renderer drew so far (all movies; each frame once).
  std::uint64_t framesShown() const { return shown_; }
  /// Of those, the frames this renderer copied into the shared textures itself.
  std::uint64_t framesUploaded() const { return uploads_; }

 private:
  std::uint64_t shown_ = 0, uploads_ = 0;
  struct Movie {
    std::shared_ptr<formats::MoviePlayer> player;
    std::shared_ptr<MovieGlTexture> gl;  // with the player, shared through players_
    std::int64_t seen = -1;              // index of the frame this renderer drew last
    bool durationTaken = false, failed = false;
  };
  vrml::NodeMap<Movie> movies_;
  std::vector<std::pair<const vrml::Node*, double>> durations_;
  std::shared_ptr<MoviePlayers> players_;
  MediaClock clock_;
  bool wait_ = false;
};

/// ImageTexture and PixelTexture nodes turned into GL textures once each (clause 6.22,
/// 6.33); MovieTexture through MovieTextures; unsupported textures become "no texture"
/// with a warning.
class TextureCache {
 public:
  /// The texture of `node` (an ImageTexture or PixelTexture), loading it on first use;
  /// URLs resolve against node.urlBaseOr(baseUrl) (`baseUrl` unless the node was written
  /// in an EXTERNPROTO's file, vrml::Node::urlBase). Failures are reported to `traversal` once and
  /// give a texture with 0 components.
  const GpuTexture& get(const vrml::Node& node, const std::string& baseUrl,
                        scene::SceneTraversal& traversal, base::Fetcher* fetcher);
  void release();
  /// The filter of textures without TextureProperties loaded from now on (the X3D browser
  /// option TextureQuality; SceneRendererOptions::textureQuality). Default high.
  void setQuality(TextureQuality quality) { quality_ = quality; }
  /// The ImageTextures and ImageTexture3Ds whose loading ended (true: loaded, false:
  /// failed) since the last call, for X3D LoadSensors (SceneRenderer::takeUrlObjectLoads).
  std::vector<std::pair<const vrml::Node*, bool>> takeLoads() {
    std::vector<std::pair<const vrml::Node*, bool>> out;
    out.swap(loads_);
    return out;
  }
  MovieTextures movies;

 private:
  vrml::NodeMap<GpuTexture> textures_;
  std::vector<std::pair<const vrml::Node*, bool>> loads_;
  TextureQuality quality_ = TextureQuality::high;
};

/// The first image of a URL list that could be read and decoded (ImageTexture.url,
/// Background.frontUrl ...; clause 4.5.4: later URLs only when earlier ones fail).
struct LoadedImage {
  Image image;            // rows top to bottom
  int components = 0;     // 1..4 (clause 5.5); 0 when no URL worked
  bool hasAlpha = false;  // some pixel is not fully opaque
  bool pending = false;   // a URL is still loading: ask again at a later draw
  std::string url;        // the URL decoded
  std::string failures;   // "url: why; ..." for the URLs that failed
};

/// Reads `urls` (resolved against `baseUrl`) in order through `fetcher` (null: local files)
/// under base::mayReference until one decodes. An RGB or grey file with transparent pixels
/// (PNG tRNS, GIF) counts as RGBA or grey+alpha. Never throws for bad content.
LoadedImage loadFirstImage(const std::vector<std::string>& urls, const std::string& baseUrl,
                           base::Fetcher* fetcher);

/// Uploads a loaded image as a mipmapped RGBA texture, bottom row first.
GpuTexture uploadImage(const LoadedImage& loaded, bool repeatS, bool repeatT);

/// Decodes an SFImage (PixelTexture) to RGBA rows bottom to top as GL expects them.
/// Returns false for inconsistent images.
bool decodeSFImage(const vrml::SFImage& image, std::vector<std::uint8_t>& rgba, bool& hasAlpha);

/// The Background (clause 6.5): the sky and ground colours as a full-screen gradient, then
/// the six panorama images on a cube around the viewer, blended over the colours by their
/// alpha. Images load through the renderer's fetcher like ImageTextures: a face
/// whose image is still on its way is left out (the colours show) and asked for again at
/// the next draw; a face whose URLs all fail is reported once and left out.
class BackgroundPass {
 public:
  /// Fills the current viewport. Only the view's rotation matters (the Background is at
  /// infinity): `view` is the camera's view matrix, `projection` its projection. Leaves
  /// depth writes and the depth buffer untouched.
  /// A TextureBackground's faces (X3D 4.0 clause 24.4.3) are its texture nodes, taken
  /// from `textures` (ImageTexture, PixelTexture, MovieTexture; loaded as shapes' are).
  void draw(const scene::BackgroundSettings& background, const glm::mat4& view,
            const glm::mat4& projection, scene::SceneTraversal& traversal, base::Fetcher* fetcher,
            TextureCache& textures);
  void release();

  /// The faces in the order of their fields: back, bottom, front, left, right, top.
  static constexpr int kFaces = 6;

 private:
  void drawGradient(const scene::BackgroundSettings& background, const glm::mat4& rotationOnly,
                    const glm::mat4& projection);
  void drawPanorama(const scene::BackgroundSettings& background, const glm::mat4& rotationOnly,
                    const glm::mat4& projection, scene::SceneTraversal& traversal,
                    base::Fetcher* fetcher, TextureCache& textures);
  void releaseFaces();

  GLuint program_ = 0, vao_ = 0;
  GLint locInverse_ = -1, locWorldToBackground_ = -1, locSkyCount_ = -1, locSkyColor_ = -1,
        locSkyAngle_ = -1, locGroundCount_ = -1, locGroundColor_ = -1, locGroundAngle_ = -1;
  GLuint faceProgram_ = 0;
  GLint locFaceMatrix_ = -1, locFaceCenter_ = -1, locFaceRight_ = -1, locFaceUp_ = -1,
        locFaceTexture_ = -1;
  // The panorama of one Background node (the bound one), reloaded when its fields change.
  const vrml::Node* facesNode_ = nullptr;
  std::uint64_t facesRevision_ = 0;
  std::array<GpuTexture, kFaces> faces_{};
  std::array<bool, kFaces> faceDone_{};   // loaded or failed: not asked for again
  std::array<GLuint, kFaces> faceIds_{};  // this frame's: faces_ or a TextureBackground's
};

}  // namespace gs::render::detail
