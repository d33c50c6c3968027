// Writes seed inputs for the QNV fuzz targets into the folder given as the one argument:
// a small volume stream in plain and compact packets (and one with packets damaged), and
// compact payloads prefixed with their record count as fuzz_qnv_compact reads them, and
// entropy payloads (original and fast layout) with and without a stream model (kind 1, and
// kind 2 with the blocks' directions) as fuzz_qnv_entropy reads them.
// Generated rather than committed so that they follow the format of this build.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "compact_payload.hpp"
#include "entropy_payload.hpp"
#include "qnv/encoder.hpp"
#include "qnv/stream.hpp"

namespace {

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: make_qnv_seeds FOLDER\n");
    return 2;
  }
  const std::string dir = argv[1];
  gs::qnv::Volume v;
  v.dims = {8, 8, 8};
  v.samples.resize(v.voxelCount());
  for (std::uint32_t z = 0; z < 8; ++z)
    for (std::uint32_t y = 0; y < 8; ++y)
      for (std::uint32_t x = 0; x < 8; ++x)
        v.samples[x + 8 * (y + 8 * z)] =
            std::max(0.0f, 255.0f - 40.0f * std::hypot(x - 3.5f, y - 3.5f, z - 3.5f));
  const gs::qnv::EncodedVectors e = gs::qnv::encodeVolume(v, {});
  gs::qnv::WriteOptions w;
  w.packetBytes = 48;
  const std::string plain = gs::qnv::writeStream(e, w);
  write(dir + "/ball_plain.qnv", plain);
  std::string damaged = plain;
  if (damaged.size() > gs::qnv::kHeaderBytes + 100) damaged[gs::qnv::kHeaderBytes + 70] ^= 0x20;
  write(dir + "/ball_damaged.qnv", damaged);
  w.packetBytes = 512;
  w.encoding = gs::qnv::PacketEncoding::compact;
  write(dir + "/ball_compact.qnv", gs::qnv::writeStream(e, w));
  for (std::size_t count : {std::size_t{1}, std::size_t{7}, std::size_t{64}}) {
    if (count > e.records.size()) break;
    std::string payload;
    payload += static_cast<char>((count - 1) & 0xff);
    payload += static_cast<char>((count - 1) >> 8);
    gs::qnv::detail::appendCompactPayload(payload, {e.records.data(), count});
    write(dir + "/compact_" + std::to_string(count) + ".bin", payload);
  }
  // Entropy payloads of a 48 x 44 x 24 shell (fuzz_qnv_entropy's volume header): the
  // first 64 records of its stream order, with and without the stream's model.
  gs::qnv::Volume shell;
  shell.dims = {48, 44, 24};
  shell.samples.resize(shell.voxelCount());
  for (std::uint32_t z = 0; z < 24; ++z)
    for (std::uint32_t y = 0; y < 44; ++y)
      for (std::uint32_t x = 0; x < 48; ++x)
        shell.samples[x + 48 * (y + 44 * z)] =
            1000.0f /
            (1.0f + std::exp(2.0f * (std::hypot(x - 20.0f, y - 22.0f, z - 11.0f) - 9.0f)));
  gs::qnv::VolumeEncodeOptions thin;
  thin.selection.fraction = 0.05;
  const gs::qnv::EncodedVectors s = gs::qnv::encodeVolume(shell, thin);
  // Variants 4 and 5: under a kind-2 model (the blocks with their directions), whose
  // payloads code theta and phi from the blocks (flag bit 3).
  const std::vector<std::string> models =
      gs::qnv::detail::streamModelCandidates(s.header, s.records);
  // Variants 6 and 7: magnitudes coarsened to 8 bits (`encode --magnitude-bits 8`), whose
  // payloads send the low bits the records share once.
  std::vector<std::uint64_t> rounded = s.records;
  gs::qnv::coarsenMagnitudes(rounded, 8);
  for (int variant = 0; variant < 8; ++variant) {
    // plain, model, fast plain, fast model, directions, fast directions, low bits, fast
    // low bits
    const bool model = variant == 1 || variant == 3 || variant == 4 || variant == 5;
    const bool fast = variant == 2 || variant == 3 || variant == 5 || variant == 7;
    gs::qnv::StreamHeader h = s.header;
    const std::span<const std::uint64_t> records(
        (variant >= 6 ? rounded : s.records).data(),
        std::min<std::size_t>(fast ? 300 : 64, s.records.size()));
    if (model) h.model = variant >= 4 ? models.at(1) : models.at(0);
    std::string input;
    input += '\1';
    input += static_cast<char>((records.size() - 1) & 0xff);
    input += static_cast<char>((records.size() - 1) >> 8);
    input += static_cast<char>(h.model.size() & 0xff);
    input += static_cast<char>(h.model.size() >> 8);
    input += h.model;
    gs::qnv::detail::appendEntropyPayload(
        input, records, gs::qnv::detail::PositionGrid::forHeader(h), nullptr, fast);
    write(dir + (fast ? "/entropy_fast" : "/entropy") +
              (variant >= 6   ? "_low_bits.bin"
               : variant >= 4 ? "_directions.bin"
               : model        ? "_model.bin"
                              : "_plain.bin"),
          input);
  }
  return 0;
}
