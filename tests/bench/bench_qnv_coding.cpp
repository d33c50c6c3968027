// Packet codings compared (docs/qnv-format.md, "Compact coding"): for each plain .qnv
// stream given, re-packs its records at 1376, 16384 and 65528 record bytes per packet
// as plain, compact (zstd) and entropy (rANS; original and fast layout, each with and
// without the stream model) packets, and prints bits per vector, the
// entropy coding's bits per field, and StreamDecoder throughput on one thread (CRC,
// payload decode and dequantization into DecodedVectors; best of 7, thread CPU time).
//
// With `--magnitude-bits N` the records are first coarsened as `ghostspace encode
// --magnitude-bits N` does (qnv::coarsenMagnitudes; docs/qnv-format.md, "Shared low bits").
//
//   ghostspace encode CThead.nhdr --fraction 0.091 -o head.qnv
//   bench_qnv_coding head.qnv bunny.qnv
//   bench_qnv_coding --magnitude-bits 7 head.qnv
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "qnv/coding.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"

namespace qnv = gs::qnv;

namespace {

// The records of a stream, in stream order per packet.
bool readRecords(const std::string& path, qnv::EncodedVectors& out) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string bytes = buffer.str();
  std::string error;
  const auto header = qnv::parseHeader(bytes, path, error);
  if (!header) {
    std::fprintf(stderr, "bench_qnv_coding: %s\n", error.c_str());
    return false;
  }
  out.header = *header;
  // Decode, then re-quantize nothing: a plain stream's payload is the records. Walk the
  // packets directly so the records stay bit-exact.
  std::size_t at = qnv::kHeaderBytes;
  while (at + qnv::kPacketHeaderBytes <= bytes.size()) {
    std::uint16_t count = 0, payload = 0;
    std::memcpy(&count, bytes.data() + at + 2, 2);
    std::memcpy(&payload, bytes.data() + at + 8, 2);
    if (bytes[at + 10] != 0 || payload != count * 8u) {
      std::fprintf(stderr, "bench_qnv_coding: %s is not a plain stream\n", path.c_str());
      return false;
    }
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t r = 0;
      std::memcpy(&r, bytes.data() + at + qnv::kPacketHeaderBytes + 8 * i, 8);
      out.records.push_back(r);  // little-endian host assumed (x86-64, arm64)
    }
    at += qnv::kPacketHeaderBytes + payload;
  }
  return true;
}

// Thread CPU time: the shared development VM is loaded, and time spent descheduled is
// not the decoder's.
double cpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Vectors per second through StreamDecoder::feed in 64 KiB chunks, the header (and the
// dequantizer's tables and the stream model it builds) fed before the clock starts.
double decodeRate(const std::string& stream) {
  double best = 1e9;
  std::uint64_t got = 0;
  for (int rep = 0; rep < 7; ++rep) {
    qnv::StreamDecoder d("bench");
    got = 0;
    const auto sink = [&](std::uint64_t, std::span<const qnv::DecodedVector> v) {
      got += v.size();
    };
    std::string error;
    const std::size_t headerBytes = qnv::parseHeader(stream, "bench", error)->headerBytes;
    d.feed(std::string_view(stream).substr(0, headerBytes), sink);
    const double t0 = cpuSeconds();
    for (std::size_t at = headerBytes; at < stream.size(); at += 1 << 16)
      d.feed(std::string_view(stream).substr(at, 1 << 16), sink);
    d.finish(sink);
    best = std::min(best, cpuSeconds() - t0);
  }
  return static_cast<double>(got) / best / 1e6;
}

}  // namespace

int main(int argc, char** argv) {
  int first = 1, magnitudeBits = qnv::kMagnitudeBits;
  if (argc > 2 && std::strcmp(argv[1], "--magnitude-bits") == 0) {
    magnitudeBits = std::atoi(argv[2]);
    first = 3;
  }
  if (argc <= first || magnitudeBits < 1 || magnitudeBits > qnv::kMagnitudeBits) {
    std::fprintf(stderr, "usage: bench_qnv_coding [--magnitude-bits N] PLAIN.qnv...\n");
    return 2;
  }
  for (int i = first; i < argc; ++i) {
    qnv::EncodedVectors e;
    if (!readRecords(argv[i], e)) return 1;
    // As `ghostspace encode --magnitude-bits N` writes them (exact streams in).
    qnv::coarsenMagnitudes(e.records, magnitudeBits);
    const double n = static_cast<double>(e.records.size());
    std::printf("== %s: %zu vectors, magnitudes of %d bits ==\n", argv[i], e.records.size(),
                magnitudeBits);
    std::printf("%8s %-14s %10s %9s %12s\n", "packet", "coding", "bytes", "bits/vec", "decode M/s");
    for (std::uint32_t packet : {1376u, 16384u, 65528u}) {
      for (int variant = 0; variant < 6; ++variant) {
        const auto coding = variant == 0   ? qnv::PacketEncoding::plain
                            : variant == 1 ? qnv::PacketEncoding::compact
                                           : qnv::PacketEncoding::entropy;
        qnv::WriteOptions options{packet, coding};
        options.streamModel = variant == 3 || variant == 5;
        options.fastEntropy = variant >= 4;
        const std::string s = qnv::writeStream(e, options);
        const char* names[] = {"plain",         "compact",      "entropy",
                               "entropy+model", "entropy-fast", "fast+model"};
        std::printf("%8u %-14s %10zu %9.2f %12.1f", packet, names[variant], s.size(),
                    8.0 * static_cast<double>(s.size() - qnv::kHeaderBytes) / n, decodeRate(s));
        std::string error;
        const std::size_t headerBytes = qnv::parseHeader(s, "bench", error)->headerBytes;
        if (headerBytes > qnv::kHeaderBytes) {  // the model's one-off cost
          const double t0 = cpuSeconds();
          qnv::StreamDecoder d("bench");
          d.feed(std::string_view(s).substr(0, headerBytes), nullptr);
          std::printf("  (model %zu bytes, header decoded in %.2f ms)",
                      headerBytes - qnv::kHeaderBytes, 1e3 * (cpuSeconds() - t0));
        }
        std::printf("\n");
      }
      for (int variant = 0; variant < 4; ++variant) {
        const bool model = variant % 2 == 1, fast = variant >= 2;
        const qnv::CodingBits b = qnv::entropyCodingBits(e, packet, model, fast);
        std::printf(
            "%8u %-14s bits/vector by field: position %.2f, direction %.2f, magnitude %.2f, "
            "colour %.2f, tables %.2f, framing %.2f, model %.2f = %.2f (%llu packets on blocks)\n",
            packet,
            fast ? (model ? "fast+model" : "entropy-fast") : (model ? "entropy+model" : "entropy"),
            b.position / n, b.direction / n, b.magnitude / n, b.color / n, b.tables / n,
            b.framing / n, b.model / n, b.total() / n,
            static_cast<unsigned long long>(b.blockPackets));
      }
    }
  }
  return 0;
}
