// splats::readGaussians on any bytes: every splat scene reader (PLY, compressed PLY, SPZ,
// SOG bundles, glTF) by content, and .splat, which has no magic, by the name given here.
// Side files (SOG's WebP images beside a meta.json, a .gltf's buffers) are never found.
// The same bytes are then read piecewise (splats::openGaussianBatches, the out-of-core
// encode's reader: binary and compressed PLY, .splat, SPZ v2-v4 and SOG bundles, by
// content) from a file named .ply or .splat by the input's size, in batches of 97
// splats, twice (rewound between), and as bytes arriving over HTTP
// (splats::openGaussianRows, the rows decoded from the bytes; splats::openGaussianColumns,
// the columns fed a piece at a time; splats::openGaussianStream, an SPZ v2/v3 fed a piece
// at a time). splats::gltfDrawsOnlyGaussians
// (a glTF capture or a world) reads them too.
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <vector>

#include "fuzz_support.hpp"
#include "splats/readers.hpp"

namespace {

// A file of this process for the piecewise reader (removed at exit with its folder).
struct ScratchFolder {
  std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("gs-fuzz-splats-" + std::to_string(::getpid()));
  ScratchFolder() { std::filesystem::create_directories(dir); }
  ~ScratchFolder() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const gs::splats::SideFileReader noFiles = [](const std::string&, std::string&,
                                                std::string& error) {
    error = "no side files while fuzzing";
    return false;
  };
  gs::fuzz::expectingErrors(
      [&] { (void)gs::splats::readGaussians(gs::fuzz::view(data, size), "fuzz.splat", noFiles); });
  (void)gs::splats::gltfDrawsOnlyGaussians(gs::fuzz::view(data, size));  // never throws
  static const ScratchFolder scratch;
  const std::filesystem::path file = scratch.dir / (size % 2 ? "scene.ply" : "scene.splat");
  {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  gs::fuzz::expectingErrors([&] {
    const auto reader = gs::splats::openGaussianBatches(file.string());
    gs::splats::GaussianCloud batch;
    for (int pass = 0; pass < 2; ++pass, reader->rewind())
      while (reader->read(batch, 97) > 0) {
      }
  });
  // And as bytes arriving over HTTP (splats::openGaussianRows): the first half, then the
  // whole, its rows decoded as the session decodes them.
  const std::string_view bytes = gs::fuzz::view(data, size);
  const std::string name = size % 2 ? "scene.ply" : "scene.splat";
  gs::fuzz::expectingErrors(
      [&] { (void)gs::splats::openGaussianRows(bytes.substr(0, size / 2), name, size); });
  gs::fuzz::expectingErrors([&] {
    const gs::splats::GaussianRows rows = gs::splats::openGaussianRows(bytes, name, size);
    if (!rows.decoder || rows.decoder->dataOffset() > size) return;
    const gs::splats::GaussianRowDecoder& d = *rows.decoder;
    const std::uint64_t whole =
        std::min<std::uint64_t>((size - d.dataOffset()) / d.rowBytes(), d.size());
    gs::splats::GaussianCloud batch;
    for (std::uint64_t first = 0; first < whole; first += 97) {
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(97, whole - first));
      d.decode(bytes.data() + d.dataOffset() + first * d.rowBytes(), first, n, batch);
    }
  });
  // And read by columns as over HTTP (splats::openGaussianColumns: SPZ v4, GLB, .gltf, SOG),
  // each column fed in pieces of 997 bytes (a .gltf's buffer file's and an SOG's images
  // from the input itself), the splats decoded 97 at a time as their records come.
  gs::fuzz::expectingErrors(
      [&] { (void)gs::splats::openGaussianColumns(bytes.substr(0, size / 2), name, size); });
  gs::fuzz::expectingErrors([&] {
    gs::splats::GaussianColumns found = gs::splats::openGaussianColumns(bytes, name, size);
    if (!found.decoder) return;
    gs::splats::GaussianColumnDecoder& d = *found.decoder;
    std::vector<std::unique_ptr<gs::splats::ColumnRecords>> columns;
    std::vector<gs::splats::ColumnRecords*> records;
    for (const auto& c : d.columns()) {
      columns.push_back(std::make_unique<gs::splats::ColumnRecords>(
          c, d.size(), name, static_cast<int>(columns.size())));
      records.push_back(columns.back().get());
      if (c.offset > size || c.bytes > size - c.offset) return;
    }
    gs::splats::GaussianCloud batch;
    std::uint64_t decoded = 0;
    for (std::uint64_t at = 0;; at += 997) {
      bool more = false;
      for (std::size_t k = 0; k < columns.size(); ++k) {
        const auto& c = d.columns()[k];
        // (A side file of unknown size, an SOG's image: the input after the column's offset.)
        const std::uint64_t bytesOf = c.bytes == 0 && c.webp ? size - c.offset : c.bytes;
        if (at >= bytesOf) continue;
        const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(997, bytesOf - at));
        columns[k]->feed(bytes.substr(static_cast<std::size_t>(c.offset + at), n));
        more = true;
      }
      // 97 splats a step while bytes come, then the rest 65,536 at a time.
      const std::size_t n =
          gs::splats::decodeColumns(d, records, decoded, more ? 97 : 65536, batch);
      decoded += n;
      if (n == 0 && !more) break;
    }
    for (const auto& c : columns) c->finish();
  });
  // And as one stream over HTTP (splats::openGaussianStream: SPZ v2/v3), fed 997 bytes at
  // a time, the splats taken 97 at a time as they come.
  gs::fuzz::expectingErrors([&] {
    const gs::splats::GaussianStream found = gs::splats::openGaussianStream(bytes, name, size);
    if (!found.decoder) return;
    gs::splats::GaussianCloud batch;
    for (std::size_t at = 0; at < size; at += 997) {
      found.decoder->feed(bytes.substr(at, 997));
      while (found.decoder->next(batch, 97) > 0) {
      }
    }
    found.decoder->finish();
  });
  return 0;
}
