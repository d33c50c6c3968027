// `ghostspace encode`: any supported input to a .qnv stream.
#include <cctype>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "app/commands.hpp"
#include "app/progress_bar.hpp"
#include "base/fetch.hpp"
#include "base/file.hpp"
#include "encode_tileset.hpp"
#include "formats/input_kind.hpp"
#include "formats/volume_readers.hpp"
#include "formats/volume_slabs.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "scene/world_triangles.hpp"
#include "session/mesh_input.hpp"
#include "session/splat_inputs.hpp"
#include "session/volume_input.hpp"
#include "session/world.hpp"
#include "splats/gaussian_tileset.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"

namespace gs::app {

namespace {

/// Splits "a,b,c" (or "a:b", "AxBxC") and parses each part as T; false on any junk.
template <typename T>
bool parseList(const std::string& text, std::size_t n, const char* separators, T* out) {
  std::size_t at = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t end = i + 1 < n ? text.find_first_of(separators, at) : text.size();
    if (end == std::string::npos) return false;
    const char* b = text.data() + at;
    const char* e = text.data() + end;
    auto [p, ec] = std::from_chars(b, e, out[i]);
    if (ec != std::errc() || p != e) return false;
    at = end + 1;
  }
  return true;
}

struct Settings {
  qnv::Selection selection;
  qnv::MagnitudeMapping mapping = qnv::MagnitudeMapping::logarithmic;
  std::optional<std::pair<float, float>> window;
  std::optional<formats::RawLayout> raw;
  qnv::WriteOptions write;
};

/// Checks the encode options; returns an empty string or the usage error.
std::string parseSettings(const EncodeOptions& e, Settings& s) {
  if (e.output.empty() == e.tileset.empty())
    return "encode: give either -o OUT.qnv or --tileset OUT/";
  if (e.tileset.empty() && !e.bricks.empty()) return "encode: --bricks I/N needs --tileset OUT/";
  if (e.tileset.empty() && e.memoryMB > 0) return "encode: --memory MB needs --tileset OUT/";
  if (!e.tileset.empty() && e.magnitudeBits != qnv::kMagnitudeBits)
    return "encode: --magnitude-bits is for streams (-o OUT.qnv), not --tileset";
  if (!(e.fraction > 0.0 && e.fraction <= 1.0))
    return "encode: --fraction must be in (0, 1], got " + std::to_string(e.fraction);
  s.selection.fraction = e.fraction;
  s.selection.count = e.count;
  if (e.magnitude == "linear")
    s.mapping = qnv::MagnitudeMapping::linear;
  else if (e.magnitude != "log")
    return "encode: --magnitude: expected log or linear, got '" + e.magnitude + "'";
  if (!e.valueWindow.empty()) {
    float w[2];
    if (!parseList(e.valueWindow, 2, ":,", w) || !(w[0] <= w[1]))
      return "encode: --window: expected LO:HI with LO <= HI, got '" + e.valueWindow + "'";
    s.window = std::make_pair(w[0], w[1]);
  }
  if (!e.rawDims.empty()) {
    formats::RawLayout layout;
    unsigned dims[3];
    if (!parseList(e.rawDims, 3, ",x", dims))
      return "encode: --raw-dims: expected X,Y,Z, got '" + e.rawDims + "'";
    layout.dims = glm::uvec3(dims[0], dims[1], dims[2]);
    float spacing[3];
    if (!parseList(e.rawSpacing, 3, ",x", spacing))
      return "encode: --raw-spacing: expected SX,SY,SZ, got '" + e.rawSpacing + "'";
    layout.spacing = glm::vec3(spacing[0], spacing[1], spacing[2]);
    try {
      layout.type = formats::parseScalarType(e.rawType);
    } catch (const qnv::InputError& error) {
      return std::string("encode: --raw-type: ") + error.what();
    }
    layout.bigEndian = e.rawBigEndian;
    layout.headerBytes = static_cast<std::size_t>(e.rawHeaderBytes);
    s.raw = layout;
  }
  if (e.packetBytes < qnv::kMinPacketBytes || e.packetBytes > qnv::kMaxPacketBytes ||
      e.packetBytes % 8 != 0)
    return "encode: --packet-bytes must be a multiple of 8 from 8 to 65528, got " +
           std::to_string(e.packetBytes);
  s.write.packetBytes = e.packetBytes;
  s.write.encoding = e.compact ? qnv::PacketEncoding::compact : qnv::PacketEncoding::plain;
  if (e.coding == "plain") s.write.encoding = qnv::PacketEncoding::plain;
  if (e.coding == "compact") s.write.encoding = qnv::PacketEncoding::compact;
  if (e.coding == "entropy" || e.coding == "entropy-fast")
    s.write.encoding = qnv::PacketEncoding::entropy;
  s.write.fastEntropy = e.coding == "entropy-fast";
  s.write.streamModel = true;  // entropy only, and only where it saves bytes
  return {};
}

std::string withCommas(std::uint64_t n) {
  std::string s = std::to_string(n);
  for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3)
    s.insert(static_cast<std::size_t>(i), ",");
  return s;
}

void printSummary(const std::string& input, const qnv::EncodeSummary& summary,
                  const char* elements) {
  std::printf("%s: %s %s, %s with a non-zero magnitude, kept %s (%.2f%%)\n", input.c_str(),
              withCommas(summary.elements).c_str(), elements,
              withCommas(summary.candidates).c_str(), withCommas(summary.kept).c_str(),
              summary.elements ? 100.0 * static_cast<double>(summary.kept) /
                                     static_cast<double>(summary.elements)
                               : 0.0);
}

// A stack of 2-D slices (formats/volume_slabs.hpp): a folder, a printf-style pattern, or
// one PNG or TIFF file.
bool isSliceStack(const std::string& input) {
  if (formats::classifyFile(input) == formats::InputKind::dicom) return false;  // a series
  std::error_code ec;
  if (std::filesystem::is_directory(input, ec) || input.find('%') != std::string::npos) return true;
  std::string ext = std::filesystem::path(input).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".png" || ext == ".tif" || ext == ".tiff";
}

// The whole volume of a volume file; the NRRD multi-file forms, which the session's
// loader refuses, through the slab readers.
qnv::Volume loadWholeVolume(const std::string& input) {
  std::unique_ptr<qnv::VolumeSlabReader> reader;
  try {
    return session::loadVolumeFile(input);
  } catch (const qnv::InputError&) {
    try {
      reader = formats::openVolumeSlabs(input);
    } catch (const qnv::InputError&) {
      reader.reset();
    }
    if (!reader) throw;  // the session loader's sentence
  }
  return qnv::readWholeVolume(*reader);
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

bool writeOutput(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) std::fprintf(stderr, "ghostspace: cannot write '%s'\n", path.c_str());
  return static_cast<bool>(out);
}

// The Gaussian splatting scene `input` (any format splats::readGaussians reads, with its
// side files); nullopt, the reason printed, when it cannot be read.
std::optional<splats::GaussianCloud> readSplatScene(const std::string& input) {
  std::string bytes, error;
  if (!base::readFile(input, bytes, error, std::size_t{16} << 30)) {
    std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
    return std::nullopt;
  }
  base::LocalFetcher fetcher;
  try {
    return splats::readGaussians(bytes, input, session::sideFileReader(fetcher, input));
  } catch (const splats::FormatError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
  }
  return std::nullopt;
}

// The packets of a Gaussian stream or tileset: compact unless --coding plain (entropy
// coding is for vectors; --compact's default of plain is the vectors' too).
qnv::PacketEncoding gaussianEncoding(const EncodeOptions& e) {
  return e.coding == "plain" ? qnv::PacketEncoding::plain : qnv::PacketEncoding::compact;
}

// A 3D Gaussian splatting scene as a QNV Gaussian stream (splats/qnv_gaussians.hpp),
// importance first. Packets: compact unless --coding plain; as large as --packet-bytes
// allows in whole splats (the default, 1376, gives the largest: zstd needs room).
int encodeGaussianScene(const Options& options, Settings s, const std::string& input) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::optional<splats::GaussianCloud> scene = readSplatScene(input);
  if (!scene) return 1;
  const splats::GaussianCloud& cloud = *scene;
  try {
    const qnv::EncodedVectors vectors = splats::encodeGaussianStream(
        cloud, {.shBits = options.encode.shBits, .shFullFraction = options.encode.shFull});
    const std::uint32_t splatBytes = 8 * vectors.header.recordsPerElement();
    if (options.encode.packetBytes == EncodeOptions{}.packetBytes)
      s.write.packetBytes = vectors.header.packetBytes;
    s.write.encoding = gaussianEncoding(options.encode);
    const std::string stream = qnv::writeStream(vectors, s.write);
    const std::size_t kept = vectors.records.size() / (splatBytes / 8);
    if (kept == 0) {  // never a silent success: nothing written, exit 1
      std::fprintf(stderr,
                   "ghostspace: %s: nothing to encode: %s Gaussians, none with an opacity and "
                   "a size\n",
                   input.c_str(), withCommas(cloud.size()).c_str());
      return 1;
    }
    std::printf("%s: %s Gaussians (SH degree %d), kept %s\n", input.c_str(),
                withCommas(cloud.size()).c_str(), cloud.shDegree, withCommas(kept).c_str());
    if (!writeOutput(options.encode.output, stream)) return 1;
    std::printf(
        "%s: %s bytes, %.2f bytes per splat (header and packets included), %s packets; "
        "%.3f s\n",
        options.encode.output.c_str(), withCommas(stream.size()).c_str(),
        kept ? static_cast<double>(stream.size()) / static_cast<double>(kept) : 0.0,
        withCommas((vectors.records.size() * 8 + s.write.packetBytes - 1) / s.write.packetBytes)
            .c_str(),
        secondsSince(t0));
    return 0;
  } catch (const qnv::InputError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
  }
  return 1;
}

// A 3D Gaussian splatting scene as a QNV tileset of Gaussian bricks
// (splats/gaussian_tileset.hpp; docs/tilesets.md, "Gaussian tilesets").
int encodeGaussianTileset(const Options& options, const Settings& s, const std::string& input) {
  const auto t0 = std::chrono::steady_clock::now();
  encode::TilesetTarget target;
  qnv::WriteOptions write = s.write;
  write.encoding = gaussianEncoding(options.encode);
  if (!tilesetTarget(options.encode, write, target)) return 2;
  if (options.encode.memoryMB > 0)  // out of core: encode/src/ooc_gaussian.cpp
    return writeGaussianTilesetOutOfCore(options, target, input);
  const std::optional<splats::GaussianCloud> cloud = readSplatScene(input);
  if (!cloud) return 1;
  if (options.encode.mergedCells == 1)  // --merged-cells not given: 16 or 32, by the scene
    target.cut.mergedCellsLog2 = splats::defaultGaussianMergedCellsLog2(*cloud);
  if (options.encode.brickVectors == 0)  // --brick-vectors not given: by the splats kept
    target.cut.brickVectors =
        splats::defaultGaussianBrickVectors(splats::gaussianFrame(*cloud).kept.size());
  const encode::TilesetResult r = encode::writeGaussianTileset(
      target, *cloud, {.shBits = options.encode.shBits, .shFullFraction = options.encode.shFull},
      options.encode.threads);
  if (!r.ok()) {
    // As writeTileset: bad options or input 2, a file not written 1.
    std::fprintf(stderr, "ghostspace: encode: %s: %s\n", input.c_str(), r.error.c_str());
    return r.failure == encode::Failure::input ? 2 : 1;
  }
  // (A share's index is its own bricks': the splats kept are the merge's to count.)
  const qnv::StreamHeader& h = r.merged.index.header;
  const std::string kept =
      target.whole ? ", kept " + withCommas(h.vectorCount / h.recordsPerElement()) : "";
  std::printf("%s: %s Gaussians (SH degree %d)%s\n", input.c_str(),
              withCommas(cloud->size()).c_str(), cloud->shDegree, kept.c_str());
  printEncodeResult(target, input, r, secondsSince(t0));
  return 0;
}

}  // namespace

int runEncode(const Options& options) {
  if (options.encode.outline) return runEncodeOutline(options);  // encode_outline.cpp
  Settings s;
  if (const std::string usage = parseSettings(options.encode, s); !usage.empty()) {
    std::fprintf(stderr, "ghostspace: %s\n", usage.c_str());
    return 2;
  }
  const std::string& input = options.inputs.front();
  ProgressBar bar("encoding", stderr, options.encode.progress);
  const auto progress = [&bar](double f) { bar.update(f); };
  const auto t0 = std::chrono::steady_clock::now();
  qnv::EncodedVectors vectors;
  qnv::SelectedVectors selected;  // --tileset: quantized per brick (encode_tileset.cpp)
  const bool tileset = !options.encode.tileset.empty();
  qnv::EncodeSummary summary;
  const char* elements = "triangles";
  if (options.encode.shFull != EncodeOptions{}.shFull && options.encode.shBits == 5) {
    bar.finish();  // never a silent no-op: every splat keeps every bit without --sh-bits
    std::fprintf(stderr,
                 "ghostspace: encode: --sh-full keeps the bits --sh-bits drops: give --sh-bits "
                 "N (1..4) with it\n");
    return 2;
  }
  if (!tileset && !s.raw && session::isGaussianSplatFile(input))
    return encodeGaussianScene(options, s, input);  // below
  if (tileset && !s.raw && session::isGaussianSplatFile(input)) {
    bar.finish();
    return encodeGaussianTileset(options, s, input);  // below
  }
  if (options.encode.shBits != EncodeOptions{}.shBits ||
      options.encode.shFull != EncodeOptions{}.shFull) {
    bar.finish();
    std::fprintf(stderr,
                 "ghostspace: encode: --sh-bits and --sh-full are for streams of Gaussian "
                 "splatting scenes "
                 "(.ply with Gaussian properties, .spz, .splat, .sog, .glb ...), not '%s'%s\n",
                 input.c_str(), tileset ? " as a --tileset" : "");
    return 2;
  }
  try {
    const bool stack = !s.raw && isSliceStack(input);
    const formats::InputKind kind =
        stack ? formats::InputKind::unknown : formats::classifyFile(input);
    if (s.raw || stack || formats::isVolume(kind)) {
      qnv::VolumeEncodeOptions v;
      v.selection = s.selection;
      v.mapping = s.mapping;
      v.valueWindow = s.window;
      if (tileset && options.encode.memoryMB > 0) {  // out of core: encode/src/ooc_volume.cpp
        bar.finish();
        const auto reader = formats::openVolumeSlabs(input, s.raw ? &*s.raw : nullptr);
        return writeVolumeTilesetOutOfCore(options, *reader, v, s.write, input);
      }
      const qnv::Volume volume = s.raw   ? session::loadRawVolumeFile(input, *s.raw)
                                 : stack ? qnv::readWholeVolume(*formats::openVolumeSlabs(input))
                                         : loadWholeVolume(input);
      v.progress = progress;
      if (tileset)
        selected = qnv::selectVolumeVectors(volume, v, &summary);
      else
        vectors = qnv::encodeVolume(volume, v, &summary);
      elements = "voxels";
    } else {
      if (options.encode.memoryMB > 0 && kind != formats::InputKind::ply)
        throw qnv::InputError(
            "--memory: out-of-core encoding reads volumes, PLY meshes and Gaussian splatting "
            "scenes (binary .ply, .splat) only, not '" +
            input + "' (docs/out-of-core.md)");
      if (options.encode.memoryMB > 0) {  // out of core: encode/src/ooc_mesh.cpp
        bar.finish();
        qnv::SurfaceEncodeOptions v;
        v.selection = s.selection;
        v.mapping = s.mapping;
        return writeMeshTilesetOutOfCore(options, input, v, s.write);
      }
      qnv::TriangleMesh mesh;
      if (formats::isMesh(kind)) {
        mesh = session::loadMeshFile(input);
      } else {
        const session::LoadedWorld world = session::loadWorld(input);
        for (const vrml::Diagnostic& d : world.scene->diagnostics.items)
          std::fprintf(stderr, "%s\n", d.format().c_str());
        if (!world.readable) return 1;
        mesh = scene::worldTriangles(world.scene);
      }
      qnv::SurfaceEncodeOptions v;
      v.selection = s.selection;
      v.mapping = s.mapping;
      v.progress = progress;
      if (tileset)
        selected = qnv::selectSurfaceVectors(mesh, v, &summary);
      else
        vectors = qnv::encodeSurface(mesh, v, &summary);
    }
  } catch (const qnv::InputError& error) {
    std::fprintf(stderr, "ghostspace: %s\n", error.what());
    return 1;
  }
  if (summary.kept == 0) {  // never a silent success: nothing written, exit 1
    bar.finish();
    std::fprintf(stderr,
                 "ghostspace: %s: nothing to encode: %s %s, none with a non-zero magnitude%s\n",
                 input.c_str(), withCommas(summary.elements).c_str(), elements,
                 summary.elements ? " in the selection" : "");
    return 1;
  }
  qnv::coarsenMagnitudes(vectors.records, options.encode.magnitudeBits);
  const std::string bytes = tileset ? std::string() : qnv::writeStream(vectors, s.write);
  bar.finish();
  printSummary(input, summary, elements);
  if (tileset) return writeTileset(options, selected, s.write, input, secondsSince(t0));
  const double seconds = secondsSince(t0);
  if (!writeOutput(options.encode.output, bytes)) return 1;
  const double bitsPerVector = summary.kept
                                   ? 8.0 * static_cast<double>(bytes.size() - qnv::kHeaderBytes) /
                                         static_cast<double>(summary.kept)
                                   : 0.0;
  const std::uint64_t perPacket = s.write.packetBytes / 8;
  std::printf(
      "%s: %s bytes, %.1f bits per vector (packets and header included), %s packets; %.3f s\n",
      options.encode.output.c_str(), withCommas(bytes.size()).c_str(), bitsPerVector,
      withCommas((summary.kept + perPacket - 1) / perPacket).c_str(), seconds);
  return 0;
}

}  // namespace gs::app
