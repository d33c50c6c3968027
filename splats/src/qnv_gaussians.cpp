// Gaussian splats as a QNV stream: the bits are in docs/splats.md, "QNV Gaussian streams".
#include "splats/qnv_gaussians.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "qnv/decoder.hpp"
#include "qnv/record.hpp"

namespace gs::splats {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;
constexpr int kFinePositionBits = 12;
constexpr std::uint32_t kFineSteps = 1u << kFinePositionBits;  // 4096 per axis
constexpr float kColorScale = 0.15f;                           // as SPZ: byte = dc * 0.15 + 0.5
constexpr float kSmallestScale = 1e-7f;                        // ln floor for zero scales

std::uint32_t fineCoordinate(float v, float lo, float hi) {
  if (!(hi > lo)) return 0;
  const double t = (static_cast<double>(v) - lo) / (static_cast<double>(hi) - lo) * kFineSteps;
  return static_cast<std::uint32_t>(std::clamp(std::floor(t), 0.0, double{kFineSteps - 1}));
}

float fineReconstruct(std::uint32_t q, float lo, float hi) {
  if (!(hi > lo)) return lo;
  return lo + (static_cast<float>(q) + 0.5f) * (hi - lo) / static_cast<float>(kFineSteps);
}

std::uint8_t byteOf(float t) {  // t in 0..1, rounded
  return static_cast<std::uint8_t>(std::clamp(std::lround(t * 255.0f), 0L, 255L));
}

// The plane frame about a unit normal: u, v with u x v = n.
void planeFrame(const glm::vec3& n, glm::vec3& u, glm::vec3& v) {
  const glm::vec3 ref = std::abs(n.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
  u = glm::normalize(glm::cross(ref, n));
  v = glm::cross(n, u);
}

// Normal at 6 bits of theta over [0, pi] and 7 of phi over [0, 2 pi), cell centres.
void quantizeNormal(const glm::vec3& n, std::uint32_t& t6, std::uint32_t& p7) {
  if (!std::isfinite(n.x + n.y + n.z)) {
    t6 = p7 = 0;
    return;
  }
  const float theta = std::acos(std::clamp(n.z, -1.0f, 1.0f));
  float phi = std::atan2(n.y, n.x);
  if (phi < 0.0f) phi += 2.0f * kPi;
  t6 = std::min<std::uint32_t>(static_cast<std::uint32_t>(theta / kPi * 64.0f), 63u);
  p7 = static_cast<std::uint32_t>(phi / (2.0f * kPi) * 128.0f) & 127u;
}

glm::vec3 reconstructNormal(std::uint32_t t6, std::uint32_t p7) {
  const float theta = (static_cast<float>(t6) + 0.5f) * kPi / 64.0f;
  const float phi = (static_cast<float>(p7) + 0.5f) * 2.0f * kPi / 128.0f;
  return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

std::uint32_t logScaleCode(float s, float lo, float hi) {
  if (!(hi > lo)) return 0;
  const float l = std::log(std::max(s, kSmallestScale));
  return static_cast<std::uint32_t>(
      std::clamp(std::lround((l - lo) / (hi - lo) * 255.0f), 0L, 255L));
}

float logScaleValue(std::uint32_t q, float lo, float hi) {
  return std::exp(hi > lo ? lo + static_cast<float>(q) * (hi - lo) / 255.0f : lo);
}

// SH coefficients beyond DC: degree 1 at 5 bits (step 1/16), higher at 4 (step 1/8);
// `dropped` low bits (0..bits - 1) make the step 2^dropped times coarser: the code is a
// multiple of 2^dropped from the middle code, within the field. A value halfway between
// two coarse steps goes to the one nearer 0 (the commonest value): a capture already on
// the fine grid (SPZ's steps are these) has many such values.
std::uint32_t shCode(float x, int bits, int dropped) {
  const float scale = bits == 5 ? 16.0f : 8.0f;
  const long half = 1L << (bits - 1), step = 1L << dropped;
  const float v = x * scale / static_cast<float>(step);
  long k = std::lround(v);
  if (dropped > 0 && std::isfinite(v))
    k = v >= 0.0f ? static_cast<long>(std::ceil(std::min(v, 1e6f) - 0.5f))
                  : -static_cast<long>(std::ceil(std::min(-v, 1e6f) - 0.5f));
  k = std::clamp(k, -half / step, (half - 1) / step);
  return static_cast<std::uint32_t>(k * step + half);
}

float shValue(std::uint32_t q, int bits) {
  const float scale = bits == 5 ? 16.0f : 8.0f;
  return (static_cast<float>(q) - static_cast<float>(1u << (bits - 1))) / scale;
}

// The first two words of splat `i` in the box and scale range of `h` (A left 0).
void quantizeSplat(const GaussianCloud& cloud, std::size_t i, const qnv::StreamHeader& h,
                   std::uint64_t* w) {
  const float scaleLo = h.valueMin, scaleHi = h.valueMax;
  const glm::vec3 lo = h.boundsMin, hi = h.boundsMax;
  // The axes by scale: major, middle, thin.
  const glm::mat3 r = glm::mat3_cast(glm::normalize(cloud.rotations[i]));
  const glm::vec3 s = glm::abs(cloud.scales[i]);
  int axis[3] = {0, 1, 2};
  std::sort(axis, axis + 3, [&](int a, int b) { return s[a] > s[b]; });
  std::uint32_t t6 = 0, p7 = 0;
  quantizeNormal(glm::normalize(r[axis[2]]), t6, p7);
  const glm::vec3 n = reconstructNormal(t6, p7);
  glm::vec3 u, v;
  planeFrame(n, u, v);
  const glm::vec3 major = r[axis[0]];
  float angle = std::atan2(glm::dot(major, v), glm::dot(major, u));
  if (angle < 0.0f) angle += kPi;
  const std::uint32_t major8 = logScaleCode(s[axis[0]], scaleLo, scaleHi),
                      middle8 = logScaleCode(s[axis[1]], scaleLo, scaleHi),
                      thin8 = logScaleCode(s[axis[2]], scaleLo, scaleHi);
  // A disc round in its plane comes back the same at any angle, and a sphere at any
  // normal too: those bits are then 0, which the compact coding stores for almost nothing.
  const std::uint32_t angleCode =
      major8 == middle8 ? 0u : static_cast<std::uint32_t>(std::lround(angle / kPi * 256.0f)) & 255u;
  if (major8 == thin8) t6 = p7 = 0;
  std::uint32_t fine[3];
  for (int a = 0; a < 3; ++a) fine[a] = fineCoordinate(cloud.positions[i][a], lo[a], hi[a]);
  qnv::RecordFields f;
  f.x = static_cast<std::uint16_t>(fine[0] >> 2);
  f.y = static_cast<std::uint16_t>(fine[1] >> 2);
  f.z = static_cast<std::uint16_t>(fine[2] >> 2);
  f.theta = static_cast<std::uint8_t>(t6 >> 1);
  f.phi = static_cast<std::uint8_t>(p7 >> 1);
  f.a = 0;  // set by the caller, from the quantized splat's importance
  f.c = byteOf(cloud.opacities[i]);
  w[0] = qnv::packRecord(f);
  const glm::vec3 dc = cloud.shDc[i];
  w[1] = std::uint64_t{byteOf(dc.r * kColorScale + 0.5f)} << 56 |
         std::uint64_t{byteOf(dc.g * kColorScale + 0.5f)} << 48 |
         std::uint64_t{byteOf(dc.b * kColorScale + 0.5f)} << 40 | std::uint64_t{major8} << 32 |
         std::uint64_t{middle8} << 24 | std::uint64_t{thin8} << 16 | std::uint64_t{angleCode} << 8 |
         std::uint64_t{fine[0] & 3u} << 6 | std::uint64_t{fine[1] & 3u} << 4 |
         std::uint64_t{fine[2] & 3u} << 2 | std::uint64_t{t6 & 1u} << 1 | std::uint64_t{p7 & 1u};
}

}  // namespace

bool keptInGaussianStream(const GaussianCloud& cloud, std::size_t i) {
  const glm::vec3 p = cloud.positions[i];
  const glm::vec3 sc = cloud.scales[i], dc = cloud.shDc[i];
  const glm::quat q = cloud.rotations[i];
  // Something to draw, and a finite splat to quantize.
  return importance(cloud, i) > 0.0f && cloud.opacities[i] >= 0.5f / 255.0f &&
         std::isfinite(p.x + p.y + p.z) && std::isfinite(sc.x + sc.y + sc.z) &&
         std::isfinite(dc.x + dc.y + dc.z) && std::isfinite(q.w + q.x + q.y + q.z) &&
         glm::dot(q, q) > 0.0f;
}

GaussianFrameBuilder::GaussianFrameBuilder(int shDegree, std::uint64_t splatCount) {
  qnv::StreamHeader& h = header_;
  h.kind = qnv::StreamKind::gaussian;
  h.shDegree = static_cast<std::uint8_t>(std::clamp(shDegree, 0, 3));
  h.mapping = qnv::MagnitudeMapping::logarithmic;
  const std::uint32_t words = h.recordsPerElement();
  // Packets as large as the format allows (zstd wants room), but at least 64 of them, so
  // that the first picture comes within the first few per cent of the bytes.
  const std::uint64_t perPacket =
      std::clamp<std::uint64_t>(splatCount / 64, 1024, qnv::kMaxPacketBytes / (8 * words));
  h.packetBytes = static_cast<std::uint32_t>(8 * words * perPacket);
}

bool GaussianFrameBuilder::addExtent(const GaussianCloud& cloud, std::size_t i) {
  header_.linearColor = cloud.colorSpace == ColorSpace::linear;
  if (!keptInGaussianStream(cloud, i)) return false;
  ++kept_;
  lo_ = glm::min(lo_, cloud.positions[i]);
  hi_ = glm::max(hi_, cloud.positions[i]);
  for (int k = 0; k < 3; ++k) {
    const float l = std::log(std::max(std::abs(cloud.scales[i][k]), kSmallestScale));
    scaleLo_ = std::min(scaleLo_, l);
    scaleHi_ = std::max(scaleHi_, l);
  }
  return true;
}

void GaussianFrameBuilder::finishExtent() {
  qnv::StreamHeader& h = header_;
  if (kept_ == 0) {
    h.boundsMin = glm::vec3(0.0f);
    h.boundsMax = glm::vec3(1.0f);
    return;
  }
  h.boundsMin = lo_;
  h.boundsMax = hi_;
  h.valueMin = scaleLo_;
  h.valueMax = scaleHi_;
}

float GaussianFrameBuilder::importanceOf(const GaussianCloud& cloud, std::size_t i) {
  std::uint64_t w[2];
  quantizeSplat(cloud, i, header_, w);
  const float a = qnv::gaussianImportance(w[0], w[1], header_);
  top_ = std::max(top_, a);
  bottom_ = std::min(bottom_, a);
  return a;
}

const qnv::StreamHeader& GaussianFrameBuilder::finish() {
  if (kept_ > 0) {
    header_.magnitudeMax = std::max(top_, 1e-30f);
    header_.magnitudeMin = std::clamp(bottom_, header_.magnitudeMax * 1e-12f, header_.magnitudeMax);
  }
  return header_;
}

GaussianFrame gaussianFrame(const GaussianCloud& cloud) {
  GaussianFrame frame;
  GaussianFrameBuilder builder(cloud.shDegree, cloud.size());
  frame.kept.reserve(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); ++i)
    if (builder.addExtent(cloud, i)) frame.kept.push_back(static_cast<std::uint32_t>(i));
  builder.finishExtent();
  frame.importance.resize(frame.kept.size());
  for (std::size_t k = 0; k < frame.kept.size(); ++k)
    frame.importance[k] = builder.importanceOf(cloud, frame.kept[k]);
  frame.header = builder.finish();
  return frame;
}

std::vector<std::uint64_t> encodeGaussianSplats(const GaussianCloud& cloud,
                                                std::span<const std::uint32_t> order,
                                                const qnv::StreamHeader& h,
                                                const GaussianStreamOptions& options) {
  const int dropped = 5 - std::clamp(options.shBits, 1, 5);
  const std::uint32_t words = h.recordsPerElement();
  const int rest = cloud.shRestPerSplat();
  // The most important splats keep every SH bit (options.shFullFraction), the rest
  // options.shBits.
  const auto fullCount = static_cast<std::size_t>(std::llround(
      std::clamp(options.shFullFraction, 0.0, 1.0) * static_cast<double>(order.size())));
  std::vector<std::uint64_t> records(order.size() * words, 0);
  for (std::size_t r = 0; r < order.size(); ++r) {
    const std::size_t i = order[r];
    std::uint64_t* w = records.data() + r * words;
    quantizeSplat(cloud, i, h, w);
    w[0] |= std::uint64_t{qnv::quantizeMagnitude(qnv::gaussianImportance(w[0], w[1], h), h.mapping,
                                                 h.magnitudeMin, h.magnitudeMax)}
            << 8;
    const int drop = r < fullCount ? 0 : dropped;
    for (int c = 0, at = 0; c < rest; ++c)
      for (int ch = 0; ch < 3; ++ch) {
        const int bits = qnv::gaussianShBits(3 * c + ch);
        qnv::writeWordBits(w + 2, at,
                           shCode(cloud.shRest[i * rest + c][ch], bits, std::min(drop, bits - 1)),
                           bits);
        at += bits;
      }
  }
  return records;
}

qnv::EncodedVectors encodeGaussianStream(const GaussianCloud& cloud,
                                         const GaussianStreamOptions& options) {
  GaussianFrame frame = gaussianFrame(cloud);
  qnv::EncodedVectors out;
  out.header = frame.header;
  // By the importance of the quantized splat, largest first, ties in cloud order.
  std::vector<std::uint32_t> order(frame.kept.size());
  for (std::uint32_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return frame.importance[a] > frame.importance[b];
  });
  for (std::uint32_t& k : order) k = frame.kept[k];
  out.records = encodeGaussianSplats(cloud, order, out.header, options);
  out.header.vectorCount = out.records.size();
  return out;
}

void appendGaussianRecords(const qnv::StreamHeader& h, std::span<const std::uint64_t> records,
                           GaussianCloud& cloud) {
  const std::uint32_t words = h.recordsPerElement();
  if (h.kind != qnv::StreamKind::gaussian || words < 2) return;
  if (cloud.empty()) cloud.setShDegree(h.shDegree);
  cloud.colorSpace = colorSpaceOf(h);
  const int rest = cloud.shRestPerSplat();
  const int have = shCoefficients(h.shDegree) - 1;  // coefficients the words hold
  const std::size_t n = records.size() / words;
  cloud.reserve(cloud.size() + n);
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint64_t* w = records.data() + k * words;
    const qnv::RecordFields f = qnv::unpackRecord(w[0]);
    const std::uint64_t e = w[1];
    glm::vec3 position;
    const std::uint32_t coarse[3] = {f.x, f.y, f.z};
    for (int a = 0; a < 3; ++a) {
      const std::uint32_t fine =
          (coarse[a] << 2) | static_cast<std::uint32_t>((e >> (6 - 2 * a)) & 3u);
      position[a] = fineReconstruct(fine, h.boundsMin[a], h.boundsMax[a]);
    }
    const std::uint32_t t6 =
        (std::uint32_t{f.theta} << 1) | static_cast<std::uint32_t>((e >> 1) & 1u);
    const std::uint32_t p7 = (std::uint32_t{f.phi} << 1) | static_cast<std::uint32_t>(e & 1u);
    const glm::vec3 n3 = reconstructNormal(t6, p7);
    glm::vec3 u, v;
    planeFrame(n3, u, v);
    const float angle = static_cast<float>((e >> 8) & 255u) * kPi / 256.0f;
    const glm::vec3 major = std::cos(angle) * u + std::sin(angle) * v;
    const glm::vec3 middle = glm::cross(n3, major);
    const glm::quat q = glm::normalize(glm::quat_cast(glm::mat3(major, middle, n3)));
    const glm::vec3 scales(logScaleValue((e >> 32) & 255u, h.valueMin, h.valueMax),
                           logScaleValue((e >> 24) & 255u, h.valueMin, h.valueMax),
                           logScaleValue((e >> 16) & 255u, h.valueMin, h.valueMax));
    const glm::vec3 dc(((static_cast<float>((e >> 56) & 255u) / 255.0f) - 0.5f) / kColorScale,
                       ((static_cast<float>((e >> 48) & 255u) / 255.0f) - 0.5f) / kColorScale,
                       ((static_cast<float>((e >> 40) & 255u) / 255.0f) - 0.5f) / kColorScale);
    cloud.positions.push_back(position);
    cloud.scales.push_back(scales);
    cloud.rotations.push_back(q);
    cloud.opacities.push_back(static_cast<float>(f.c) / 255.0f);
    cloud.shDc.push_back(dc);
    for (int c = 0, at = 0; c < rest; ++c) {
      glm::vec3 coefficient(0.0f);
      if (c < have)
        for (int ch = 0; ch < 3; ++ch) {
          const int bits = qnv::gaussianShBits(3 * c + ch);
          coefficient[ch] = shValue(qnv::readWordBits(w + 2, at, bits), bits);
          at += bits;
        }
      cloud.shRest.push_back(coefficient);
    }
  }
}

bool placeGaussianRecords(const qnv::StreamHeader& header, std::uint64_t firstRecord,
                          std::span<const std::uint64_t> records, GaussianCloud& cloud) {
  GaussianCloud packet;
  packet.setShDegree(cloud.empty() ? header.shDegree : cloud.shDegree);
  appendGaussianRecords(header, records, packet);
  const std::size_t first = static_cast<std::size_t>(firstRecord / header.recordsPerElement());
  const bool over = first < cloud.size();
  if (cloud.empty()) cloud.setShDegree(packet.shDegree);
  cloud.colorSpace = packet.colorSpace;
  if (cloud.size() < first + packet.size()) {
    const std::size_t before = cloud.size();
    cloud.resize(first + packet.size());
    std::fill(cloud.opacities.begin() + static_cast<std::ptrdiff_t>(before), cloud.opacities.end(),
              0.0f);
  }
  const int rest = cloud.shRestPerSplat();
  for (std::size_t k = 0; k < packet.size(); ++k) {
    const std::size_t i = first + k;
    cloud.positions[i] = packet.positions[k];
    cloud.scales[i] = packet.scales[k];
    cloud.rotations[i] = packet.rotations[k];
    cloud.opacities[i] = packet.opacities[k];
    cloud.shDc[i] = packet.shDc[k];
    for (int c = 0; c < rest; ++c)
      cloud.shRest[i * static_cast<std::size_t>(rest) + static_cast<std::size_t>(c)] =
          packet.shRest[k * static_cast<std::size_t>(rest) + static_cast<std::size_t>(c)];
  }
  return over;
}

GaussianCloud readQnvGaussians(std::string_view bytes, std::string_view name) {
  qnv::StreamDecoder decoder{std::string(name)};
  GaussianCloud cloud;
  bool kindChecked = false;
  std::string wrongKind;
  decoder.setRecordSink([&](std::uint64_t first, std::span<const std::uint64_t> records) {
    // A packet's place comes from its sequence number: believe it only as far as the
    // bytes could hold (a splat takes at least 2 bytes, as net::QnvStream assumes), so
    // that a hostile stream cannot size the cloud.
    const std::uint64_t words = decoder.header()->recordsPerElement();
    if (first + records.size() > (bytes.size() / 2 + 65536) * words) return;
    placeGaussianRecords(*decoder.header(), first, records, cloud);
  });
  // Feed in slices so that a stream of another kind is refused before its packets decode.
  for (std::size_t at = 0; at < bytes.size();) {
    const std::size_t n = std::min<std::size_t>(bytes.size() - at, 1 << 20);
    if (!decoder.feed(bytes.substr(at, n), {})) break;
    at += n;
    if (!kindChecked && decoder.header()) {
      kindChecked = true;
      if (decoder.header()->kind != qnv::StreamKind::gaussian)
        throw FormatError(std::string(name) +
                          ": a QNV stream of normal vectors, not of Gaussian splats");
    }
  }
  decoder.finish({});
  if (!decoder.header()) throw FormatError(decoder.error());
  if (decoder.header()->kind != qnv::StreamKind::gaussian)
    throw FormatError(std::string(name) +
                      ": a QNV stream of normal vectors, not of Gaussian splats");
  return cloud;
}

}  // namespace gs::splats
