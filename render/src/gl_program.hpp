// Private to render/: GLSL program compilation and the shader sources.
#pragma once

#include <glad/gl.h>

#include <string>

namespace gs::render::detail {

/// Compiles and links a vertex + fragment program, with a geometry stage when
/// `geometrySource` is not null. Throws std::runtime_error with the compiler's log
/// (prefixed by `name`) on failure.
GLuint buildProgram(const char* name, const char* vertexSource, const char* fragmentSource,
                    const char* geometrySource = nullptr);

/// Compiles and links a compute program (OpenGL 4.3). Throws std::runtime_error with the
/// compiler's log (prefixed by `name`) on failure.
GLuint buildComputeProgram(const char* name, const char* source);

/// Location of uniform `name` in `program` (-1 when the compiler dropped it).
inline GLint uniform(GLuint program, const char* name) {
  return glGetUniformLocation(program, name);
}

/// The lit/unlit surface program (VRML97 lighting, clause 4.14), shaders.cpp.
extern const char* const kSurfaceVertexShader;
extern const char* const kSurfaceFragmentShader;
/// The physically based fragment stage (PhysicalMaterial, glTF), shaders_physical.cpp;
/// with kSurfaceVertexShader.
extern const char* const kPhysicalFragmentShader;
/// The full-screen Background gradient program.
extern const char* const kBackgroundVertexShader;
extern const char* const kBackgroundFragmentShader;
extern const char* const kPanoramaVertexShader;
extern const char* const kPanoramaFragmentShader;

/// Maximum number of lights per shape in the surface program.
inline constexpr int kMaxLights = 8;
/// Maximum number of sky or ground colours in the background program.
inline constexpr int kMaxBackgroundColors = 16;

}  // namespace gs::render::detail
