// Volume files from disk: file reading, gzip and detached NRRD data files around the
// parsers of formats/volume_readers.hpp.
#include "session/volume_input.hpp"

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "base/file.hpp"
#include "base/gzip.hpp"
#include "base/text.hpp"
#include "formats/dicom_reader.hpp"
#include "formats/input_kind.hpp"
#include "formats/tiff_reader.hpp"
#include "formats/vdb_reader.hpp"
#include "formats/volume_slabs.hpp"
#include "qnv/error.hpp"

namespace gs::session {

namespace {

// The largest volume (kMaxVoxels float64 samples) plus room for a header.
constexpr std::size_t kMaxFileBytes = qnv::kMaxVoxels * 8 + (std::size_t{64} << 20);
// Decompressed bytes allowed beyond what a header describes (trailing padding).
constexpr std::size_t kGzipSlack = std::size_t{1} << 20;

std::string readOrThrow(const std::string& path) {
  std::string bytes, error;
  if (!base::readFile(path, bytes, error, kMaxFileBytes)) throw qnv::InputError(error);
  return bytes;
}

// base::gunzipIfCompressed with its GzipError turned into an InputError naming `path`.
std::string gunzip(std::string_view bytes, const std::string& path, std::size_t maxBytes) {
  try {
    return base::gunzipIfCompressed(bytes, maxBytes);
  } catch (const base::GzipError& e) {
    if (e.kind == base::GzipError::Kind::tooLarge)
      throw qnv::InputError(path + ": decompressed data exceed " + std::to_string(maxBytes) +
                            " bytes, more than the volume needs");
    throw qnv::InputError(path + ": " + e.what());
  }
}

// The detached data file `dataFile` of the header at `headerPath`, which must lie in the
// header's folder or below it.
std::string resolveDataFile(const std::string& headerPath, const std::string& dataFile) {
  const std::filesystem::path rel(dataFile);
  if (rel.is_absolute() || rel.has_root_path())
    throw qnv::InputError(headerPath + ": data file '" + dataFile +
                          "' is an absolute path; only files beside the header are read");
  for (const auto& part : rel)
    if (part == "..")
      throw qnv::InputError(headerPath + ": data file '" + dataFile +
                            "' leaves the header's folder ('..'); only files beside the "
                            "header are read");
  std::filesystem::path dir = std::filesystem::path(headerPath).parent_path();
  if (dir.empty()) dir = ".";
  return (dir / rel).string();
}

qnv::Volume loadNrrd(const std::string& path, const std::string& bytes) {
  const formats::NrrdHeader h = formats::parseNrrdHeader(bytes, path);
  std::string dataName = path;
  std::string fileBytes;
  std::string_view data;
  if (h.dataFile.empty()) {
    data = std::string_view(bytes).substr(std::min(h.dataOffset, bytes.size()));
  } else {
    dataName = resolveDataFile(path, h.dataFile);
    fileBytes = readOrThrow(dataName);
    data = fileBytes;
  }
  if (h.encoding != formats::NrrdHeader::Encoding::gzip)
    return formats::decodeNrrdData(h, data, dataName);

  // teem skips lines in the compressed bytes and bytes in the decompressed ones.
  data = formats::skipNrrdLines(data, h.lineSkip, dataName);
  if (!base::isGzip(data))
    throw qnv::InputError(dataName +
                          ": the NRRD header says 'encoding: gzip' but the data are not gzip");
  const std::size_t skip =
      h.byteSkip > 0 ? std::min(static_cast<std::size_t>(h.byteSkip), kMaxFileBytes) : 0;
  const std::string inflated = gunzip(data, dataName, h.dataBytes() + skip + kGzipSlack);
  return formats::decodeNrrdData(h, inflated, dataName);
}

}  // namespace

qnv::Volume loadVolumeFile(const std::string& path) {
  const formats::InputKind kind = formats::classifyFile(path);
  if (kind == formats::InputKind::dicom)
    return formats::loadDicom(path).volume;  // a file, a folder or a DICOMDIR
  std::error_code ec;
  if (kind == formats::InputKind::tiff && std::filesystem::is_directory(path, ec))
    return qnv::readWholeVolume(*formats::openVolumeSlabs(path));  // single-page slices
  if (kind == formats::InputKind::tiff) return formats::readTiff(readOrThrow(path), path).volume;
  if (kind == formats::InputKind::vdb) return qnv::readWholeVolume(*formats::openVdb(path));
  const std::string bytes = readOrThrow(path);
  if (formats::classifyInput(path, bytes) == formats::InputKind::nrrd) return loadNrrd(path, bytes);
  if (!base::isGzip(bytes)) return formats::readNifti(bytes, path);
  return formats::readNifti(gunzip(bytes, path, kMaxFileBytes), path);
}

qnv::Volume loadRawVolumeFile(const std::string& path, const formats::RawLayout& layout) {
  std::string bytes = readOrThrow(path);
  if (base::endsWithNoCase(path, ".gz")) {
    // Bound the decompressed size by the layout (dims beyond the limits fail in decodeRaw).
    const glm::uvec3 d = layout.dims;
    const std::uint64_t xy = std::uint64_t{d.x} * d.y;
    const bool fits = xy <= qnv::kMaxVoxels && xy * d.z <= qnv::kMaxVoxels;
    const std::size_t need =
        fits ? static_cast<std::size_t>(xy * d.z) * qnv::scalarBytes(layout.type) : 0;
    const std::size_t header = std::min(layout.headerBytes, kMaxFileBytes);
    bytes = gunzip(bytes, path, need + header + kGzipSlack);
  }
  return formats::decodeRaw(bytes, layout, path);
}

}  // namespace gs::session
