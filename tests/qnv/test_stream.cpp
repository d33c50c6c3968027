// The .qnv container: every prefix decodes, lost and damaged packets cost only their own
// vectors, and hostile bytes give explicit errors (docs/qnv-format.md).
#include <catch2/catch.hpp>

#include <map>
#include <set>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <random>

#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"

using namespace gs::qnv;

namespace {

// A bumpy sphere of 2 * n * n triangles with a colour per face.
TriangleMesh sphere(int n) {
  TriangleMesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float th = 3.14159265f * i / n, ph = 6.2831853f * j / n;
      const float r = 1.0f + 0.1f * std::sin(5.0f * th) * std::cos(3.0f * ph);
      m.positions.push_back(
          {r * std::sin(th) * std::cos(ph), r * std::sin(th) * std::sin(ph), r * std::cos(th)});
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::uint32_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, b, b, c, d});
      m.faceColors.push_back(
          {static_cast<std::uint8_t>(i * 7), 100, static_cast<std::uint8_t>(j * 5), 255});
      m.faceColors.push_back(
          {static_cast<std::uint8_t>(i * 7), 200, static_cast<std::uint8_t>(j * 5), 255});
    }
  return m;
}

struct Decoded {
  std::map<std::uint64_t, DecodedVector> byIndex;  // plain packets keep stream order
  std::size_t vectors = 0;
  bool ok = true;
  bool finished = false;
  StreamDecoder decoder{"test.qnv"};
};

void decodeInto(Decoded& out, std::string_view bytes, std::size_t chunk) {
  auto sink = [&](std::uint64_t first, std::span<const DecodedVector> v) {
    for (std::size_t i = 0; i < v.size(); ++i) out.byIndex[first + i] = v[i];
    out.vectors += v.size();
  };
  for (std::size_t at = 0; at < bytes.size() && out.ok; at += chunk)
    out.ok = out.decoder.feed(bytes.substr(at, chunk), sink);
  out.finished = out.decoder.finish(sink);
}

bool same(const DecodedVector& a, const DecodedVector& b) {
  return a.position == b.position && a.normal == b.normal && a.magnitude == b.magnitude &&
         a.rgba == b.rgba;
}

const EncodedVectors& encoded() {
  static const EncodedVectors e = encodeSurface(sphere(24), {});
  return e;
}

}  // namespace

TEST_CASE("a surface round-trips within the documented bounds", "[qnv][stream]") {
  const TriangleMesh mesh = sphere(24);
  const EncodedVectors e = encodeSurface(mesh, {});
  std::size_t nonDegenerate = 0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                    b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
    nonDegenerate += glm::length(glm::cross(b - a, c - a)) > 0.0f;
  }
  REQUIRE(nonDegenerate < mesh.triangleCount());  // the poles have degenerate triangles
  REQUIRE(e.records.size() == nonDegenerate);
  Decoded d;
  decodeInto(d, writeStream(e), 1 << 20);
  REQUIRE(d.finished);
  REQUIRE(d.vectors == nonDegenerate);
  // Largest first: magnitudes never grow along the stream.
  for (std::size_t i = 1; i < d.vectors; ++i)
    REQUIRE(d.byIndex[i].magnitude <= d.byIndex[i - 1].magnitude);
  // Every triangle is matched by one vector within half a step, 3.98 degrees and the
  // magnitude bound.
  const glm::vec3 step = (e.header.boundsMax - e.header.boundsMin) / 1024.0f;
  const double relBound =
      std::pow(double{e.header.magnitudeMax} / e.header.magnitudeMin, 1.0 / 65536) - 1.0;
  std::size_t matched = 0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
    const glm::vec3 a = mesh.positions[mesh.indices[3 * t]],
                    b = mesh.positions[mesh.indices[3 * t + 1]],
                    c = mesh.positions[mesh.indices[3 * t + 2]];
    const glm::vec3 centroid = (a + b + c) / 3.0f, cross = glm::cross(b - a, c - a);
    const float area = 0.5f * glm::length(cross);
    if (!(area > 0.0f)) continue;
    for (const auto& [i, v] : d.byIndex) {
      const glm::vec3 err = glm::abs(v.position - centroid);
      if (err.x > step.x * 0.5001f || err.y > step.y * 0.5001f || err.z > step.z * 0.5001f)
        continue;
      if (std::abs(v.magnitude - area) > area * (relBound + 1e-6)) continue;
      if (glm::dot(v.normal, glm::normalize(cross)) < std::cos(0.0695f)) continue;
      ++matched;
      break;
    }
  }
  CHECK(matched == nonDegenerate);
}

TEST_CASE("chunk size does not change what decodes", "[qnv][stream]") {
  const std::string bytes = writeStream(encoded(), {48, PacketEncoding::plain});
  Decoded whole;
  decodeInto(whole, bytes, bytes.size());
  for (std::size_t chunk : {1, 7, 16, 1000}) {
    Decoded d;
    decodeInto(d, bytes, chunk);
    REQUIRE(d.finished);
    REQUIRE(d.vectors == whole.vectors);
    for (const auto& [i, v] : whole.byIndex) REQUIRE(same(d.byIndex[i], v));
  }
}

TEST_CASE("every prefix of a stream decodes the packets it holds", "[qnv][stream]") {
  SurfaceEncodeOptions options;
  options.selection.count = 100;
  const std::string bytes =
      writeStream(encodeSurface(sphere(24), options), {48, PacketEncoding::plain});
  Decoded whole;
  decodeInto(whole, bytes, bytes.size());
  const std::size_t packet = kPacketHeaderBytes + 48;
  for (std::size_t length = 0; length <= bytes.size(); ++length) {
    Decoded d;
    decodeInto(d, std::string_view(bytes).substr(0, length), 4096);
    if (length < kHeaderBytes) {
      REQUIRE(d.vectors == 0);
      REQUIRE(!d.decoder.error().empty());  // "no QNV header" / "truncated"
      continue;
    }
    REQUIRE(d.ok);
    // 16 full packets of 6 records, then a last one of 4 records (48 bytes).
    const std::size_t packets = (length - kHeaderBytes) / packet;
    const bool lastArrived = packets == 16 && length - kHeaderBytes - 16 * packet >= 48;
    REQUIRE(d.vectors == packets * 6 + (lastArrived ? 4 : 0));
    REQUIRE(d.decoder.stats().packetsCorrupt == 0);
    REQUIRE(d.finished == (length == bytes.size()));
    for (const auto& [i, v] : d.byIndex) REQUIRE(same(v, whole.byIndex[i]));
  }
}

TEST_CASE("lost packets cost only their own vectors", "[qnv][stream]") {
  const std::uint32_t payload = GENERATE(48u, 1376u);
  const double loss = GENERATE(0.1, 0.5);
  const EncodedVectors& e = encoded();
  const std::string bytes = writeStream(e, {payload, PacketEncoding::plain});
  Decoded whole;
  decodeInto(whole, bytes, bytes.size());
  std::mt19937 rng(42);
  std::bernoulli_distribution drop(loss);
  std::string damaged = bytes.substr(0, kHeaderBytes);
  const std::size_t per = payload / 8;
  std::size_t kept = 0, lastKept = 0, packets = 0;
  for (std::size_t first = 0, seq = 0; first < e.records.size(); first += per, ++seq) {
    const std::size_t n = std::min(per, e.records.size() - first);
    const std::size_t at = kHeaderBytes + seq * (kPacketHeaderBytes + payload);
    ++packets;
    if (drop(rng)) continue;
    damaged += bytes.substr(at, kPacketHeaderBytes + n * 8);
    kept += n;
    lastKept = seq;
  }
  Decoded d;
  decodeInto(d, damaged, 333);
  REQUIRE(d.ok);
  CHECK(!d.finished);
  CHECK(d.vectors == kept);
  CHECK(d.decoder.stats().packetsCorrupt == 0);
  CHECK(d.decoder.stats().packetsMissing == lastKept + 1 - d.decoder.stats().packetsDecoded);
  CHECK(d.decoder.stats().packetsDecoded < packets);
  for (const auto& [i, v] : d.byIndex) REQUIRE(same(v, whole.byIndex[i]));
}

TEST_CASE("every flipped bit is caught by a CRC", "[qnv][stream]") {
  SurfaceEncodeOptions options;
  options.selection.count = 20;
  const std::string bytes =
      writeStream(encodeSurface(sphere(6), options), {48, PacketEncoding::plain});
  Decoded whole;
  decodeInto(whole, bytes, bytes.size());
  REQUIRE(whole.vectors == 20);
  for (std::size_t bit = 0; bit < bytes.size() * 8; ++bit) {
    std::string flipped = bytes;
    flipped[bit / 8] = static_cast<char>(flipped[bit / 8] ^ (1 << (bit % 8)));
    Decoded d;
    decodeInto(d, flipped, 100);
    if (bit / 8 < kHeaderBytes) {
      REQUIRE(d.vectors == 0);  // a damaged header is rejected, never misread
      REQUIRE(!d.decoder.error().empty());
      continue;
    }
    REQUIRE(d.ok);
    REQUIRE(!d.finished);
    const std::size_t packet = (bit / 8 - kHeaderBytes) / (kPacketHeaderBytes + 48);
    REQUIRE(d.vectors == 20 - (packet < 3 ? 6 : 2));  // exactly the damaged packet's vectors
    REQUIRE(d.decoder.stats().packetsCorrupt == 1);
    for (const auto& [i, v] : d.byIndex) REQUIRE(same(v, whole.byIndex[i]));
  }
}

TEST_CASE("hostile streams give explicit errors", "[qnv][stream]") {
  std::string bytes = writeStream(encoded(), {48, PacketEncoding::plain});
  SECTION("an unknown version") {
    bytes[8] = 9;
    Decoded d;
    decodeInto(d, bytes, 64);
    CHECK(!d.ok);
    CHECK_THAT(d.decoder.error(), Catch::Contains("test.qnv: QNV version 9 is newer"));
  }
  SECTION("not a QNV stream") {
    Decoded d;
    decodeInto(d, "#VRML V2.0 utf8\nShape {}\n", 64);
    CHECK(!d.ok);
    CHECK_THAT(d.decoder.error(), Catch::Contains("not a QNV stream"));
  }
  SECTION("an impossible vector count, header CRC recomputed") {
    StreamHeader h = encoded().header;
    h.vectorCount = kMaxVectorCount + 1;
    bytes.replace(0, kHeaderBytes, serializeHeader(h));
    Decoded d;
    decodeInto(d, bytes, 4096);
    CHECK_THAT(d.decoder.error(), Catch::Contains("impossible vector count"));
  }
  SECTION("a packet claiming more records than a packet holds") {
    bytes[kHeaderBytes + 2] = 100;
    Decoded d;
    decodeInto(d, bytes, 4096);
    CHECK(d.ok);
    CHECK(d.decoder.stats().packetsCorrupt == 1);
    CHECK(d.vectors == encoded().records.size() - 6);
  }
  SECTION("trailing garbage") {
    bytes += "garbage after the end";
    Decoded d;
    decodeInto(d, bytes, 4096);
    CHECK(d.finished);
    CHECK(d.vectors == encoded().records.size());
    REQUIRE(!d.decoder.warnings().empty());
    CHECK_THAT(d.decoder.warnings().front(), Catch::Contains("trailing garbage"));
  }
  SECTION("random garbage after a valid header") {
    std::mt19937 rng(5);
    std::string junk = bytes.substr(0, kHeaderBytes);
    for (int i = 0; i < 200000; ++i)
      junk.push_back(static_cast<char>(i % 97 == 0 ? 'Q' : i % 89 == 0 ? 'P' : rng()));
    Decoded d;
    decodeInto(d, junk, 777);
    CHECK(d.ok);
    CHECK(d.vectors == 0);
  }
}

TEST_CASE("compact packets carry the same records in fewer bytes", "[qnv][stream]") {
  const EncodedVectors& e = encoded();
  const std::string plain = writeStream(e, {1376, PacketEncoding::plain});
  const std::string compact = writeStream(e, {1376, PacketEncoding::compact});
  CHECK(compact.size() < plain.size());
  Decoded a, b;
  decodeInto(a, plain, plain.size());
  decodeInto(b, compact, 100);
  REQUIRE(b.finished);
  REQUIRE(b.vectors == a.vectors);
  // Inside a compact packet records are in spatial order: compare per packet as sets.
  const std::size_t per = 1376 / 8;
  for (std::size_t first = 0; first < a.vectors; first += per) {
    std::multiset<std::tuple<float, float, float, float, std::uint32_t>> x, y;
    for (std::size_t i = first; i < std::min(a.vectors, first + per); ++i) {
      const DecodedVector& va = a.byIndex[i];
      const DecodedVector& vb = b.byIndex[i];
      x.insert({va.position.x, va.position.y, va.position.z, va.magnitude, va.rgba});
      y.insert({vb.position.x, vb.position.y, vb.position.z, vb.magnitude, vb.rgba});
    }
    REQUIRE(x == y);
  }
  // A damaged compact packet is caught too.
  std::string bad = compact;
  bad[kHeaderBytes + kPacketHeaderBytes + 3] ^= 0x10;
  Decoded c;
  decodeInto(c, bad, 100);
  CHECK(c.decoder.stats().packetsCorrupt == 1);
  CHECK(c.vectors == a.vectors - per);
}
