// glTF materials as X3D 4 appearance (glTF 2.0 clause 3.9; X3D 4.0 clause 12.4.10
// PhysicalMaterial, 12.4.12 UnlitMaterial, 12.4.2 Appearance alphaMode): metallic-roughness
// as PhysicalMaterial, KHR_materials_unlit as UnlitMaterial, each texture an ImageTexture
// (external images by URL, embedded ones as data: URLs), samplers as TextureProperties
// (filters, wrap modes; repeatS / repeatT too, for what reads only those).
#include "importer.hpp"

#include "base/data_url.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace gs::gltf::x3d {
namespace {

glm::vec3 rgb(const std::vector<double>& v, glm::vec3 fallback) {
  if (v.size() < 3) return fallback;
  return {static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

const tinygltf::Material* materialAt(const tinygltf::Model& m, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= m.materials.size()) return nullptr;
  return &m.materials[static_cast<std::size_t>(index)];
}

double number(const tinygltf::Value& o, const char* key, double fallback) {
  return o.Has(key) && o.Get(key).IsNumber() ? o.Get(key).GetNumberAsDouble() : fallback;
}

std::string sniffMediaType(const std::vector<unsigned char>& b) {
  if (b.size() >= 4 && b[0] == 0x89 && b[1] == 'P' && b[2] == 'N' && b[3] == 'G')
    return "image/png";
  if (b.size() >= 2 && b[0] == 0xFF && b[1] == 0xD8) return "image/jpeg";
  return "application/octet-stream";
}

}  // namespace

std::vector<int> GltfImporter::texCoordSets(int material, std::array<int, 5>* used, bool report) {
  std::array<int, 5> sets{-1, -1, -1, -1, -1};
  if (const tinygltf::Material* mat = materialAt(m_, material)) {
    const auto& pbr = mat->pbrMetallicRoughness;
    const auto of = [](int index, int texCoord) {
      return index < 0 ? -1 : std::clamp(texCoord, 0, 7);
    };
    sets = {of(pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord),
            of(pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord),
            of(mat->normalTexture.index, mat->normalTexture.texCoord),
            of(mat->emissiveTexture.index, mat->emissiveTexture.texCoord),
            of(mat->occlusionTexture.index, mat->occlusionTexture.texCoord)};
    if (mat->extensions.count("KHR_materials_unlit")) sets = {sets[0], -1, -1, -1, -1};
  }
  if (used != nullptr) *used = sets;
  std::vector<int> out{std::max(sets[0], 0)};
  std::vector<int> others;
  for (std::size_t i = 1; i < sets.size(); ++i)
    if (sets[i] >= 0 && sets[i] != out[0]) others.push_back(sets[i]);
  std::sort(others.begin(), others.end());
  others.erase(std::unique(others.begin(), others.end()), others.end());
  if (!others.empty()) out.push_back(others.front());
  if (others.size() > 1 && report)
    warn("material " + std::to_string(material) + " reads " + std::to_string(others.size() + 1) +
         " TEXCOORD sets; only two are drawn (TEXCOORD_" + std::to_string(out[0]) + " and _" +
         std::to_string(out[1]) + "), the others' textures read TEXCOORD_" +
         std::to_string(out[0]));
  return out;
}

glm::mat3 GltfImporter::uvTransform(int material) const {
  const tinygltf::Material* mat = materialAt(m_, material);
  if (mat == nullptr) return glm::mat3(1.0f);
  const auto& ext = mat->pbrMetallicRoughness.baseColorTexture.extensions;
  const auto it = ext.find("KHR_texture_transform");
  if (it == ext.end()) return glm::mat3(1.0f);
  const tinygltf::Value& t = it->second;
  auto pair = [&](const char* key, glm::vec2 fallback) {
    if (!t.Has(key) || !t.Get(key).IsArray() || t.Get(key).ArrayLen() != 2 ||
        !t.Get(key).Get(0).IsNumber() || !t.Get(key).Get(1).IsNumber())
      return fallback;
    return glm::vec2(static_cast<float>(t.Get(key).Get(0).GetNumberAsDouble()),
                     static_cast<float>(t.Get(key).Get(1).GetNumberAsDouble()));
  };
  const glm::vec2 offset = pair("offset", glm::vec2(0.0f));
  const glm::vec2 scale = pair("scale", glm::vec2(1.0f));
  const auto r = static_cast<float>(number(t, "rotation", 0.0));
  // KHR_texture_transform: uv' = T * R * S * uv, R rotating counter-clockwise in UV space.
  const glm::mat3 T(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 R(std::cos(r), -std::sin(r), 0, std::sin(r), std::cos(r), 0, 0, 0, 1);
  const glm::mat3 S(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  return T * R * S;
}

NodePtr GltfImporter::texture(int index) {
  if (index < 0) return nullptr;
  if (const auto it = textures_.find(index); it != textures_.end()) return it->second;
  NodePtr out;
  if (static_cast<std::size_t>(index) >= m_.textures.size()) {
    warn("texture " + std::to_string(index) + " does not exist");
  } else {
    const tinygltf::Texture& t = m_.textures[static_cast<std::size_t>(index)];
    if (t.source >= 0 && static_cast<std::size_t>(t.source) < m_.images.size()) {
      const tinygltf::Image& image = m_.images[static_cast<std::size_t>(t.source)];
      std::string url;
      if (!image.uri.empty())
        url = image.uri;
      else if (!image.image.empty())
        url =
            base::makeDataUrl(image.mimeType.empty() ? sniffMediaType(image.image) : image.mimeType,
                              std::string_view(reinterpret_cast<const char*>(image.image.data()),
                                               image.image.size()));
      if (!url.empty()) {
        out = make("ImageTexture");
        set(*out, "url", FieldValue::make<FieldType::MFString>(std::vector<std::string>{url}));
        if (t.sampler >= 0 && static_cast<std::size_t>(t.sampler) < m_.samplers.size()) {
          const tinygltf::Sampler& s = m_.samplers[static_cast<std::size_t>(t.sampler)];
          set(*out, "repeatS", FieldValue::make<FieldType::SFBool>(s.wrapS != 33071));
          set(*out, "repeatT", FieldValue::make<FieldType::SFBool>(s.wrapT != 33071));
          set(*out, "textureProperties", FieldValue::make<FieldType::SFNode>(sampler(s)));
        }
      }
    } else if (!t.extensions.empty()) {
      warn("texture " + std::to_string(index) + " has its image only in extension " +
           t.extensions.begin()->first + ", which is not supported");
    }
  }
  return textures_[index] = out;
}

NodePtr GltfImporter::sampler(const tinygltf::Sampler& s) {
  // glTF 2.0 clause 5.26 (sampler) as X3D 4.0 clause 18.4.9 TextureProperties; an
  // undefined filter is DEFAULT (trilinear minification, bilinear magnification).
  auto minification = [](int f) -> std::string {
    switch (f) {
      case 9728:
        return "NEAREST_PIXEL";
      case 9729:
        return "AVG_PIXEL";
      case 9984:
        return "NEAREST_PIXEL_NEAREST_MIPMAP";
      case 9985:
        return "AVG_PIXEL_NEAREST_MIPMAP";
      case 9986:
        return "NEAREST_PIXEL_AVG_MIPMAP";
      case 9987:
        return "AVG_PIXEL_AVG_MIPMAP";
      default:
        return "DEFAULT";
    }
  };
  auto wrap = [](int w) -> std::string {
    return w == 33071 ? "CLAMP_TO_EDGE" : w == 33648 ? "MIRRORED_REPEAT" : "REPEAT";
  };
  NodePtr p = make("TextureProperties");
  set(*p, "minificationFilter", FieldValue::make<FieldType::SFString>(minification(s.minFilter)));
  set(*p, "magnificationFilter",
      FieldValue::make<FieldType::SFString>(s.magFilter == 9728   ? "NEAREST_PIXEL"
                                            : s.magFilter == 9729 ? "AVG_PIXEL"
                                                                  : "DEFAULT"));
  set(*p, "boundaryModeS", FieldValue::make<FieldType::SFString>(wrap(s.wrapS)));
  set(*p, "boundaryModeT", FieldValue::make<FieldType::SFString>(wrap(s.wrapT)));
  set(*p, "generateMipMaps", FieldValue::make<FieldType::SFBool>(true));
  return p;
}

NodePtr GltfImporter::appearance(int material) {
  if (const auto it = appearances_.find(material); it != appearances_.end()) return it->second;
  NodePtr a = make("Appearance");
  const tinygltf::Material* mat = materialAt(m_, material);
  if (material >= 0 && mat == nullptr)
    warn("material " + std::to_string(material) + " does not exist");
  NodePtr m;
  if (mat == nullptr) {
    // The default material (clause 3.9.6): white, fully rough, not metallic.
    m = make("PhysicalMaterial");
  } else {
    const auto& pbr = mat->pbrMetallicRoughness;
    const std::vector<double>& base = pbr.baseColorFactor;
    const float alpha = base.size() == 4 ? static_cast<float>(base[3]) : 1.0f;
    const glm::vec3 baseColor = glm::clamp(rgb(base, glm::vec3(1.0f)), 0.0f, 1.0f);
    const float transparency = std::clamp(1.0f - alpha, 0.0f, 1.0f);
    float emissiveStrength = 1.0f;
    if (const auto it = mat->extensions.find("KHR_materials_emissive_strength");
        it != mat->extensions.end())
      emissiveStrength = static_cast<float>(number(it->second, "emissiveStrength", 1.0));
    const glm::vec3 emissive = rgb(mat->emissiveFactor, glm::vec3(0.0f)) * emissiveStrength;
    if (mat->extensions.count("KHR_materials_unlit")) {
      m = make("UnlitMaterial");
      set(*m, "emissiveColor", FieldValue::make<FieldType::SFColor>(baseColor));
      if (NodePtr t = texture(pbr.baseColorTexture.index))
        set(*m, "emissiveTexture", FieldValue::make<FieldType::SFNode>(t));
    } else {
      m = make("PhysicalMaterial");
      set(*m, "baseColor", FieldValue::make<FieldType::SFColor>(baseColor));
      set(*m, "metallic",
          FieldValue::make<FieldType::SFFloat>(
              std::clamp(static_cast<float>(pbr.metallicFactor), 0.0f, 1.0f)));
      set(*m, "roughness",
          FieldValue::make<FieldType::SFFloat>(
              std::clamp(static_cast<float>(pbr.roughnessFactor), 0.0f, 1.0f)));
      set(*m, "emissiveColor", FieldValue::make<FieldType::SFColor>(emissive));
      if (NodePtr t = texture(pbr.baseColorTexture.index))
        set(*m, "baseTexture", FieldValue::make<FieldType::SFNode>(t));
      if (NodePtr t = texture(pbr.metallicRoughnessTexture.index))
        set(*m, "metallicRoughnessTexture", FieldValue::make<FieldType::SFNode>(t));
      if (NodePtr t = texture(mat->normalTexture.index)) {
        set(*m, "normalTexture", FieldValue::make<FieldType::SFNode>(t));
        set(*m, "normalScale",
            FieldValue::make<FieldType::SFFloat>(static_cast<float>(mat->normalTexture.scale)));
      }
      if (NodePtr t = texture(mat->occlusionTexture.index)) {
        set(*m, "occlusionTexture", FieldValue::make<FieldType::SFNode>(t));
        set(*m, "occlusionStrength",
            FieldValue::make<FieldType::SFFloat>(
                static_cast<float>(mat->occlusionTexture.strength)));
      }
      if (NodePtr t = texture(mat->emissiveTexture.index))
        set(*m, "emissiveTexture", FieldValue::make<FieldType::SFNode>(t));
      // Textures on two TEXCOORD sets name theirs (X3D 4.0 clause 12.4.10 *TextureMapping;
      // the geometry's MultiTextureCoordinate, primitiveShape()).
      std::array<int, 5> used{};
      const std::vector<int> sets = texCoordSets(material, &used, true);
      static constexpr std::array<const char*, 5> kMapping = {
          "baseTextureMapping", "metallicRoughnessTextureMapping", "normalTextureMapping",
          "emissiveTextureMapping", "occlusionTextureMapping"};
      for (std::size_t i = 0; sets.size() > 1 && i < used.size(); ++i) {
        if (used[i] < 0) continue;
        const int s =
            std::find(sets.begin(), sets.end(), used[i]) != sets.end() ? used[i] : sets[0];
        set(*m, kMapping[i],
            FieldValue::make<FieldType::SFString>("TEXCOORD_" + std::to_string(s)));
      }
    }
    set(*m, "transparency", FieldValue::make<FieldType::SFFloat>(transparency));
    const std::string mode = mat->alphaMode.empty() ? "OPAQUE" : mat->alphaMode;
    set(*a, "alphaMode", FieldValue::make<FieldType::SFString>(mode));
    set(*a, "alphaCutoff",
        FieldValue::make<FieldType::SFFloat>(static_cast<float>(mat->alphaCutoff)));
  }
  set(*a, "material", FieldValue::make<FieldType::SFNode>(m));
  return appearances_[material] = a;
}

}  // namespace gs::gltf::x3d
