// World files for the render tests: written to a temporary folder, loaded by the real
// parser and drawn off-screen at kWorldSize x kWorldSize pixels by a SceneRenderer from the
// world's initial camera (test_worlds.cpp, test_multi_texture.cpp).
#pragma once

#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <catch2/catch.hpp>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace gs::test {

inline constexpr int kWorldSize = 64;

/// The folder the world files go to (with a sub/ folder), created if absent.
inline std::filesystem::path worldDir() {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gs_render_worlds";
  std::filesystem::create_directories(dir / "sub");
  return dir;
}

inline void writeText(const std::filesystem::path& p, const std::string& text) {
  std::ofstream(p) << text;
}

struct Rendered {
  render::Image image;
  vrml::Diagnostics diagnostics;  // the renderer's (the parser's are WARNed)
  /// The output events the drawing computed (SceneRenderer::takeDrawnOutputs), each as
  /// "Type.field=value" (a node's DEF name for its type when it has one), SFBool, SFInt32
  /// and SFFloat values written out (std::to_string), others as their type's name.
  std::vector<std::string> outputs;
};

/// `outputs` as Rendered::outputs writes them.
inline std::vector<std::string> drawnOutputText(const vrml::DrawnOutputs& outputs) {
  std::vector<std::string> text;
  for (const vrml::DrawnOutput& o : outputs) {
    const vrml::Node& n = *o.node.node;
    std::string value = o.value.type() == vrml::FieldType::SFBool
                            ? (o.value.get<vrml::FieldType::SFBool>() ? "TRUE" : "FALSE")
                        : o.value.type() == vrml::FieldType::SFInt32
                            ? std::to_string(o.value.get<vrml::FieldType::SFInt32>())
                        : o.value.type() == vrml::FieldType::SFFloat
                            ? std::to_string(o.value.get<vrml::FieldType::SFFloat>())
                            : std::string(vrml::fieldTypeName(o.value.type()));
    text.push_back((n.defName.empty() ? n.typeName() : n.defName) + "." + o.field + "=" + value);
  }
  return text;
}

/// Loads `file` and draws `frames` frames (the first is drawn by the generic surface
/// program, later ones by the shader variants: surface_programs.hpp), keeping the last.
/// With GS_RENDER_TEST_DUMP=DIR set, the picture is also written to DIR/<file stem>.png to
/// be looked at.
inline Rendered renderFile(const std::filesystem::path& file, int frames = 1) {
  static auto context = render::createOffscreenContext(kWorldSize, kWorldSize);
  context->makeCurrent();
  auto scene = std::make_shared<vrml::Scene>(vrml::loadVrmlFile(file.string()));
  for (const auto& d : scene->diagnostics.items) WARN(d.format());
  render::SceneRenderer r(scene);
  for (int i = 0; i < frames; ++i) r.draw(r.initialCamera(1.0f), 0, 0, kWorldSize, kWorldSize);
  Rendered out{render::readPixels(0, 0, kWorldSize, kWorldSize), r.diagnostics(),
               drawnOutputText(r.takeDrawnOutputs())};
  if (const char* dir = std::getenv("GS_RENDER_TEST_DUMP"))
    render::writePng((std::filesystem::path(dir) / (file.stem().string() + ".png")).string(),
                     out.image);
  return out;
}

/// Whether RGB pixel `p` is within `tolerance` of (r, g, b) in every channel.
inline bool close(const std::uint8_t* p, int r, int g, int b, int tolerance) {
  return std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance &&
         std::abs(p[2] - b) <= tolerance;
}

}  // namespace gs::test
