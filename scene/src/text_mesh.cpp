// Text (6.47) as triangles: layout from formats/, glyph outlines triangulated by
// vrml::triangulateOutline (ear clipping with holes bridged), cached per face and glyph.
#include "scene/text_mesh.hpp"

#include "scene/node_access.hpp"

#include <map>
#include <memory>
#include <mutex>
#include <tuple>

namespace gs::scene {

namespace {

struct GlyphMesh {
  std::vector<glm::vec2> positions;  // font units
  std::vector<std::uint32_t> indices;
};

std::mutex gCacheMutex;
std::map<std::tuple<const void*, std::uint32_t, std::uint32_t>, std::shared_ptr<const GlyphMesh>>
    gGlyphMeshes;

std::shared_ptr<const GlyphMesh> glyphMesh(formats::FontLibrary& fonts, formats::GlyphKey key) {
  const auto k = std::make_tuple(static_cast<const void*>(&fonts), key.face, key.glyph);
  {
    const std::lock_guard lock(gCacheMutex);
    if (auto it = gGlyphMeshes.find(k); it != gGlyphMeshes.end()) return it->second;
  }
  auto mesh = std::make_shared<GlyphMesh>();
  const formats::GlyphOutline& outline = fonts.outline(key);
  std::vector<glm::vec3> points;
  for (const formats::GlyphRegion& region : outline.regions) {
    points.clear();
    for (glm::vec2 p : region.points) points.emplace_back(p, 0.0f);
    const vrml::Mesh m = vrml::triangulateOutline(points, region.loopLengths);
    const auto base = static_cast<std::uint32_t>(mesh->positions.size());
    for (const glm::vec3& p : m.positions) mesh->positions.emplace_back(p);
    for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
      std::uint32_t a = m.indices[t], b = m.indices[t + 1], c = m.indices[t + 2];
      const glm::vec2 pa(m.positions[a]), pb(m.positions[b]), pc(m.positions[c]);
      const glm::vec2 u = pb - pa, v = pc - pa;
      if (u.x * v.y - u.y * v.x < 0.0f) std::swap(b, c);  // counter-clockwise seen from +Z
      mesh->indices.insert(mesh->indices.end(), {base + a, base + b, base + c});
    }
  }
  const std::lock_guard lock(gCacheMutex);
  return gGlyphMeshes.try_emplace(k, std::move(mesh)).first->second;
}

}  // namespace

formats::TextStyle textStyleOf(const vrml::Node& text, vrml::Diagnostics* diag) {
  formats::TextStyle style;
  style.length = mfFloat(text, "length");
  style.maxExtent = sfFloat(text, "maxExtent", 0.0f);
  const vrml::NodePtr fs = text.sfnode("fontStyle");
  if (!fs) return style;
  style.family = mfString(*fs, "family");
  if (fs->field("family") == nullptr) style.family = {"SERIF"};
  style.style = fs->field("style") ? sfString(*fs, "style") : std::string("PLAIN");
  style.language = sfString(*fs, "language");
  // X3D Layout's ScreenFontStyle (clause 36.4.5) gives `pointSize` instead: points of
  // 4/3 pixel (CSS's), in a ScreenGroup's pixel units.
  style.size = fs->typeId() == vrml::NodeTypeId::ScreenFontStyle
                   ? sfFloat(*fs, "pointSize", 12.0f) * (4.0f / 3.0f)
                   : sfFloat(*fs, "size", 1.0f);
  style.spacing = sfFloat(*fs, "spacing", 1.0f);
  style.horizontal = sfBool(*fs, "horizontal", true);
  style.leftToRight = sfBool(*fs, "leftToRight", true);
  style.topToBottom = sfBool(*fs, "topToBottom", true);
  std::vector<std::string> justify = {"BEGIN"};
  if (fs->field("justify") != nullptr) justify = mfString(*fs, "justify");
  std::string unknown;
  formats::parseJustify(justify, style.major, style.minor, &unknown);
  if (!unknown.empty() && diag != nullptr)
    diag->warning(fs->location, "FontStyle: unknown justify value \"" + unknown + "\"");
  return style;
}

vrml::Mesh tessellateText(const vrml::Node& text, vrml::Diagnostics* diag,
                          formats::FontLibrary& fonts) {
  vrml::Mesh mesh;
  mesh.solid = false;
  const formats::TextStyle style = textStyleOf(text, diag);
  const formats::TextLayout layout = fonts.layout(mfString(text, "string"), style);
  if (diag != nullptr)
    for (const std::string& w : layout.warnings) diag->warning(text.location, w);
  const float unit = layout.textureUnit > 0.0f ? 1.0f / layout.textureUnit : 1.0f;
  for (const formats::PlacedGlyph& g : layout.glyphs) {
    const std::shared_ptr<const GlyphMesh> gm = glyphMesh(fonts, g.key);
    if (gm->indices.empty()) continue;
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (glm::vec2 p : gm->positions) {
      const glm::vec2 q = g.origin + g.scale * p;
      mesh.positions.emplace_back(q, 0.0f);
      mesh.normals.emplace_back(0.0f, 0.0f, 1.0f);
      mesh.texCoords.push_back((q - layout.textureOrigin) * unit);
      mesh.bounds.extend(glm::vec3(q, 0.0f));
    }
    for (std::uint32_t i : gm->indices) mesh.indices.push_back(base + i);
  }
  // The bounding box is the lines' layout boxes (advance by ascender..descender), not just
  // the glyphs' ink, as castle-model-viewer's: it frames the same camera on a Text world
  // (docs/castle-comparison.md).
  if (!mesh.indices.empty() && !layout.bounds.empty()) {
    mesh.bounds.extend(glm::vec3(layout.bounds.min, 0.0f));
    mesh.bounds.extend(glm::vec3(layout.bounds.max, 0.0f));
  }
  return mesh;
}

vrml::Mesh tessellateGeometry(const vrml::Node& geometry, vrml::Diagnostics* diag,
                              float nurbsTessellationScale) {
  if (geometry.typeId() == vrml::NodeTypeId::Text) return tessellateText(geometry, diag);
  return vrml::tessellate(geometry, diag, nurbsTessellationScale);
}

std::size_t cachedGlyphMeshCount() {
  const std::lock_guard lock(gCacheMutex);
  return gGlyphMeshes.size();
}

}  // namespace gs::scene
