// Private to render/: X3D's programmable shaders (ISO/IEC 19775-1 X3D 4.0 clause 31, the
// Shaders component) as far as a desktop OpenGL renderer draws them: an Appearance's first
// ComposedShader in GLSL whose ShaderParts compile and link replaces the built-in surface
// program for that shape (clause 31.2.2: "the first shader the browser supports").
//
// Sources written for OpenGL 2 (GLSL 1.10 to 1.50: attribute, varying, texture2D,
// gl_Vertex, gl_ModelViewMatrix, gl_FragColor ...) are translated to GLSL 3.30 core
// (translateGlsl); the vertex data and matrices are offered under castle-model-viewer's
// names (castle_Vertex, castle_ModelViewMatrix ...), X_ITE's (x3d_Vertex,
// x3d_ModelViewMatrix ...) and OpenGL 2's built-ins. Each field the shader node declares
// (initializeOnly or inputOutput) sets the uniform of its name every frame (clause 31.2.3),
// SFNode texture fields binding their texture to a unit of its own; Appearance.texture
// is on unit 0. A ProgramShader's ShaderPrograms are built the same way (each program's
// own fields its uniforms); the vertex attribute nodes of the geometry (FloatVertexAttribute
// ...) feed the program's attributes of their names. PackagedShader and other languages
// are passed over (31.2.2), PackagedShader with a warning.
#pragma once

#include "gl_program.hpp"
#include "gpu_resources.hpp"

#include "base/fetch.hpp"
#include "scene/traversal.hpp"
#include "vrml/drawn_output.hpp"
#include "vrml/node.hpp"

#include <glm/mat4x4.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gs::render::detail {

enum class ShaderStage { vertex, fragment };

/// GLSL `source` of `stage` as GLSL 3.30 core: unchanged when it declares `#version 330`
/// or later (not `es`); otherwise the #version line is dropped, its #extension lines are
/// kept first, and macros and declarations map OpenGL 2's keywords, functions and
/// built-in variables that `source` uses onto core ones (gl_Vertex onto the input
/// gs_Vertex, gl_ModelViewMatrix onto the uniform gs_ModelViewMatrix, gl_FragColor onto an
/// output ...). A `#line 1` keeps the compiler's line numbers those of `source`.
std::string translateGlsl(std::string_view source, ShaderStage stage);

/// A linked program of one ComposedShader or ProgramShader node and the uniforms and
/// vertex attributes it takes.
/// Texture units of X_ITE's x3d_Texture3D[0] and x3d_TextureCube[0] in a user program (the
/// shader nodes' texture fields take units 1..13).
inline constexpr GLint kUserTexture3DUnit = 14;
inline constexpr GLint kUserTextureCubeUnit = 15;

struct UserProgram {
  GLuint id = 0;
  const vrml::Node* shader = nullptr;  // the ComposedShader or ProgramShader
  std::vector<GLint> modelView, projection, normalMatrix, modelViewProjection;
  /// X_ITE's x3d_NumTextures, x3d_TextureMatrix[0], x3d_Texture2D[0], x3d_Texture3D[0] and
  /// x3d_TextureCube[0] (-1: the program has none).
  GLint numTextures = -1, textureMatrix = -1, texture2D = -1, texture3D = -1, textureCube = -1;
  struct FieldUniform {
    const vrml::Node* node;  // the ComposedShader, or a ShaderProgram (read per draw)
    std::size_t field;       // index into that node's fields
    GLint location;
    GLint unit;  // texture unit for an SFNode texture field, else -1
  };
  std::vector<FieldUniform> fields;
  /// The attributes other than the vertex data's (the vertex attribute nodes', X3D 4.0
  /// clause 31.4), at locations 8 and up (GpuMesh::bindAttributes feeds them).
  std::vector<ProgramAttribute> attributes;
};

/// The programs of the ComposedShaders of one GL context, built on first use. Needs that
/// context current in every call.
class UserPrograms {
 public:
  /// The program for a shape with Appearance `appearance`: that of the first node of its
  /// `shaders` field that is a ComposedShader (its ShaderParts) or a ProgramShader (its
  /// ShaderPrograms, one VERTEX and one FRAGMENT at least) in GLSL (or with no language)
  /// whose sources load (urls: files, data: URLs, the network under the fetcher's rules;
  /// resolved against `baseUrl`), compile and link (X3D 4.0 clause 31.2.2). Null when
  /// there is none, or while a source is still arriving (the built-in shading draws the
  /// shape meanwhile). A shader that fails is reported to `traversal` once (at the node,
  /// with the compiler's log) and not tried again until its sources change. Shaders in
  /// other languages are passed over silently; a PackagedShader (31.4.5: no package
  /// format is run here) is passed over with one warning naming it.
  const UserProgram* find(const vrml::Node& appearance, const std::string& baseUrl,
                          scene::SceneTraversal& traversal, base::Fetcher* fetcher);

  /// Makes `program` current with the uniforms of one shape: the matrices (`modelView`
  /// and `projection` as column-major glm matrices), the shader node's field values and
  /// textures (from `textures`, units 1..13), and `texture` (Appearance.texture, may be
  /// null) on unit 0, or for X_ITE's x3d_Texture3D[0] / x3d_TextureCube[0] on units 14 /
  /// 15, with `textureMatrix` (the Appearance's texture transform, column-major, acting
  /// on (s, t, r, 1)) as x3d_TextureMatrix[0]. Leaves texture unit 0 active.
  void use(const UserProgram& program, const glm::mat4& modelView, const glm::mat4& projection,
           const GpuTexture* texture, const glm::mat4& textureMatrix, TextureCache& textures,
           const std::string& baseUrl, scene::SceneTraversal& traversal, base::Fetcher* fetcher);

  /// Deletes every program.
  void release();

  /// The shaders' isValid and isSelected output events (X3D 4.0 clause 31.3.1) since the
  /// last call, each when it changed: find() sends isValid TRUE and isSelected TRUE for the
  /// shader whose program it returns, isValid FALSE (and isSelected FALSE after TRUE) for
  /// one whose sources fail to compile or link, and for a PackagedShader.
  vrml::DrawnOutputs takeOutputs() { return std::exchange(outputs_, {}); }

 private:
  struct Entry {
    std::uint64_t partsRevision = 0;
    bool failed = false;
    bool selectedNoted = false;  // noteState(valid, selected) ran for this program
    UserProgram program;
  };
  const UserProgram* build(const vrml::Node& shader, Entry& entry, const std::string& baseUrl,
                           scene::SceneTraversal& traversal, base::Fetcher* fetcher, bool& pending);
  static void skipPackaged(const vrml::Node& shader, scene::SceneTraversal& traversal);
  /// Notes what `shader`'s isValid and isSelected now say: events for what changed.
  void noteState(const vrml::Node& shader, bool valid, bool selected);
  vrml::NodeMap<Entry> programs_;
  struct SentState {
    std::optional<bool> valid, selected;
  };
  vrml::NodeMap<SentState> sent_;
  vrml::DrawnOutputs outputs_;
  /// Per ShaderProgram: (its revision, the hash of its type and urls) (sourcesRevision).
  vrml::NodeMap<std::pair<std::uint64_t, std::uint64_t>> sourceHashes_;
};

}  // namespace gs::render::detail
