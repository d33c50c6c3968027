// X3D ProgramShader, PackagedShader and the vertex attribute nodes (X3D 4.0 clause 31.4):
// ShaderPrograms linked as one GL program with their own fields as uniforms, a
// PackagedShader passed over with a warning, FloatVertexAttribute and
// Matrix4VertexAttribute values reaching the shader per vertex; drawn off-screen at
// 64x64.
#include "geometry/geometry.hpp"
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <string>

namespace fs = std::filesystem;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// A world with one square filling the view from (0, 0, 1) (points 0 and 1 at the bottom,
/// 2 and 3 at the top), emissive blue, its Appearance's shaders `shaders` and its
/// IndexedFaceSet's `attrib` field `attrib`.
fs::path programShaderWorld(const std::string& name, const std::string& shaders,
                            const std::string& attrib = "") {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V3.3 utf8
PROFILE Interchange
COMPONENT Shaders:1
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance {
    material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 }
    shaders [ )" + shaders +
                      R"( ]
  }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] )" +
                      attrib + R"( } } }
)");
  return file;
}

/// A vertex program (castle's names) passing the attribute `attribute` (declared as
/// `declaration`) to the fragment program as the varying vec4 `c` by `expression`.
std::string attributeVertexProgram(const std::string& declaration, const std::string& expression) {
  return R"(ShaderProgram { type "VERTEX" url "data:text/plain,
      uniform mat4 castle_ModelViewMatrix;
      uniform mat4 castle_ProjectionMatrix;
      attribute vec4 castle_Vertex;
      )" +
         declaration + R"(
      varying vec4 c;
      void main(void) {
        c = )" +
         expression + R"(;
        gl_Position = castle_ProjectionMatrix * (castle_ModelViewMatrix * castle_Vertex);
      }" })";
}

const std::string kVaryingFragment = R"(ShaderProgram { type "FRAGMENT" url "data:text/plain,
      varying vec4 c;
      void main(void) { gl_FragColor = c; }" })";

}  // namespace

TEST_CASE("A ProgramShader links its vertex and fragment programs, their fields as uniforms",
          "[render][offscreen][world][shaders]") {
  // The vertex program's `shrink` (0.5) draws the square at half size; the fragment
  // program's `tint` colours it.
  const Rendered r = renderFile(programShaderWorld("program_shader", R"(
    ProgramShader { language "GLSL" programs [
      ShaderProgram { type "VERTEX"
        initializeOnly SFFloat shrink 0.5
        url "data:text/plain,
          uniform mat4 castle_ModelViewMatrix;
          uniform mat4 castle_ProjectionMatrix;
          uniform float shrink;
          attribute vec4 castle_Vertex;
          void main(void) {
            vec4 p = vec4(castle_Vertex.xy * shrink, castle_Vertex.zw);
            gl_Position = castle_ProjectionMatrix * (castle_ModelViewMatrix * p);
          }" }
      ShaderProgram { type "FRAGMENT"
        inputOutput SFColor tint 1 0.5 0
        url "data:text/plain,
          uniform vec3 tint;
          void main(void) { gl_FragColor = vec4(tint, 1.0); }" }
    ] })"));
  CHECK(r.diagnostics.items.empty());
  CHECK(gs::test::close(r.image.pixel(32, 32), 255, 128, 0, 4));  // the tint
  CHECK(gs::test::close(r.image.pixel(3, 3), 0, 0, 0, 4));        // outside the half-size square
  CHECK(gs::test::close(r.image.pixel(60, 60), 0, 0, 0, 4));
}

TEST_CASE("A ProgramShader that does not compile, or lacks a stage, leaves the built-in shading",
          "[render][offscreen][world][shaders]") {
  const Rendered r = renderFile(programShaderWorld(
      "program_shader_broken",
      "ProgramShader { programs [ " + attributeVertexProgram("", "vec4(1.0)") + R"(
        ShaderProgram { type "FRAGMENT" url "data:text/plain,
          void main(void) { gl_FragColor = undeclared; }" } ] })"));
  REQUIRE(r.diagnostics.items.size() == 1);
  const std::string& message = r.diagnostics.items[0].message;
  CHECK(message.find("ProgramShader not used") != std::string::npos);
  CHECK(message.find("FRAGMENT program") != std::string::npos);
  CHECK(message.find("undeclared") != std::string::npos);
  CHECK(gs::test::close(r.image.pixel(32, 32), 0, 0, 255, 4));  // the Material's emissive blue
  // Without a FRAGMENT program: one warning, the built-in shading.
  const Rendered vertexOnly = renderFile(programShaderWorld(
      "program_shader_vertex_only",
      "ProgramShader { programs [ " + attributeVertexProgram("", "vec4(1.0)") + " ] }"));
  REQUIRE(vertexOnly.diagnostics.items.size() == 1);
  CHECK(vertexOnly.diagnostics.items[0].message.find("no FRAGMENT ShaderProgram") !=
        std::string::npos);
  CHECK(gs::test::close(vertexOnly.image.pixel(32, 32), 0, 0, 255, 4));
}

TEST_CASE("A PackagedShader is passed over with one warning for the next shader of the list",
          "[render][offscreen][world][shaders]") {
  const Rendered r = renderFile(programShaderWorld("packaged_shader", R"(
    PackagedShader { language "Cg" url "data:text/plain,whatever" }
    ComposedShader { language "GLSL" parts [
      ShaderPart { type "VERTEX" url "data:text/plain,
        uniform mat4 castle_ModelViewMatrix;
        uniform mat4 castle_ProjectionMatrix;
        attribute vec4 castle_Vertex;
        void main(void) {
          gl_Position = castle_ProjectionMatrix * (castle_ModelViewMatrix * castle_Vertex);
        }" }
      ShaderPart { type "FRAGMENT" url "data:text/plain,
        void main(void) { gl_FragColor = vec4(0.0, 1.0, 0.0, 1.0); }" } ] })"),
                                2);  // the second frame does not repeat the warning
  REQUIRE(r.diagnostics.items.size() == 1);
  const std::string& message = r.diagnostics.items[0].message;
  CHECK(message.find("PackagedShader not used") != std::string::npos);
  CHECK(message.find("\"Cg\"") != std::string::npos);
  CHECK(gs::test::close(r.image.pixel(32, 32), 0, 255, 0, 4));  // the ComposedShader's green
}

TEST_CASE("Vertex attribute nodes follow the coordinates onto the mesh's vertices",
          "[vrml][geometry][shaders]") {
  // An ElevationGrid's FloatVertexAttribute value i belongs to grid point i: vertex v
  // takes the value of pointIndices[v], whatever order the tessellator made them in.
  const fs::path file = worldDir() / "attributes_mesh.x3dv";
  writeText(file, R"(#X3D V3.3 utf8
PROFILE Interchange
COMPONENT Shaders:1
Shape { geometry ElevationGrid { xDimension 2 zDimension 2 height [0 0 0 0]
  attrib [ FloatVertexAttribute { name "two" numComponents 2 value [0 10, 1 11, 2 12, 3 13] }
           FloatVertexAttribute { name "bad" numComponents 5 value [1 2 3 4 5] }
           Matrix3VertexAttribute { name "m" value [1 0 0 0 1 0 0 0 1] } ] } }
)");
  const gs::vrml::Scene scene = gs::vrml::loadVrmlFile(file.string());
  const gs::vrml::NodePtr& grid = scene.rootNodes.at(0)->sfnode("geometry");
  REQUIRE(grid != nullptr);
  gs::vrml::Diagnostics diag;
  const gs::vrml::Mesh m = gs::vrml::tessellate(*grid, &diag);
  REQUIRE(m.positions.size() == 4);
  REQUIRE(m.pointIndices.size() == 4);
  REQUIRE(m.attributes.size() == 2);  // "bad" (numComponents 5) is left out
  const gs::vrml::VertexAttribute& two = m.attributes[0];
  CHECK(two.name == "two");
  CHECK(two.components == 2);
  for (std::size_t v = 0; v < 4; ++v) {
    const std::uint32_t p = m.pointIndices[v];
    // Grid point p = i + j * 2 lies at x = i, z = j.
    CHECK(m.positions[v].x == static_cast<float>(p % 2));
    CHECK(m.positions[v].z == static_cast<float>(p / 2));
    CHECK(two.values[2 * v] == static_cast<float>(p));
    CHECK(two.values[2 * v + 1] == static_cast<float>(10 + p));
  }
  // The matrix attribute has one value for 4 points: the other 3 are 0, reported; with
  // the numComponents warning, one diagnostic for the node (the first problem + a count).
  CHECK(m.attributes[1].components == 9);
  REQUIRE(diag.items.size() == 1);
  CHECK(diag.items[0].message.find("numComponents 5") != std::string::npos);
  // A change of an attribute node makes the geometry's mesh stale.
  const std::uint64_t before = gs::vrml::revisionWithFields(*grid);
  grid->mfnode("attrib").at(0)->markChanged();
  CHECK(gs::vrml::revisionWithFields(*grid) != before);
}

TEST_CASE("The XML encoding's ProgramShader (CDATA) feeds an IndexedTriangleSet's attribute",
          "[render][offscreen][world][shaders]") {
  // X_ITE's names; the attribute h is 0 on the left points and 1 on the right ones, the
  // fragment program's field c (orange) scaled by it.
  const fs::path file = worldDir() / "program_shader_xml.x3d";
  writeText(file, R"(<?xml version="1.0" encoding="UTF-8"?>
<X3D profile='Interchange' version='4.0'>
<head><component name='Shaders' level='1'/></head>
<Scene>
<NavigationInfo headlight='false'/>
<Viewpoint position='0 0 1' fieldOfView='1.5708'/>
<Shape>
 <Appearance>
  <Material diffuseColor='0 0 1'/>
  <ProgramShader language='GLSL'>
   <ShaderProgram containerField='programs' type='VERTEX'><![CDATA[
uniform mat4 x3d_ModelViewMatrix; uniform mat4 x3d_ProjectionMatrix;
attribute vec4 x3d_Vertex; attribute float h; varying float v;
void main() { v = h; gl_Position = x3d_ProjectionMatrix * x3d_ModelViewMatrix * x3d_Vertex; }
]]></ShaderProgram>
   <ShaderProgram containerField='programs' type='FRAGMENT'>
    <field name='c' type='SFColor' accessType='inputOutput' value='1 0.5 0'/><![CDATA[
uniform vec3 c; varying float v;
void main() { gl_FragColor = vec4(c * v, 1.0); }
]]></ShaderProgram>
  </ProgramShader>
 </Appearance>
 <IndexedTriangleSet index='0 1 2 0 2 3'>
  <Coordinate point='-1 -1 0 1 -1 0 1 1 0 -1 1 0'/>
  <FloatVertexAttribute containerField='attrib' name='h' numComponents='1' value='0 1 1 0'/>
 </IndexedTriangleSet>
</Shape>
</Scene>
</X3D>
)");
  const Rendered r = renderFile(file);
  CHECK(r.diagnostics.items.empty());
  // The square spans the view: x = 32 is halfway (v = 0.5), x = 1 nearly 0, x = 62 nearly 1.
  CHECK(gs::test::close(r.image.pixel(32, 32), 128, 64, 0, 6));
  CHECK(gs::test::close(r.image.pixel(1, 32), 6, 3, 0, 6));
  CHECK(gs::test::close(r.image.pixel(62, 32), 250, 125, 0, 6));
}

TEST_CASE("A FloatVertexAttribute colours the vertices through the shader",
          "[render][offscreen][world][shaders]") {
  // Per point an RGB colour: the bottom points red, the top points blue.
  const Rendered r = renderFile(
      programShaderWorld("float_vertex_attribute",
                         "ProgramShader { programs [ " +
                             attributeVertexProgram("attribute vec3 rgb;", "vec4(rgb, 1.0)") +
                             kVaryingFragment + " ] }",
                         R"(attrib FloatVertexAttribute { name "rgb" numComponents 3
           value [1 0 0, 1 0 0, 0 0 1, 0 0 1] })"));
  CHECK(r.diagnostics.items.empty());
  const std::uint8_t* bottom = r.image.pixel(32, 62);  // rows top to bottom
  const std::uint8_t* top = r.image.pixel(32, 1);
  const std::uint8_t* middle = r.image.pixel(32, 32);
  CHECK(bottom[0] > 240);
  CHECK(bottom[2] < 15);
  CHECK(top[0] < 15);
  CHECK(top[2] > 240);
  CHECK(gs::test::close(middle, 128, 0, 128, 8));  // halfway: interpolated per vertex
}

TEST_CASE("A Matrix4VertexAttribute reaches the shader as a mat4 attribute",
          "[render][offscreen][world][shaders]") {
  // The matrix's floats in file order reach the shader's columns, as X_ITE passes them
  // (create3000's Shaders/Matrix3VertexAttribute.x3d "must show a 2x2 rectangle"): the
  // file's third row (0, 1, 0, 1) is the shader's m[2], green.
  const std::string matrix = "1 0 0 0  0 0 0 0  0 1 0 1  0 0 0 0";
  const Rendered r = renderFile(programShaderWorld(
      "matrix4_vertex_attribute",
      "ProgramShader { programs [ " + attributeVertexProgram("attribute mat4 m;", "m[2]") +
          kVaryingFragment + " ] }",
      "attrib Matrix4VertexAttribute { name \"m\" value [" + matrix + ", " + matrix + ", " +
          matrix + ", " + matrix + "] }"));
  CHECK(r.diagnostics.items.empty());
  CHECK(gs::test::close(r.image.pixel(32, 32), 0, 255, 0, 4));
  CHECK(gs::test::close(r.image.pixel(5, 58), 0, 255, 0, 4));
}

TEST_CASE("castle's shader worlds load and draw without a diagnostic",
          "[render][offscreen][world][shaders][corpus]") {
  if (!gs::test::haveCorpus("x3d/castle/shaders")) return;
  for (const char* world : {"attributes.x3dv", "shaders.x3dv", "shaders_inlined.x3dv"}) {
    INFO(world);
    const fs::path file = gs::test::corpusDir() / "x3d/castle/shaders" / world;
    const gs::vrml::Scene scene = gs::vrml::loadVrmlFile(file.string());
    std::string loaded, drawn;
    for (const auto& d : scene.diagnostics.items) loaded += d.format() + "\n";
    CHECK(loaded.empty());
    const Rendered r = renderFile(file);
    for (const auto& d : r.diagnostics.items) drawn += d.format() + "\n";
    CHECK(drawn.empty());
  }
}
