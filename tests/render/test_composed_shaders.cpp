// X3D ComposedShader (X3D 4.0 clause 31): OpenGL 2 GLSL translated to 3.30 core, the
// shader's fields as uniforms, failures falling back to the built-in shading; drawn
// off-screen at 64x64.
#include "../../render/src/composed_shaders.hpp"
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <string>

namespace fs = std::filesystem;
using gs::render::detail::ShaderStage;
using gs::render::detail::translateGlsl;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// A square filling the view from (0, 0, 1), emissive blue, drawn by a ComposedShader with
/// castle-model-viewer's vertex names, fragment shader body `fragment` and the extra
/// shader fields `fields`.
fs::path shaderWorld(const std::string& name, const std::string& fragment,
                     const std::string& fields) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Interchange
COMPONENT Shaders:1
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance {
    material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 }
    shaders ComposedShader {
      language "GLSL"
      )" + fields + R"(
      parts [
        ShaderPart { type "VERTEX" url "data:text/plain,
          uniform mat4 castle_ModelViewMatrix;
          uniform mat4 castle_ProjectionMatrix;
          attribute vec4 castle_Vertex;
          varying vec2 position;
          void main(void) {
            position = castle_Vertex.xy;
            gl_Position = castle_ProjectionMatrix * (castle_ModelViewMatrix * castle_Vertex);
          }" }
        ShaderPart { type "FRAGMENT" url "data:text/plain,
          varying vec2 position;
          )" + fragment +
                      R"(" }
      ]
    }
  }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } }
)");
  return file;
}

int linesOf(const std::string& s) {
  return static_cast<int>(std::count(s.begin(), s.end(), '\n'));
}

}  // namespace

TEST_CASE("translateGlsl maps OpenGL 2 GLSL onto 3.30 core and keeps line numbers",
          "[render][shaders]") {
  const std::string vertex = "#version 120\nvoid main() { gl_Position = ftransform(); }\n";
  const std::string v = translateGlsl(vertex, ShaderStage::vertex);
  CHECK(v.starts_with("#version 330 core\n"));
  CHECK(v.find("#define attribute in") != std::string::npos);
  CHECK(v.find("#define varying out") != std::string::npos);
  CHECK(v.find("in vec4 gs_Vertex;") != std::string::npos);
  CHECK(v.find("uniform mat4 gs_ModelViewProjectionMatrix;") != std::string::npos);
  CHECK(v.find("#version 120") == std::string::npos);
  // The body after "#line 1" has the source's lines.
  CHECK(linesOf(v.substr(v.find("#line 1\n") + 8)) == linesOf(vertex));
  // Only what is used is declared.
  CHECK(v.find("gs_Normal") == std::string::npos);

  const std::string fragment =
      "#extension GL_OES_standard_derivatives : enable\nvarying vec3 n;\n"
      "void main() { gl_FragColor = texture2D(t, n.xy) * gl_Color; }\n";
  const std::string f = translateGlsl(fragment, ShaderStage::fragment);
  CHECK(f.find("#define varying in") != std::string::npos);
  CHECK(f.find("out vec4 gs_FragColor;") != std::string::npos);
  CHECK(f.find("#define texture2D texture") != std::string::npos);
  CHECK(f.find("in vec4 gs_FrontColor;\n#define gl_Color gs_FrontColor") != std::string::npos);
  // The extension comes before every declaration, and its line is blank in the body.
  CHECK(f.find("#extension GL_OES") < f.find("#define"));
  CHECK(f.find("#extension", f.find("#line 1")) == std::string::npos);

  // GLSL 3.30 and later is left as written.
  const std::string modern = "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1); }\n";
  CHECK(translateGlsl(modern, ShaderStage::fragment) == modern);
}

TEST_CASE("A ComposedShader draws the shape with its fields as uniforms",
          "[render][offscreen][world][shaders]") {
  // An SFColor field and an SFNode texture field; the left half shows the colour, the
  // right half the texture.
  const Rendered r = renderFile(
      shaderWorld("shader_fields",
                  "uniform vec3 my_color; uniform sampler2D my_texture;\n"
                  "void main(void) { gl_FragColor = position.x < 0.0 ? vec4(my_color, 1.0)\n"
                  "  : texture2D(my_texture, vec2(0.5)); }",
                  "inputOutput SFColor my_color 0 1 0\n"
                  "inputOutput SFNode my_texture PixelTexture { image 1 1 3 0xFF0000 }"));
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(10, 32), 0, 255, 0, 4));
  CHECK(close(r.image.pixel(54, 32), 255, 0, 0, 4));
  // MF fields become uniform arrays; doubles are given as floats.
  const Rendered arrays =
      renderFile(shaderWorld("shader_arrays",
                             "uniform float a[2]; uniform vec3 d;\n"
                             "void main(void) { gl_FragColor = vec4(a[0], a[1], d.z, 1.0); }",
                             "initializeOnly MFFloat a [1 0.5] initializeOnly SFVec3d d 0 0 0.25"));
  CHECK(close(arrays.image.pixel(32, 32), 255, 128, 64, 4));
  // A matrix field's values in file order fill the shader matrix column by column, as
  // X_ITE passes them: the file's first row (0 0 1) is m[0], blue.
  const Rendered matrix =
      renderFile(shaderWorld("shader_matrix",
                             "uniform mat3 m;\n"
                             "void main(void) { gl_FragColor = vec4(m[0], 1.0); }",
                             "initializeOnly SFMatrix3f m 0 0 1  0 0 0  0 0 0"));
  CHECK(matrix.diagnostics.items.empty());
  CHECK(close(matrix.image.pixel(32, 32), 0, 0, 255, 4));
}

TEST_CASE("A ComposedShader that does not compile leaves the built-in shading, with a warning",
          "[render][offscreen][world][shaders]") {
  const Rendered r = renderFile(
      shaderWorld("shader_broken", "void main(void) { gl_FragColor = undeclared; }", ""));
  REQUIRE(r.diagnostics.items.size() == 1);
  const std::string& message = r.diagnostics.items[0].message;
  CHECK(message.find("ComposedShader not used") != std::string::npos);
  CHECK(message.find("FRAGMENT") != std::string::npos);
  CHECK(message.find("undeclared") != std::string::npos);
  CHECK(close(r.image.pixel(32, 32), 0, 0, 255, 4));  // the Material's emissive blue
  // Another language is not tried: the Material draws, without a warning.
  const fs::path hlsl = worldDir() / "shader_hlsl.x3dv";
  writeText(hlsl, R"(#X3D V3.2 utf8
PROFILE Interchange
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 }
    shaders ComposedShader { language "HLSL" parts ShaderPart { type "FRAGMENT" url "x.hlsl" } } }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } }
)");
  const Rendered other = renderFile(hlsl);
  CHECK(other.diagnostics.items.empty());
  CHECK(close(other.image.pixel(32, 32), 0, 0, 255, 4));
}

TEST_CASE("Shaders say whether they compiled and which one the Appearance draws with",
          "[render][offscreen][world][shaders]") {
  // X3D 4.0 clause 31.3.1: the first shader does not compile (isValid FALSE), the second
  // is selected (isValid and isSelected TRUE); the third is never tried.
  const fs::path file = worldDir() / "shader_selection.x3dv";
  writeText(file, R"(#X3D V4.0 utf8
PROFILE Immersive
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance { material Material { emissiveColor 0 0 1 }
    shaders [
      DEF Broken ComposedShader { language "GLSL" parts ShaderPart { type "FRAGMENT"
        url "data:text/plain,void main(void) { gl_FragColor = undeclared; }" } }
      DEF Green ComposedShader { language "GLSL" parts [
        ShaderPart { type "VERTEX" url "data:text/plain,void main(void) { gl_Position = ftransform(); }" }
        ShaderPart { type "FRAGMENT"
          url "data:text/plain,void main(void) { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }" } ] }
      DEF Spare ComposedShader { language "GLSL" parts ShaderPart { type "FRAGMENT"
        url "data:text/plain,void main(void) { gl_FragColor = vec4(1.0); }" } }
    ] }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } }
)");
  const Rendered r = renderFile(file, 3);
  for (const auto& d : r.diagnostics.items) INFO(d.format());
  CHECK(r.diagnostics.items.size() == 1);
  CHECK(close(r.image.pixel(32, 32), 0, 255, 0, 4));
  CHECK(r.outputs == std::vector<std::string>{"Broken.isValid=FALSE", "Green.isValid=TRUE",
                                              "Green.isSelected=TRUE"});
}

TEST_CASE("castle's shader type test: every field type reaches its uniform",
          "[render][offscreen][world][shaders][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/shaders")) return;
  // types.fs paints a column white when its uniform has the value the world gives it and
  // red otherwise, for 36 columns (every SF and MF type).
  const Rendered r = renderFile(gs::test::corpusDir() / "x3d/castle/shaders/types_test.x3dv");
  int white = 0;
  for (int x = 0; x < gs::test::kWorldSize; ++x)
    white += close(r.image.pixel(x, 32), 255, 255, 255, 4) ? 1 : 0;
  CHECK(white == gs::test::kWorldSize);
}

TEST_CASE(
    "X_ITE's shader built-ins: x3d_Max constants, x3d_TexCoord0, the texture and its "
    "matrix",
    "[render][offscreen][world][shaders]") {
  // As create3000's Texturing3D/Volume.x3d writes them (#version 300 es): a 2 x 1 x 1
  // PixelTexture3D, red | green, sampled at x3d_TextureMatrix[0] * x3d_TexCoord0, whose
  // TextureTransform3D flips s (s' = -(s - 1), clause 33.4.9), so the left half of the
  // square shows green.
  const fs::path file = worldDir() / "xite_builtins.x3dv";
  writeText(file, R"(#X3D V3.3 utf8
PROFILE Immersive
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance {
    texture PixelTexture3D { image [ 3 2 1 1 0xFF0000 0x00FF00 ] }
    textureTransform TextureTransform3D { scale -1 1 1 translation -1 0 0 }
    shaders ComposedShader {
      language "GLSL"
      parts [
        ShaderPart { type "VERTEX" url "data:x-shader/x-vertex,#version 300 es
          precision mediump float;
          uniform mat4 x3d_ProjectionMatrix;
          uniform mat4 x3d_ModelViewMatrix;
          uniform mat4 x3d_TextureMatrix [1];
          in vec4 x3d_Vertex;
          in vec4 x3d_TexCoord0;
          out vec4 texCoord;
          void main () {
            texCoord = x3d_TextureMatrix [0] * x3d_TexCoord0;
            gl_Position = x3d_ProjectionMatrix * x3d_ModelViewMatrix * x3d_Vertex;
          }" }
        ShaderPart { type "FRAGMENT" url "data:x-shader/x-fragment,#version 300 es
          precision mediump float;
          precision mediump sampler3D;
          uniform int x3d_NumTextures;
          uniform sampler3D x3d_Texture3D [1];
          uniform vec4 x3d_ClipPlane [x3d_MaxClipPlanes];
          in vec4 texCoord;
          out vec4 x3d_FragColor;
          void main () {
            if (x3d_NumTextures != 1) discard;
            x3d_FragColor = texture (x3d_Texture3D [0], texCoord.stp / texCoord.q);
          }" }
      ]
    }
  }
  geometry QuadSet {
    coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    texCoord TextureCoordinate3D { point [0 0 0.5, 1 0 0.5, 1 1 0.5, 0 1 0.5] }
  } } }
)");
  const Rendered r = renderFile(file);
  INFO(r.diagnostics.items.size());
  CHECK(r.diagnostics.items.empty());
  CHECK(close(r.image.pixel(10, 32), 0, 255, 0, 8));
  CHECK(close(r.image.pixel(54, 32), 255, 0, 0, 8));
}
