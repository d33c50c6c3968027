#include "render/splat_source.hpp"

#include <glm/geometric.hpp>

#include "base/file.hpp"
#include "scene/world_triangles.hpp"

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

std::shared_ptr<SplatSet> worldSplatSet(std::shared_ptr<const vrml::Scene> scene) {
  return splatSetFromEncoded(qnv::encodeSurface(scene::worldTriangles(std::move(scene)), {}));
}

}  // namespace gs::render
