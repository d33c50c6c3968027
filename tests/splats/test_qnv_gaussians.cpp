// Gaussian splats as a QNV stream (splats/qnv_gaussians.hpp; docs/splats.md, "QNV Gaussian
// streams"): every field comes back within its quantization step, in importance order,
// any prefix decodes, damaged and hostile streams are refused or skipped.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include <zstd.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include "qnv/decoder.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

using namespace gs::splats;

namespace {

GaussianCloud bunnySmall() {
  const std::string bytes =
      gs::test::readBytes(gs::test::sourceDir() / "tests/data/splats/bunny_small.ply");
  REQUIRE(!bytes.empty());
  return sortByImportance(readPlyGaussians(bytes, "bunny_small.ply"));
}

glm::mat3 covarianceOf(const GaussianCloud& c, std::size_t i) {
  const glm::mat3 r = glm::mat3_cast(c.rotations[i]);
  const glm::vec3 s = c.scales[i];
  return r * glm::mat3(s.x * s.x, 0, 0, 0, s.y * s.y, 0, 0, 0, s.z * s.z) * glm::transpose(r);
}

}  // namespace

TEST_CASE("a Gaussian stream gives back every splat within its quantization", "[splats][qnv]") {
  const GaussianCloud cloud = bunnySmall();
  REQUIRE(cloud.shDegree == 1);
  const gs::qnv::EncodedVectors encoded = encodeGaussianStream(cloud);
  CHECK(encoded.header.kind == gs::qnv::StreamKind::gaussian);
  CHECK(encoded.header.recordsPerElement() == 3);
  REQUIRE(encoded.records.size() == cloud.size() * 3);
  for (const auto coding : {gs::qnv::PacketEncoding::plain, gs::qnv::PacketEncoding::compact}) {
    const std::string bytes = gs::qnv::writeStream(encoded, {24 * 100, coding});
    GaussianCloud back = readQnvGaussians(bytes, "bunny.qnv");
    REQUIRE(back.size() == cloud.size());
    REQUIRE(back.shDegree == 1);
    // Compact packets give their splats in Morton order: match each back by position.
    back = sortByImportance(back);
    const glm::vec3 box = encoded.header.boundsMax - encoded.header.boundsMin;
    double worstPosition = 0, worstColor = 0, worstSh = 0, worstCovariance = 0, worstOpacity = 0;
    std::size_t matched = 0;
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      // The same splat: the nearest decoded centre among those of about its importance.
      std::size_t best = 0;
      float bestDistance = INFINITY;
      for (std::size_t j = 0; j < back.size(); ++j) {
        const float d = glm::length(back.positions[j] - cloud.positions[i]);
        if (d < bestDistance && std::abs(back.opacities[j] - cloud.opacities[i]) < 0.01f &&
            glm::length(back.shDc[j] - cloud.shDc[i]) < 0.05f) {
          bestDistance = d;
          best = j;
        }
      }
      if (bestDistance == INFINITY) continue;
      ++matched;
      for (int a = 0; a < 3; ++a)
        worstPosition =
            std::max(worstPosition,
                     double(std::abs(back.positions[best][a] - cloud.positions[i][a]) / box[a]));
      worstOpacity =
          std::max(worstOpacity, double(std::abs(back.opacities[best] - cloud.opacities[i])));
      worstColor = std::max(worstColor, double(glm::length(back.shDc[best] - cloud.shDc[i])));
      for (int k = 0; k < 3; ++k)
        worstSh = std::max(
            worstSh, double(glm::length(back.shRest[best * 3 + k] -
                                        glm::clamp(cloud.shRest[i * 3 + k], -1.0f, 0.9375f))));
      const glm::mat3 a = covarianceOf(cloud, i), b = covarianceOf(back, best);
      const float largest = std::max({cloud.scales[i].x, cloud.scales[i].y, cloud.scales[i].z});
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          worstCovariance =
              std::max(worstCovariance, double(std::abs(a[c][r] - b[c][r]) / (largest * largest)));
    }
    INFO("matched " << matched << " of " << cloud.size());
    CHECK(matched >= cloud.size() * 99 / 100);
    CHECK(worstPosition <= 0.5 / 4096 + 1e-6);  // half a 12-bit step of the box
    CHECK(worstOpacity <= 0.5 / 255 + 1e-6);
    CHECK(worstColor <= 0.5 / 255 / 0.15 * std::sqrt(3.0) + 1e-4);
    CHECK(worstSh <= 0.5 / 16 * std::sqrt(3.0) + 1e-4);
    // Scales at 8 bits of their log range and the axes at about a degree: the covariance
    // within a few per cent of the largest variance.
    CHECK(worstCovariance <= 0.15);
    WARN("worst covariance error " << worstCovariance << " of the largest variance");
  }
}

TEST_CASE("fewer SH bits: coarser steps, the same layout, smaller compact packets",
          "[splats][qnv]") {
  // The bunny with degree-1 SH of a capture's spread (its own are about 0): uniform in
  // [-0.6, 0.6], fixed seed.
  GaussianCloud cloud = bunnySmall();
  REQUIRE(cloud.shDegree == 1);
  std::uint32_t seed = 12345;
  for (glm::vec3& v : cloud.shRest)
    for (int ch = 0; ch < 3; ++ch) {
      seed = seed * 1664525u + 1013904223u;
      v[ch] = (static_cast<float>(seed >> 8) / 16777216.0f - 0.5f) * 1.2f;
    }
  std::size_t previous = 0;
  for (const int bits : {5, 4, 3}) {
    INFO("--sh-bits " << bits);
    const gs::qnv::EncodedVectors encoded = encodeGaussianStream(cloud, {.shBits = bits});
    REQUIRE(encoded.records.size() == cloud.size() * 3);  // the layout is unchanged
    const std::string bytes = gs::qnv::writeStream(
        encoded,
        {static_cast<std::uint32_t>(encoded.header.packetBytes), gs::qnv::PacketEncoding::compact});
    const GaussianCloud back = readQnvGaussians(bytes, "bunny.qnv");
    REQUIRE(back.size() == cloud.size());
    // Every degree-1 value is a multiple of the step 2^(5 - bits) / 16, and the values of
    // all splats together are within half a step of the source's (clamped to the field).
    const float step = static_cast<float>(1 << (5 - bits)) / 16.0f;
    double sourceSum = 0.0, backSum = 0.0;
    for (std::size_t i = 0; i < back.size(); ++i)
      for (int k = 0; k < 3; ++k)
        for (int ch = 0; ch < 3; ++ch) {
          const float v = back.shRest[i * 3 + k][ch];
          CHECK(std::abs(v / step - std::round(v / step)) < 1e-4f);
          backSum += std::abs(v);
          sourceSum += std::abs(glm::clamp(cloud.shRest[i * 3 + k][ch], -1.0f, 1.0f));
        }
    CHECK(std::abs(backSum - sourceSum) <= 0.5 * step * double(back.size()) * 9);
    CHECK(backSum > 0.2 * double(back.size()) * 9);  // values, not zeros
    // Coarser values pack tighter.
    if (previous != 0) CHECK(bytes.size() < previous);
    previous = bytes.size();
  }
  // shFullFraction: the stream's first splats keep every bit, the rest are coarser. All of
  // them: the records of shBits 5; none: those of the coarse setting.
  const auto whole = encodeGaussianStream(cloud);
  const auto coarse = encodeGaussianStream(cloud, {.shBits = 3});
  CHECK(encodeGaussianStream(cloud, {.shBits = 3, .shFullFraction = 1.0}).records == whole.records);
  CHECK(encodeGaussianStream(cloud, {.shBits = 3, .shFullFraction = 0.0}).records ==
        coarse.records);
  const auto half = encodeGaussianStream(cloud, {.shBits = 3, .shFullFraction = 0.5});
  REQUIRE(half.records.size() == whole.records.size());
  const std::size_t splats = whole.records.size() / 3, first = (splats + 1) / 2;
  for (std::size_t k = 0; k < splats; ++k) {
    INFO("splat " << k << " of the stream");
    const auto& want = k < first ? whole.records : coarse.records;
    CHECK(half.records[3 * k + 2] == want[3 * k + 2]);   // the SH word
    CHECK(half.records[3 * k] == whole.records[3 * k]);  // the rest: the same splat
  }
}

TEST_CASE("a Gaussian stream is in importance order and every prefix decodes", "[splats][qnv]") {
  const GaussianCloud cloud = bunnySmall();
  const gs::qnv::EncodedVectors encoded = encodeGaussianStream(cloud);
  for (std::size_t k = 3; k < encoded.records.size(); k += 3)
    REQUIRE(gs::qnv::magnitudeCode(encoded.records[k]) <=
            gs::qnv::magnitudeCode(encoded.records[k - 3]));
  const std::string bytes =
      gs::qnv::writeStream(encoded, {24 * 50, gs::qnv::PacketEncoding::compact});
  std::size_t previous = 0;
  for (std::size_t cut = 1132; cut <= bytes.size(); cut += bytes.size() / 17) {
    const GaussianCloud prefix = readQnvGaussians(bytes.substr(0, cut), "bunny.qnv");
    CHECK(prefix.size() % 50 == 0);
    CHECK(prefix.size() >= previous);
    previous = prefix.size();
  }
}

TEST_CASE("round discs store no angle and spheres no normal, and come back the same",
          "[splats][qnv]") {
  // One round disc, one sphere and one flat ellipse, each turned at random.
  GaussianCloud cloud;
  cloud.setShDegree(0);
  const glm::vec3 scales[] = {
      {0.02f, 0.02f, 0.001f}, {0.01f, 0.01f, 0.01f}, {0.03f, 0.01f, 0.001f}};
  for (int k = 0; k < 3; ++k) {
    cloud.positions.push_back(glm::vec3(0.1f * static_cast<float>(k)));
    cloud.scales.push_back(scales[k]);
    cloud.rotations.push_back(glm::normalize(glm::quat(0.3f, 0.5f + 0.1f * k, -0.7f, 0.2f)));
    cloud.opacities.push_back(0.8f);
    cloud.shDc.push_back(glm::vec3(0.2f));
  }
  const gs::qnv::EncodedVectors encoded = encodeGaussianStream(cloud);
  REQUIRE(encoded.records.size() == 6);
  const GaussianCloud back = readQnvGaussians(gs::qnv::writeStream(encoded), "shapes.qnv");
  REQUIRE(back.size() == 3);
  int discs = 0, spheres = 0, ellipses = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::uint64_t word = encoded.records[2 * k + 1];
    const std::uint32_t major = (word >> 32) & 255u, middle = (word >> 24) & 255u,
                        thin = (word >> 16) & 255u, angle = (word >> 8) & 255u;
    const gs::qnv::RecordFields f = gs::qnv::unpackRecord(encoded.records[2 * k]);
    if (major == thin) {
      ++spheres;
      CHECK(angle == 0);
      CHECK(f.theta == 0);
      CHECK(f.phi == 0);
      CHECK((word & 3u) == 0);  // the normal's low bits
    } else if (major == middle) {
      ++discs;
      CHECK(angle == 0);
    } else {
      ++ellipses;  // its angle kept: the covariance check below needs it
    }
    // The covariance comes back within the quantization, whatever the angle stored.
    std::size_t i = 0;
    while (i < 3 && glm::distance(cloud.positions[i], back.positions[k]) > 0.01f) ++i;
    REQUIRE(i < 3);
    const glm::mat3 a = covarianceOf(cloud, i), b = covarianceOf(back, k);
    const float largest = std::max({a[0][0], a[1][1], a[2][2]});
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) CHECK(std::abs(a[c][r] - b[c][r]) < 0.05f * largest);
  }
  CHECK(discs == 1);
  CHECK(spheres == 1);
  CHECK(ellipses == 1);
}

TEST_CASE("compact Gaussian packets hold a zstd block per field", "[splats][qnv]") {
  const GaussianCloud cloud = bunnySmall();
  const std::string bytes = gs::qnv::writeStream(encodeGaussianStream(cloud),
                                                 {24 * 1500, gs::qnv::PacketEncoding::compact});
  // The first packet's payload: one zstd frame; walk its block headers (RFC 8878 3.1.1.2).
  const std::size_t at = gs::qnv::kHeaderBytes + gs::qnv::kPacketHeaderBytes;
  REQUIRE(bytes.size() > at + 32);
  REQUIRE(static_cast<unsigned char>(bytes[gs::qnv::kHeaderBytes + 10]) == 1);  // compact
  const unsigned char* p = reinterpret_cast<const unsigned char*>(bytes.data()) + at;
  const std::size_t payload =
      static_cast<unsigned char>(bytes[gs::qnv::kHeaderBytes + 8]) |
      static_cast<std::size_t>(static_cast<unsigned char>(bytes[gs::qnv::kHeaderBytes + 9])) << 8;
  // The frame header (RFC 8878 3.1.1.1): magic, descriptor, window, dictionary, size.
  REQUIRE(payload > 6);
  REQUIRE((p[0] | p[1] << 8 | p[2] << 16 | static_cast<std::uint32_t>(p[3]) << 24) ==
          ZSTD_MAGICNUMBER);
  const unsigned descriptor = p[4];
  const bool singleSegment = (descriptor >> 5) & 1u;
  const std::size_t sizeBytes[] = {singleSegment ? 1u : 0u, 2, 4, 8}, dictBytes[] = {0, 1, 2, 4};
  const std::size_t frameHeader =
      5 + (singleSegment ? 0 : 1) + dictBytes[descriptor & 3u] + sizeBytes[descriptor >> 6];
  int blocks = 0;
  for (std::size_t pos = frameHeader; pos + 3 <= payload; ++blocks) {
    const std::uint32_t h =
        p[pos] | (std::uint32_t{p[pos + 1]} << 8) | (std::uint32_t{p[pos + 2]} << 16);
    const std::uint32_t type = (h >> 1) & 3u, size = h >> 3;
    pos += 3 + (type == 1 ? 1 : size);  // an RLE block holds one byte
    if (h & 1u) {
      ++blocks;
      break;
    }
  }
  // Positions, direction twice, A, C, colour, two scale blocks, angle, low bits, SH degree 1.
  CHECK(blocks >= 10);
  // The blocks pay: bunny_small took 36,935 bytes in one block a packet (fifteenth session).
  const std::string stream = gs::qnv::writeStream(encodeGaussianStream(cloud),
                                                  {24 * 1024, gs::qnv::PacketEncoding::compact});
  CHECK(stream.size() < 35800);  // 35,181 measured
}

TEST_CASE("a damaged Gaussian stream loses only its damaged packets", "[splats][qnv]") {
  const GaussianCloud cloud = bunnySmall();
  const std::string bytes = gs::qnv::writeStream(encodeGaussianStream(cloud),
                                                 {24 * 100, gs::qnv::PacketEncoding::compact});
  std::string damaged = bytes;
  damaged[damaged.size() / 2] ^= 0x40;
  const GaussianCloud back = readQnvGaussians(damaged, "bunny.qnv");
  CHECK(back.size() == cloud.size());  // the lost packet's place is kept, transparent
  CHECK(std::count(back.opacities.begin(), back.opacities.end(), 0.0f) == 100);
  // Every packet twice: the same splats, not twice as many.
  const std::size_t header = gs::qnv::kHeaderBytes;
  const std::string twice = bytes + bytes.substr(header);
  CHECK(readQnvGaussians(twice, "twice.qnv").size() == cloud.size());
  // Records of another kind, or no stream at all, are errors that name the input.
  CHECK_THROWS_WITH(readQnvGaussians("not a stream", "x.qnv"), Catch::Contains("x.qnv"));
  gs::qnv::EncodedVectors vectors;
  vectors.header.boundsMax = glm::vec3(1.0f);
  vectors.records = {gs::qnv::packRecord({1, 2, 3, 4, 5, 6, 7})};
  CHECK_THROWS_WITH(readQnvGaussians(gs::qnv::writeStream(vectors), "v.qnv"),
                    Catch::Contains("not of Gaussian splats"));
}

TEST_CASE("hostile Gaussian words decode to finite splats", "[splats][qnv]") {
  gs::qnv::StreamHeader h;
  h.kind = gs::qnv::StreamKind::gaussian;
  h.shDegree = 3;
  h.boundsMax = glm::vec3(1.0f);
  h.valueMin = -80.0f;
  h.valueMax = 80.0f;
  std::vector<std::uint64_t> words(5 * 64);
  std::uint64_t x = 0x9e3779b97f4a7c15ull;
  for (auto& w : words) w = (x = x * 6364136223846793005ull + 1442695040888963407ull);
  GaussianCloud cloud;
  appendGaussianRecords(h, words, cloud);
  REQUIRE(cloud.size() == 64);
  REQUIRE(cloud.shRest.size() == 64 * 15);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    CHECK(std::isfinite(glm::length(cloud.positions[i])));
    CHECK(std::isfinite(glm::length(glm::vec4(cloud.rotations[i].x, cloud.rotations[i].y,
                                              cloud.rotations[i].z, cloud.rotations[i].w))));
  }
}

TEST_CASE("appendRange appends what append appends, splat by splat", "[splats][gaussian]") {
  const GaussianCloud bunny = bunnySmall();
  REQUIRE(bunny.shDegree > 0);
  const auto sameAs = [](const GaussianCloud& a, const GaussianCloud& b) {
    return a.shDegree == b.shDegree && a.positions == b.positions && a.scales == b.scales &&
           a.rotations == b.rotations && a.opacities == b.opacities && a.shDc == b.shDc &&
           a.shRest == b.shRest;
  };
  for (const int degree : {bunny.shDegree, 0, 3}) {
    INFO("into a cloud of SH degree " << degree);
    GaussianCloud ranged, single;
    ranged.shDegree = single.shDegree = degree;
    ranged.append(bunny, 0);
    single.append(bunny, 0);
    ranged.appendRange(bunny, 10, 400);
    for (std::size_t i = 10; i < 400; ++i) single.append(bunny, i);
    ranged.appendRange(bunny, 7, 7);  // nothing
    CHECK(ranged.size() == 391);
    CHECK(sameAs(ranged, single));
  }
}

TEST_CASE("a Gaussian stream keeps its scene's colour space", "[splats][qnv]") {
  // glTF's lin_rec709_display: the SH colours are linear and shown through the sRGB
  // transfer function; before header byte 51 said so, such a scene came back sRGB.
  GaussianCloud cloud = bunnySmall();
  for (const ColorSpace space : {ColorSpace::srgb, ColorSpace::linear}) {
    cloud.colorSpace = space;
    const gs::qnv::EncodedVectors encoded = encodeGaussianStream(cloud);
    CHECK(encoded.header.linearColor == (space == ColorSpace::linear));
    std::string bytes = gs::qnv::writeStream(encoded, {24 * 100, gs::qnv::PacketEncoding::compact});
    CHECK(static_cast<int>(bytes[51]) == (space == ColorSpace::linear ? 1 : 0));
    const GaussianCloud back = readQnvGaussians(bytes, "bunny.qnv");
    REQUIRE(back.size() == cloud.size());
    CHECK(back.colorSpace == space);
    // Any other value is refused by the header's check (its CRC made good again).
    std::string header = bytes.substr(0, gs::qnv::kHeaderBytes);
    header[51] = 2;
    const std::uint32_t crc =
        gs::qnv::crc32(std::string_view(header).substr(0, gs::qnv::kHeaderBytes - 4));
    for (int i = 0; i < 4; ++i)
      header[gs::qnv::kHeaderBytes - 4 + i] = static_cast<char>(crc >> (8 * i));
    std::string error;
    CHECK_FALSE(gs::qnv::parseHeader(header, "bad.qnv", error));
    CHECK_THAT(error, Catch::Contains("unknown colour space 2"));
  }
}
