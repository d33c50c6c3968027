#include "render/splat_source.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "base/file.hpp"
#include "scene/world_triangles.hpp"
#include "splats/gaussian.hpp"
#include "splats/lod_tree.hpp"

namespace gs::render {

namespace {

std::shared_ptr<SplatSet> makeSet(const qnv::StreamHeader& header,
                                  std::vector<qnv::DecodedVector> vectors) {
  auto set = std::make_shared<SplatSet>();
  set->vectors = std::move(vectors);
  set->style = SplatStyle::fromHeader(header);
  set->computeBounds();
  return set;
}

}  // namespace

std::shared_ptr<const SplatSet> loadQnvFile(const std::string& path, std::string& error,
                                            std::vector<std::string>* warnings) {
  std::string bytes;
  if (!base::readFile(path, bytes, error)) return nullptr;
  qnv::StreamDecoder decoder(path);
  std::vector<qnv::DecodedVector> vectors;
  const auto sink = [&](std::uint64_t first, std::span<const qnv::DecodedVector> v) {
    // Keep stream order (largest first) even when packets were lost: place by index.
    const std::size_t end = static_cast<std::size_t>(first) + v.size();
    if (vectors.size() < end) vectors.resize(end, qnv::DecodedVector{{}, 0.0f, {0, 0, 1}, 0});
    std::copy(v.begin(), v.end(), vectors.begin() + static_cast<std::ptrdiff_t>(first));
  };
  decoder.feed(bytes, sink);
  decoder.finish(sink);
  if (warnings) *warnings = decoder.warnings();
  if (!decoder.header()) {
    error = decoder.error();
    return nullptr;
  }
  return makeSet(*decoder.header(), std::move(vectors));
}

std::shared_ptr<SplatSet> splatSetFromEncoded(const qnv::EncodedVectors& encoded) {
  const qnv::Dequantizer dq(encoded.header);
  std::vector<qnv::DecodedVector> vectors(encoded.records.size());
  dq.decode(encoded.records.data(), encoded.records.size(), vectors.data());
  return makeSet(encoded.header, std::move(vectors));
}

std::shared_ptr<SplatSet> inlineSplatSet(const vrml::Node& node) {
  using vrml::FieldType;
  const auto positions = node.get<FieldType::MFVec3f>("position", std::vector<glm::vec3>{});
  if (positions.empty()) return nullptr;
  const auto directions = node.get<FieldType::MFVec3f>("direction", std::vector<glm::vec3>{});
  const auto magnitudes = node.get<FieldType::MFFloat>("magnitude", std::vector<float>{});
  const auto colors = node.get<FieldType::MFColor>("color", std::vector<glm::vec3>{});
  auto set = std::make_shared<SplatSet>();
  float largest = 0.0f;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    qnv::DecodedVector v;
    v.position = positions[i];
    const glm::vec3 d = i < directions.size() ? directions[i] : glm::vec3(0, 0, 1);
    v.normal = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0, 0, 1);
    v.magnitude = i < magnitudes.size() ? std::max(magnitudes[i], 0.0f) : 1.0f;
    const glm::vec3 c =
        glm::clamp(i < colors.size() ? colors[i] : glm::vec3(1.0f), 0.0f, 1.0f) * 255.0f + 0.5f;
    v.rgba = static_cast<std::uint32_t>(c.r) | (static_cast<std::uint32_t>(c.g) << 8) |
             (static_cast<std::uint32_t>(c.b) << 16) | (255u << 24);
    largest = std::max(largest, v.magnitude);
    set->vectors.push_back(v);
  }
  std::stable_sort(set->vectors.begin(), set->vectors.end(),
                   [](const qnv::DecodedVector& a, const qnv::DecodedVector& b) {
                     return a.magnitude > b.magnitude;
                   });
  set->style.kind = qnv::StreamKind::surface;
  set->style.magnitudeMax = std::max(largest, 1e-30f);
  set->computeBounds();
  return set;
}

std::shared_ptr<SplatSet> inlineGaussianSet(const vrml::Node& node) {
  using vrml::FieldType;
  const auto positions = node.get<FieldType::MFVec3f>("positions", std::vector<glm::vec3>{});
  if (positions.empty()) return nullptr;
  const auto orientations = node.get<FieldType::MFVec4f>("orientations", std::vector<glm::vec4>{});
  const auto scales = node.get<FieldType::MFVec3f>("scales", std::vector<glm::vec3>{});
  const auto opacities = node.get<FieldType::MFFloat>("opacities", std::vector<float>{});
  const std::size_t n = positions.size();
  // The SH coefficients, k = l * l + c (degree l, coefficient c): Kerbl et al.'s order
  // within a channel, 0 the dc term.
  std::vector<glm::vec3> coefficients[16];
  for (int l = 0; l <= 3; ++l)
    for (int c = 0; c < 2 * l + 1; ++c)
      coefficients[l * l + c] = node.get<FieldType::MFVec3f>(
          "sphericalHarmonicsDegree" + std::to_string(l) + "Coef" + std::to_string(c),
          std::vector<glm::vec3>{});
  // The highest degree whose coefficients, and all lower ones', cover every splat.
  int degree = -1;
  for (int l = 0; l <= 3; ++l) {
    bool filled = true;
    for (int c = 0; c < 2 * l + 1 && filled; ++c) filled = coefficients[l * l + c].size() >= n;
    if (!filled) break;
    degree = l;
  }
  splats::GaussianCloud cloud;
  cloud.shDegree = std::max(degree, 0);
  cloud.resize(n);
  cloud.colorSpace =
      node.get<FieldType::SFString>("colorSpace", std::string()) == "LIN_REC709_DISPLAY"
          ? splats::ColorSpace::linear
          : splats::ColorSpace::srgb;
  for (std::size_t i = 0; i < n; ++i) {
    cloud.positions[i] = positions[i];
    cloud.scales[i] = i < scales.size() ? glm::max(scales[i], glm::vec3(0.0f)) : glm::vec3(0.01f);
    glm::quat q(1, 0, 0, 0);
    if (i < orientations.size()) {
      const glm::vec4 o = orientations[i];
      const float len = glm::length(o);
      if (len > 0.0f && std::isfinite(len))
        q = glm::quat(o.w / len, o.x / len, o.y / len, o.z / len);
    }
    cloud.rotations[i] = q;
    cloud.opacities[i] = i < opacities.size() ? std::clamp(opacities[i], 0.0f, 1.0f) : 1.0f;
    cloud.shDc[i] = glm::vec3(0.0f);
  }
  if (degree >= 0)
    for (std::size_t i = 0; i < n; ++i) cloud.shDc[i] = coefficients[0][i];
  const auto rest = static_cast<std::size_t>(cloud.shRestPerSplat());
  for (std::size_t k = 1; k < rest + 1; ++k)
    for (std::size_t i = 0; i < n; ++i) cloud.shRest[i * rest + k - 1] = coefficients[k][i];
  auto set = std::make_shared<SplatSet>();
  set->gaussians = std::make_shared<const splats::GaussianCloud>(splats::sortByImportance(cloud));
  set->lodTree = std::make_shared<const splats::LodTree>(splats::buildLodTree(*set->gaussians));
  set->computeBounds();
  return set;
}

std::shared_ptr<SplatSet> worldSplatSet(std::shared_ptr<const vrml::Scene> scene) {
  return splatSetFromEncoded(qnv::encodeSurface(scene::worldTriangles(std::move(scene)), {}));
}

}  // namespace gs::render
