#include "scene/layout.hpp"

#include "scene/node_access.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace gs::scene {

namespace {

// One word of an MFString for axis `axis`: the second for y when given, else the first.
const std::string* word(const std::vector<std::string>& words, int axis) {
  if (words.empty()) return nullptr;
  return &words[std::min<std::size_t>(static_cast<std::size_t>(axis), words.size() - 1)];
}

LayoutUnit unitOf(const std::string* w) {
  if (w == nullptr) return LayoutUnit::world;
  if (*w == "FRACTION") return LayoutUnit::fraction;
  if (*w == "PIXEL") return LayoutUnit::pixel;
  return LayoutUnit::world;
}

float valueOf(const std::vector<float>& values, int axis, float fallback) {
  if (values.empty()) return fallback;
  return values[std::min<std::size_t>(static_cast<std::size_t>(axis), values.size() - 1)];
}

enum class ScaleMode { none, fraction, stretch, pixel };

ScaleMode scaleModeOf(const std::string* w) {
  if (w == nullptr) return ScaleMode::none;
  if (*w == "FRACTION") return ScaleMode::fraction;
  if (*w == "STRETCH") return ScaleMode::stretch;
  if (*w == "PIXEL") return ScaleMode::pixel;
  return ScaleMode::none;
}

}  // namespace

LayoutPlacement placeLayout(const vrml::Node& layout, const LayoutRectangle& parent) {
  const auto& align = mfString(layout, "align");
  const auto& offsetUnits = mfString(layout, "offsetUnits");
  const auto& sizeUnits = mfString(layout, "sizeUnits");
  const auto& scaleModes = mfString(layout, "scaleMode");
  const auto& offset = mfFloat(layout, "offset");
  const auto& size = mfFloat(layout, "size");
  LayoutPlacement p;
  std::array<ScaleMode, 2> mode{};
  for (int a = 0; a < 2; ++a) {
    const auto i = static_cast<std::size_t>(a);
    // WORLD: the parent's unit (FRACTION at the top).
    LayoutUnit su = unitOf(word(sizeUnits, a));
    if (su == LayoutUnit::world) su = parent.sizeUnits[i];
    LayoutUnit ou = unitOf(word(offsetUnits, a));
    if (ou == LayoutUnit::world) ou = parent.offsetUnits[i];
    p.rectangle.sizeUnits[i] = su;
    p.rectangle.offsetUnits[i] = ou;
    const float s = valueOf(size, a, 1.0f);
    const float rect = su == LayoutUnit::pixel ? s * parent.metresPerPixel[a] : s * parent.size[a];
    p.rectangle.size[a] = rect;
    p.rectangle.metresPerPixel[a] = parent.metresPerPixel[a];
    // Align: LEFT / BOTTOM and RIGHT / TOP put the rectangle against the parent's side.
    const std::string* al = word(align, a);
    float t = 0.0f;
    if (al != nullptr && (*al == (a == 0 ? "LEFT" : "BOTTOM"))) t = -(parent.size[a] - rect) / 2;
    if (al != nullptr && (*al == (a == 0 ? "RIGHT" : "TOP"))) t = (parent.size[a] - rect) / 2;
    const float o = valueOf(offset, a, 0.0f);
    t += ou == LayoutUnit::pixel ? o * parent.metresPerPixel[a] : o * parent.size[a];
    p.translation[a] = t;
    mode[i] = scaleModeOf(word(scaleModes, a));
    if (parent.top && mode[i] == ScaleMode::none) mode[i] = ScaleMode::fraction;
    switch (mode[i]) {
      case ScaleMode::none:
        p.keepScale[i] = true;
        break;
      case ScaleMode::fraction:
        p.scale[a] = rect;
        break;
      case ScaleMode::pixel:
        p.scale[a] = parent.metresPerPixel[a];
        break;
      case ScaleMode::stretch:
        break;
    }
  }
  p.rectangle.top = false;
  const bool sx = mode[0] == ScaleMode::stretch, sy = mode[1] == ScaleMode::stretch;
  if (sx && sy) {
    p.scale.x = p.scale.y = std::max(p.rectangle.size.x, p.rectangle.size.y);
  } else if (sx) {
    p.scale.x = p.scale.y;
    p.keepScale[0] = p.keepScale[1];
  } else if (sy) {
    p.scale.y = p.scale.x;
    p.keepScale[1] = p.keepScale[0];
  }
  return p;
}

LayoutRectangle viewRectangle(glm::vec2 pixels, float smallerSide) {
  LayoutRectangle r;
  const glm::vec2 px = glm::max(pixels, glm::vec2(1.0f));
  const float perPixel = smallerSide / std::min(px.x, px.y);
  r.size = px * perPixel;
  r.metresPerPixel = glm::vec2(perPixel);
  return r;
}

}  // namespace gs::scene
