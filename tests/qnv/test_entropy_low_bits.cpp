// Magnitude codes rounded to fewer bits (roundMagnitudeCode, coarsenMagnitudes: `ghostspace
// encode --magnitude-bits`) and the entropy packets' shared low bits (docs/qnv-format.md, "Shared
// low bits"): the magnitude byte's high nibble says how many low bits every offset A - aMin
// shares, and those are sent once, in both layouts.
#include <catch2/catch.hpp>

#include <bit>
#include <cmath>
#include <set>

#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "qnv/record.hpp"
#include "stream_support.hpp"

using namespace gs::qnv;
using gs::qnv::packets::DecodedStream;
using gs::qnv::packets::decodeStream;
using gs::qnv::packets::packetStarts;
using gs::qnv::packets::plainDecoded;
using gs::qnv::packets::resealPacket;

namespace {

// Two shells of different density, 48 x 44 x 24 voxels: a wide range of magnitudes.
const EncodedVectors& shellVectors() {
  static const EncodedVectors e =
      gs::qnv::packets::sphereShellVectors({48, 44, 24}, 22, 21, 23, 15, 2.5f, 0.4);
  return e;
}

EncodedVectors rounded(int bits) {
  EncodedVectors e = shellVectors();
  coarsenMagnitudes(e.records, bits);
  return e;
}

// The packets' offsets, after the header (whose size grows with a stream model).
std::vector<std::size_t> starts(const std::string& s) {
  std::string why;
  const auto header = parseHeader(s, "x.qnv", why);
  REQUIRE(header);
  return packetStarts(s, header->headerBytes);
}

}  // namespace

TEST_CASE("magnitude codes rounded to fewer bits keep their top bits and sort order",
          "[qnv][record]") {
  std::size_t unchanged = 0, wrong = 0;
  for (std::uint32_t q = 0; q < kMagnitudeSteps; ++q) unchanged += roundMagnitudeCode(q, 15) == q;
  CHECK(unchanged == kMagnitudeSteps);
  for (int bits = 1; bits < 15; ++bits) {
    const int drop = 15 - bits;
    std::uint32_t previous = 0;
    for (std::uint32_t q = 0; q < kMagnitudeSteps; ++q) {
      const std::uint32_t r = roundMagnitudeCode(q, bits);
      wrong += r >= kMagnitudeSteps || r >> drop != q >> drop   // the same coarse cell
               || (r & ((1u << drop) - 1)) != 1u << (drop - 1)  // its middle
               || r < previous;                                 // monotone
      previous = r;
    }
  }
  CHECK(wrong == 0);
  // At 10 bits over a range of 10^4 the reconstruction is within half a coarse step, 0.45%
  // ((10^4)^(2^-11) - 1), plus half a fine one, of the exact code's.
  const float lo = 0.01f, hi = 100.0f;
  double worst = 0;
  for (std::uint32_t q = 0; q < kMagnitudeSteps; q += 7) {
    const double a = reconstructMagnitude(q, MagnitudeMapping::logarithmic, lo, hi);
    const double b =
        reconstructMagnitude(roundMagnitudeCode(q, 10), MagnitudeMapping::logarithmic, lo, hi);
    worst = std::max(worst, std::abs(b / a - 1.0));
  }
  CHECK(worst < 0.00452);
  CHECK(worst > 0.00448);
}

TEST_CASE("coarsened magnitudes stay sorted largest first, each run of equal codes in Morton order",
          "[qnv][record]") {
  const std::vector<std::uint64_t>& exact = shellVectors().records;
  std::vector<std::uint64_t> same = exact;
  coarsenMagnitudes(same, 15);
  CHECK(same == exact);
  std::vector<std::uint64_t> coarse = exact;
  coarsenMagnitudes(coarse, 8);
  // The same records but for A, rounded.
  std::vector<std::uint64_t> roundedOnly = exact;
  roundMagnitudes(roundedOnly, 8);
  CHECK(std::multiset<std::uint64_t>(coarse.begin(), coarse.end()) ==
        std::multiset<std::uint64_t>(roundedOnly.begin(), roundedOnly.end()));
  const auto morton = [](std::uint64_t r) {
    const RecordFields f = unpackRecord(r);
    std::uint64_t m = 0;
    for (int b = 0; b < 10; ++b)
      m |= (std::uint64_t{(f.x >> b) & 1u} << (3 * b)) |
           (std::uint64_t{(f.y >> b) & 1u} << (3 * b + 1)) |
           (std::uint64_t{(f.z >> b) & 1u} << (3 * b + 2));
    return m;
  };
  std::size_t outOfOrder = 0, runs = 1;
  for (std::size_t i = 1; i < coarse.size(); ++i) {
    const std::uint32_t a = magnitudeCode(coarse[i - 1]), b = magnitudeCode(coarse[i]);
    outOfOrder += b > a || (b == a && morton(coarse[i]) < morton(coarse[i - 1]));
    runs += b != a;
  }
  CHECK(outOfOrder == 0);
  CHECK(runs > 20);  // many codes, each a run
  CHECK(runs < coarse.size() / 20);
  CHECK(coarse != roundedOnly);  // the rounding alone left runs in exact-magnitude order
}

TEST_CASE("entropy packets send the low magnitude bits their records share once",
          "[qnv][entropy]") {
  const std::size_t n = shellVectors().records.size();
  REQUIRE(n > 5000);
  for (const bool fast : {false, true})
    for (const bool model : {false, true}) {
      INFO((fast ? "fast layout" : "original layout") << (model ? ", stream model" : ""));
      WriteOptions options{16384, PacketEncoding::entropy, model, fast};
      const std::size_t exact = writeStream(shellVectors(), options).size();
      std::size_t previous = exact;
      for (const int bits : {12, 10, 8}) {
        const EncodedVectors e = rounded(bits);
        const std::string s = writeStream(e, options);
        const DecodedStream b = decodeStream(s, 1000);
        REQUIRE(b.finished);
        CHECK(b.stats.packetsCorrupt == 0);
        CHECK(b.byFirst == plainDecoded(e, 16384).byFirst);
        // Each packet's magnitude byte: the offsets' width, and the low bits they share.
        const std::size_t perPacket = 16384 / 8;
        const std::vector<std::size_t> packets = starts(s);
        REQUIRE(packets.size() == (n + perPacket - 1) / perPacket);
        for (std::size_t p = 0; p < packets.size(); ++p) {
          std::uint32_t aMin = kMagnitudeSteps, aMax = 0, used = 0;
          for (std::size_t i = p * perPacket; i < std::min(n, (p + 1) * perPacket); ++i) {
            aMin = std::min(aMin, magnitudeCode(e.records[i]));
            aMax = std::max(aMax, magnitudeCode(e.records[i]));
          }
          for (std::size_t i = p * perPacket; i < std::min(n, (p + 1) * perPacket); ++i)
            used |= magnitudeCode(e.records[i]) - aMin;
          const int shift = used == 0 ? 0 : std::countr_zero(used);
          const auto byte = static_cast<unsigned char>(s[packets[p] + kPacketHeaderBytes + 3]);
          CHECK(byte >> 4 == shift);
          CHECK((byte & 15) == std::bit_width((aMax - aMin) >> shift));
          CHECK((used == 0 || shift >= 15 - bits));
        }
        // Each packet spans thousands of codes: 10 bits save 5 bits a vector, 4 at least.
        if (bits == 10) CHECK(s.size() * 8 + n * 4 < exact * 8);
        CHECK(s.size() < previous);
        previous = s.size();
      }
    }
}

TEST_CASE("a magnitude byte whose width and shift overrun 15 bits refuses its packet",
          "[qnv][entropy]") {
  for (const bool fast : {false, true}) {
    INFO((fast ? "fast layout" : "original layout"));
    const std::string s = writeStream(rounded(10), {16384, PacketEncoding::entropy, true, fast});
    const std::size_t at = starts(s)[1];
    const std::size_t byteAt = at + kPacketHeaderBytes + 3;
    const int width = static_cast<unsigned char>(s[byteAt]) & 15;
    REQUIRE(width > 0);
    const std::size_t whole = decodeStream(s).vectors;
    const std::size_t lost = 16384 / 8;
    for (int shift = 0; shift < 16; ++shift) {
      std::string t = s;
      t[byteAt] = static_cast<char>(width | (shift << 4));
      resealPacket(t, at, gs::qnv::packets::payloadBytes(t, at));
      const DecodedStream p = decodeStream(t);
      INFO("width " << width << ", shift " << shift);
      if (width + shift > 15) {
        CHECK(p.stats.packetsCorrupt == 1);
        CHECK(p.vectors == whole - lost);
      }
      CHECK(p.vectors + lost * p.stats.packetsCorrupt == whole);
    }
  }
  // A packet whose magnitudes are all one code has no width, and then no shift either.
  for (const bool fast : {false, true}) {
    EncodedVectors e = shellVectors();
    e.records.resize(300);
    for (std::uint64_t& r : e.records) r = (r & ~(std::uint64_t{32767} << 8)) | (1234u << 8);
    const std::string s = writeStream(e, {16384, PacketEncoding::entropy, false, fast});
    const std::size_t at = starts(s)[0];
    const std::size_t byteAt = at + kPacketHeaderBytes + 3;
    REQUIRE(s[byteAt] == 0);
    CHECK(decodeStream(s).vectors == 300);
    std::string t = s;
    t[byteAt] = static_cast<char>(3 << 4);
    resealPacket(t, at, gs::qnv::packets::payloadBytes(t, at));
    const DecodedStream p = decodeStream(t);
    CHECK(p.stats.packetsCorrupt == 1);
    CHECK(p.vectors == 0);
  }
}
