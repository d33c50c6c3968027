// MultiTexture read into texture stages (multi_texture.hpp).
#include "multi_texture.hpp"

#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <algorithm>
#include <cctype>
#include <optional>
#include <string_view>
#include <utility>

namespace gs::render::detail {

namespace {

std::string upperTrimmed(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return out;
}

std::optional<TextureMode> modeNamed(const std::string& name) {
  static constexpr std::pair<std::string_view, TextureMode> kModes[] = {
      {"", TextureMode::modulate},
      {"MODULATE", TextureMode::modulate},
      {"REPLACE", TextureMode::replace},
      {"SELECTARG1", TextureMode::replace},
      {"MODULATE2X", TextureMode::modulate2x},
      {"MODULATE4X", TextureMode::modulate4x},
      {"ADD", TextureMode::add},
      {"ADDSIGNED", TextureMode::addSigned},
      {"ADDSIGNED2X", TextureMode::addSigned2x},
      {"SUBTRACT", TextureMode::subtract},
      {"ADDSMOOTH", TextureMode::addSmooth},
      {"BLENDDIFFUSEALPHA", TextureMode::blendDiffuseAlpha},
      {"BLENDTEXTUREALPHA", TextureMode::blendTextureAlpha},
      {"BLENDFACTORALPHA", TextureMode::blendFactorAlpha},
      {"BLENDCURRENTALPHA", TextureMode::blendCurrentAlpha},
      {"MODULATEALPHA_ADDCOLOR", TextureMode::modulateAlphaAddColor},
      {"MODULATEINVALPHA_ADDCOLOR", TextureMode::modulateInvAlphaAddColor},
      {"MODULATEINVCOLOR_ADDALPHA", TextureMode::modulateInvColorAddAlpha},
      {"OFF", TextureMode::off},
      {"SELECTARG2", TextureMode::selectArg2},
      {"DOTPRODUCT3", TextureMode::dotProduct3},
  };
  for (const auto& [n, m] : kModes)
    if (n == name) return m;
  return std::nullopt;
}

std::optional<TextureSource> sourceNamed(const std::string& name) {
  if (name.empty()) return TextureSource::previous;
  if (name == "DIFFUSE") return TextureSource::diffuse;
  if (name == "SPECULAR") return TextureSource::specular;
  if (name == "FACTOR") return TextureSource::factor;
  return std::nullopt;
}

std::optional<TextureFunction> functionNamed(const std::string& name) {
  if (name.empty()) return TextureFunction::none;
  if (name == "COMPLEMENT") return TextureFunction::complement;
  if (name == "ALPHAREPLICATE") return TextureFunction::alphaReplicate;
  return std::nullopt;
}

// "RGB / ALPHA" or "RGB, ALPHA" in one string: the two halves; else the whole twice.
std::pair<std::string, std::string> perChannel(const std::string& s) {
  const std::size_t split = s.find_first_of("/,");
  if (split == std::string::npos) return {upperTrimmed(s), upperTrimmed(s)};
  return {upperTrimmed(std::string_view(s).substr(0, split)),
          upperTrimmed(std::string_view(s).substr(split + 1))};
}

const std::string& entry(const std::vector<std::string>& list, std::size_t i) {
  static const std::string kEmpty;
  return i < list.size() ? list[i] : kEmpty;
}

}  // namespace

MultiTextureStages readMultiTexture(const vrml::Node& multiTexture,
                                    const vrml::Node* textureTransform) {
  MultiTextureStages out;
  out.factor =
      glm::vec4(glm::clamp(scene::sfColor(multiTexture, "color", glm::vec3(1.0f)), 0.0f, 1.0f),
                std::clamp(scene::sfFloat(multiTexture, "alpha", 1.0f), 0.0f, 1.0f));
  const std::vector<std::string>& modes = scene::mfString(multiTexture, "mode");
  const std::vector<std::string>& sources = scene::mfString(multiTexture, "source");
  const std::vector<std::string>& functions = scene::mfString(multiTexture, "function");
  const std::vector<vrml::NodePtr>* transforms = nullptr;
  if (textureTransform != nullptr &&
      textureTransform->typeId() == vrml::NodeTypeId::MultiTextureTransform)
    transforms = &textureTransform->mfnode("textureTransform");
  const std::vector<vrml::NodePtr>& textures = multiTexture.mfnode("texture");
  for (std::size_t i = 0; i < textures.size(); ++i) {
    const vrml::NodePtr& t = textures[i];
    if (!t || t->unresolved) continue;
    if (t->typeId() == vrml::NodeTypeId::MultiTexture) {
      out.problems.push_back("a MultiTexture inside a MultiTexture is not drawn");
      continue;
    }
    if (out.stages.size() == static_cast<std::size_t>(kMaxTextureStages)) {
      out.problems.push_back("MultiTexture has " + std::to_string(textures.size()) +
                             " textures: only the first " + std::to_string(kMaxTextureStages) +
                             " are drawn");
      break;
    }
    TextureStage stage;
    stage.texture = t.get();
    const auto [rgb, alpha] = perChannel(entry(modes, i));
    const auto rgbMode = modeNamed(rgb), alphaMode = modeNamed(alpha);
    if (!rgbMode || !alphaMode)
      out.problems.push_back("unknown MultiTexture mode \"" + entry(modes, i) +
                             "\": read as MODULATE");
    stage.rgbMode = rgbMode.value_or(TextureMode::modulate);
    stage.alphaMode = alphaMode.value_or(TextureMode::modulate);
    // OFF in either channel turns the whole stage off (table 18.3).
    if (stage.rgbMode == TextureMode::off || stage.alphaMode == TextureMode::off)
      stage.rgbMode = stage.alphaMode = TextureMode::off;
    const std::string source = upperTrimmed(entry(sources, i));
    const auto src = sourceNamed(source);
    if (!src)
      out.problems.push_back("unknown MultiTexture source \"" + entry(sources, i) +
                             "\": read as the previous stage");
    stage.source = src.value_or(TextureSource::previous);
    const auto function = functionNamed(upperTrimmed(entry(functions, i)));
    if (!function)
      out.problems.push_back("unknown MultiTexture function \"" + entry(functions, i) +
                             "\": ignored");
    stage.function = function.value_or(TextureFunction::none);
    const std::size_t index = out.stages.size();
    if (transforms != nullptr && index < transforms->size() && (*transforms)[index] &&
        !(*transforms)[index]->unresolved)
      stage.matrix = scene::textureTransformMatrix(*(*transforms)[index]);
    out.stages.push_back(stage);
  }
  return out;
}

int stageTexCoordSet(int stage, const vrml::Node& geometry, bool meshHasSecondSet) {
  if (!meshHasSecondSet || stage <= 0) return 0;
  const vrml::NodePtr& tc = geometry.sfnode("texCoord");
  if (!tc || tc->typeId() != vrml::NodeTypeId::MultiTextureCoordinate) return 0;
  const std::size_t sets = tc->mfnode("texCoord").size();
  if (sets < 2) return 0;
  return 1;  // entry 1, or a later one (GpuMesh holds two sets: later ones read the second)
}

}  // namespace gs::render::detail
