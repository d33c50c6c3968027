// The X3D browser options TextureQuality and Shading (browser_options.hpp).
#include "render/browser_options.hpp"

#include "gl_program.hpp"
#include "multi_texture.hpp"
#include "render/image.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>
#include <utility>

namespace gs::render {

namespace {

bool equalsIgnoringCase(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

/// The value whose name equals `name` in any case, into `out`; false when none does.
template <typename Value, std::size_t N>
bool parseName(std::string_view name, const std::pair<const char*, Value> (&names)[N], Value& out) {
  for (const auto& [text, value] : names)
    if (equalsIgnoringCase(name, text)) {
      out = value;
      return true;
    }
  return false;
}

}  // namespace

bool parseTextureQuality(std::string_view name, TextureQuality& out) {
  static constexpr std::pair<const char*, TextureQuality> kNames[] = {
      {"low", TextureQuality::low},
      {"medium", TextureQuality::medium},
      {"high", TextureQuality::high}};
  return parseName(name, kNames, out);
}

bool parseShadingOption(std::string_view name, ShadingOption& out) {
  static constexpr std::pair<const char*, ShadingOption> kNames[] = {
      {"point", ShadingOption::point},         {"pointset", ShadingOption::point},
      {"wireframe", ShadingOption::wireframe}, {"flat", ShadingOption::flat},
      {"gouraud", ShadingOption::gouraud},     {"phong", ShadingOption::phong}};
  return parseName(name, kNames, out);
}

std::string_view shadingName(ShadingOption shading) {
  switch (shading) {
    case ShadingOption::point:
      return "POINT";
    case ShadingOption::wireframe:
      return "WIREFRAME";
    case ShadingOption::flat:
      return "FLAT";
    case ShadingOption::gouraud:
      return "GOURAUD";
    case ShadingOption::phong:
      break;
  }
  return "PHONG";
}

bool textureAfterLighting(ShadingOption shading, std::string_view x3dVersion) {
  if (shading != ShadingOption::gouraud) return false;
  if (x3dVersion.empty()) return true;                                  // VRML97
  return std::strtod(std::string(x3dVersion).c_str(), nullptr) < 3.35;  // "3.3" and older
}

RenderingLimits renderingLimits() {
  return {kMaxImageSide, detail::kMaxTextureStages, detail::kMaxLights};
}

}  // namespace gs::render
