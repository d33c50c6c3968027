// NRRD, NIfTI-1 and raw volumes read slab by slab (formats/volume_slabs.hpp): the data
// of a volume are a sequence of pieces (one per data file, or the one file after its
// header), each raw (read at offsets) or gzip (inflated forward).
#include <algorithm>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "base/text.hpp"
#include "formats/dicom_reader.hpp"
#include "formats/input_kind.hpp"
#include "formats/vdb_reader.hpp"
#include "formats/volume_slabs.hpp"
#include "slab_io.hpp"

namespace gs::formats {

namespace detail {
// slab_images.cpp: folders, patterns and multi-page TIFFs of 2-D slices.
std::unique_ptr<VolumeSlabReader> openSliceStack(const std::string& path);
void checkGrid(const VolumeGridInfo& info, const std::string& name);
}  // namespace detail

namespace {

using detail::GzipStream;
using detail::RandomFile;

// deflate's largest compression ratio (RFC 1951: a 258-byte match in about 2 bits), with
// room for headers: compressed data of N bytes cannot hold more than this many per byte.
constexpr std::uint64_t kMaxDeflateRatio = 1032;
constexpr std::uint64_t kDeflateSlack = 64 * 1024;
// The most header text read before the blank line that ends it (LIST headers are long).
constexpr std::uint64_t kMaxHeaderBytes = std::uint64_t{64} << 20;
// Bytes converted per step (the reader's fixed buffer).
constexpr std::size_t kChunkBytes = std::size_t{4} << 20;

struct Piece {
  std::string path;
  bool gzip = false;
  std::uint64_t offset = 0;  // raw: first sample byte; gzip: first compressed byte
  std::uint64_t skip = 0;    // gzip: decompressed bytes before the first sample
  std::uint64_t samples = 0;
  std::uint64_t firstSample = 0;  // index of its first sample in the volume
};

class PiecewiseReader final : public VolumeSlabReader {
 public:
  PiecewiseReader(VolumeGridInfo info, ScalarType type, bool bigEndian, std::vector<Piece> pieces)
      : info_(info), type_(type), bigEndian_(bigEndian), pieces_(std::move(pieces)) {
    std::uint64_t first = 0;
    for (Piece& p : pieces_) p.firstSample = first, first += p.samples;
  }
  void setScale(float slope, float inter) { scale_ = std::pair{slope, inter}; }
  const VolumeGridInfo& info() const override { return info_; }

  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    if (!(z0 < z1 && z1 <= info_.dims.z))
      throw InputError(pieces_.front().path +
                       ": expected slices 0 <= z0 < z1 <= " + std::to_string(info_.dims.z) +
                       ", got [" + std::to_string(z0) + ", " + std::to_string(z1) + ")");
    const std::uint64_t slice = info_.sliceVoxels();
    out.resize(static_cast<std::size_t>(slice * (z1 - z0)));
    readSamples(slice * z0, out.size(), out.data());
    if (scale_)
      for (float& s : out) s = s * scale_->first + scale_->second;
  }

 private:
  void readSamples(std::uint64_t first, std::size_t count, float* out) {
    auto it = std::upper_bound(pieces_.begin(), pieces_.end(), first,
                               [](std::uint64_t v, const Piece& p) { return v < p.firstSample; });
    std::size_t index = static_cast<std::size_t>(it - pieces_.begin()) - 1;
    const std::size_t bytes = scalarBytes(type_);
    while (count > 0) {
      const Piece& p = pieces_[index];
      const std::uint64_t local = first - p.firstSample;
      const std::size_t n =
          static_cast<std::size_t>(std::min<std::uint64_t>(count, p.samples - local));
      for (std::size_t done = 0; done < n;) {
        const std::size_t step = std::min(n - done, kChunkBytes / bytes);
        scratch_.resize(step * bytes);
        fetch(index, (local + done) * bytes, scratch_.data(), scratch_.size());
        convertSamples(scratch_.data(), step, type_, bigEndian_, out + done);
        done += step;
      }
      out += n;
      first += n;
      count -= n;
      ++index;
    }
  }

  // `n` bytes of piece `index` from its sample byte `at`.
  void fetch(std::size_t index, std::uint64_t at, char* dst, std::size_t n) {
    const Piece& p = pieces_[index];
    if (!p.gzip) {
      if (!file_ || fileIndex_ != index) {
        file_.reset();
        file_ = std::make_unique<RandomFile>(p.path);
        fileIndex_ = index;
      }
      file_->readAt(p.offset + at, dst, n);
      return;
    }
    if (!gzip_ || gzipIndex_ != index) {
      gzip_.reset();
      gzip_ = std::make_unique<GzipStream>(p.path, p.offset);
      gzipIndex_ = index;
    }
    const std::uint64_t target = p.skip + at;
    if (gzip_->position() > target) gzip_->rewind();
    gzip_->skip(target - gzip_->position());
    const std::size_t got = gzip_->position() == target ? gzip_->read(dst, n) : 0;
    if (got < n)
      throw InputError(p.path + ": short read at decompressed byte offset " +
                       std::to_string(target) + ": expected " + std::to_string(n) +
                       " bytes of voxel data, the gzip data end at byte " +
                       std::to_string(gzip_->position()));
  }

  VolumeGridInfo info_;
  ScalarType type_;
  bool bigEndian_;
  std::vector<Piece> pieces_;
  std::optional<std::pair<float, float>> scale_;
  std::vector<char> scratch_;
  std::unique_ptr<RandomFile> file_;
  std::size_t fileIndex_ = 0;
  std::unique_ptr<GzipStream> gzip_;
  std::size_t gzipIndex_ = 0;
};

// A Volume read whole (ascii NRRD), served as slabs.
class OwnedVolumeSlabs final : public VolumeSlabReader {
 public:
  explicit OwnedVolumeSlabs(Volume v) : volume_(std::move(v)), reader_(volume_) {}
  const VolumeGridInfo& info() const override { return reader_.info(); }
  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    reader_.readSlices(z0, z1, out);
  }

 private:
  Volume volume_;
  qnv::MemoryVolumeSlabs reader_;
};

// Checks that a piece's file can hold `bytes` of samples and fixes its offsets. `base`:
// where the piece's data start before the skips.
void placePiece(Piece& p, std::uint64_t base, std::uint64_t lineSkip, std::int64_t byteSkip,
                std::uint64_t bytes) {
  const RandomFile file(p.path);
  const std::uint64_t start = detail::offsetAfterLines(file, base, lineSkip);
  if (!p.gzip) {
    if (byteSkip == -1) {
      if (file.size() < bytes || file.size() - bytes < start)
        throw InputError(p.path + ": expected " + std::to_string(bytes) +
                         " bytes of voxel data at the end of the file, the file has " +
                         std::to_string(file.size() - std::min(file.size(), start)) +
                         " bytes after its header");
      p.offset = file.size() - bytes;
    } else {
      p.offset = start + static_cast<std::uint64_t>(byteSkip);
    }
    if (p.offset > file.size() || file.size() - p.offset < bytes)
      throw InputError(p.path + ": expected " + std::to_string(bytes) +
                       " bytes of voxel data from byte offset " + std::to_string(p.offset) +
                       ", the file has " +
                       std::to_string(file.size() - std::min(file.size(), p.offset)) +
                       " (the header's sizes do not match the file)");
    return;
  }
  p.offset = start;
  const std::uint64_t compressed = file.size() - std::min(file.size(), start);
  if (bytes > compressed * kMaxDeflateRatio + kDeflateSlack)
    throw InputError(p.path + ": " + std::to_string(compressed) +
                     " bytes of gzip data cannot hold the " + std::to_string(bytes) +
                     " bytes of voxel data the header describes");
  if (byteSkip >= 0) {
    p.skip = static_cast<std::uint64_t>(byteSkip);
    return;
  }
  // -1: the samples are the last bytes of the decompressed data; one counting pass.
  GzipStream stream(p.path, start);
  const std::uint64_t total = stream.skip(std::numeric_limits<std::uint64_t>::max());
  if (total < bytes)
    throw InputError(p.path + ": expected " + std::to_string(bytes) +
                     " bytes of voxel data, the gzip data hold " + std::to_string(total));
  p.skip = total - bytes;
}

std::unique_ptr<VolumeSlabReader> openNrrd(const std::string& path) {
  // The header: up to its blank line (attached data) or the whole file (.nhdr).
  const RandomFile file(path);
  std::string head;
  std::uint64_t at = 0;
  while (at < file.size() && head.size() < kMaxHeaderBytes) {
    const std::size_t want = static_cast<std::size_t>(
        std::min<std::uint64_t>({file.size() - at, 256 * 1024, kMaxHeaderBytes - head.size()}));
    const std::size_t from = head.size() > 3 ? head.size() - 3 : 0;
    head.resize(head.size() + want);
    file.readAt(at, head.data() + head.size() - want, want);
    at += want;
    if (head.find("\n\n", from) != std::string::npos ||
        head.find("\n\r\n", from) != std::string::npos)
      break;
  }
  NrrdParseOptions options;
  options.multiFile = true;
  options.maxVoxels = qnv::kMaxSlabVolumeVoxels;
  const NrrdHeader h = parseNrrdHeader(head, path, options);
  if (h.dataOffset >= head.size() && at < file.size() && h.dataFile.empty() && h.dataFiles.empty())
    throw InputError(path + ": NRRD header longer than " + std::to_string(kMaxHeaderBytes) +
                     " bytes");

  VolumeGridInfo info;
  info.dims = h.dims;
  info.spacing = h.spacing;
  info.origin = h.origin;
  info.sourceType = h.type;
  detail::checkGrid(info, path);

  if (h.encoding == NrrdHeader::Encoding::ascii || h.encoding == NrrdHeader::Encoding::hex) {
    if (h.voxelCount() > kMaxVoxels)
      throw InputError(path + ": ascii and hex NRRD data are read whole, and " +
                       std::to_string(h.voxelCount()) + " voxels exceed the limit of " +
                       std::to_string(kMaxVoxels));
    if (!h.dataFiles.empty())
      throw InputError(path + ": ascii or hex NRRD data in several files are not supported");
    const std::string dataPath =
        h.dataFile.empty() ? path : detail::resolveBeside(path, h.dataFile);
    const RandomFile data(dataPath);
    const std::uint64_t from = h.dataFile.empty() ? h.dataOffset : 0;
    // Each value takes at least 2 bytes, so a file of this size is enough.
    const std::uint64_t limit = std::uint64_t{kMaxVoxels} * 64;
    if (data.size() - std::min(data.size(), from) > limit)
      throw InputError(dataPath + ": ascii data larger than " + std::to_string(limit) + " bytes");
    std::string bytes(static_cast<std::size_t>(data.size() - std::min(data.size(), from)), '\0');
    data.readAt(from, bytes.data(), bytes.size());
    return std::make_unique<OwnedVolumeSlabs>(decodeNrrdData(h, bytes, dataPath));
  }

  const bool gzip = h.encoding == NrrdHeader::Encoding::gzip;
  const std::size_t bytesPer = scalarBytes(h.type);
  std::vector<Piece> pieces;
  if (!h.dataFiles.empty()) {
    pieces.reserve(h.dataFiles.size());
    for (const std::string& f : h.dataFiles) {
      Piece p;
      p.path = detail::resolveBeside(path, f);
      p.gzip = gzip;
      p.samples = h.samplesPerDataFile;
      try {
        placePiece(p, 0, h.lineSkip, h.byteSkip, p.samples * bytesPer);
      } catch (const InputError& e) {
        throw InputError(path + ": data file '" + f + "': " + e.what());
      }
      pieces.push_back(std::move(p));
    }
  } else {
    Piece p;
    p.path = h.dataFile.empty() ? path : detail::resolveBeside(path, h.dataFile);
    p.gzip = gzip;
    p.samples = info.voxelCount();
    placePiece(p, h.dataFile.empty() ? h.dataOffset : 0, h.lineSkip, h.byteSkip,
               p.samples * bytesPer);
    pieces.push_back(std::move(p));
  }
  return std::make_unique<PiecewiseReader>(info, h.type, h.bigEndian, std::move(pieces));
}

std::unique_ptr<VolumeSlabReader> openNifti(const std::string& path) {
  const RandomFile file(path);
  std::string head(348, '\0');
  const bool gzip = file.readSome(0, head.data(), 2) == 2 &&
                    static_cast<unsigned char>(head[0]) == 0x1f &&
                    static_cast<unsigned char>(head[1]) == 0x8b;
  std::size_t got = 0;
  if (gzip) {
    GzipStream stream(path, 0);
    got = stream.read(head.data(), head.size());
  } else {
    got = file.readSome(0, head.data(), head.size());
  }
  head.resize(got);
  const NiftiHeader h =
      parseNiftiHeader(head, path, gzip ? std::numeric_limits<std::uint64_t>::max() : file.size());
  VolumeGridInfo info;
  info.dims = h.layout.dims;
  info.spacing = h.layout.spacing;
  info.origin = h.origin;
  info.sourceType = h.layout.type;
  detail::checkGrid(info, path);
  Piece p;
  p.path = path;
  p.gzip = gzip;
  p.samples = info.voxelCount();
  placePiece(p, 0, 0, static_cast<std::int64_t>(h.layout.headerBytes),
             p.samples * scalarBytes(h.layout.type));
  std::vector<Piece> pieces;
  pieces.push_back(std::move(p));
  auto reader =
      std::make_unique<PiecewiseReader>(info, h.layout.type, h.layout.bigEndian, std::move(pieces));
  if (h.scaled) reader->setScale(h.slope, h.inter);
  return reader;
}

std::unique_ptr<VolumeSlabReader> openRaw(const std::string& path, const RawLayout& layout) {
  VolumeGridInfo info;
  info.dims = layout.dims;
  info.spacing = layout.spacing;
  info.sourceType = layout.type;
  detail::checkGrid(info, path);
  Piece p;
  p.path = path;
  p.gzip = base::endsWithNoCase(path, ".gz");
  p.samples = info.voxelCount();
  if (layout.headerBytes > std::uint64_t{std::numeric_limits<std::int64_t>::max()})
    throw InputError(path + ": header of " + std::to_string(layout.headerBytes) + " bytes");
  placePiece(p, 0, 0, static_cast<std::int64_t>(layout.headerBytes),
             p.samples * scalarBytes(layout.type));
  std::vector<Piece> pieces;
  pieces.push_back(std::move(p));
  return std::make_unique<PiecewiseReader>(info, layout.type, layout.bigEndian, std::move(pieces));
}

}  // namespace

std::unique_ptr<VolumeSlabReader> openVolumeSlabs(const std::string& path, const RawLayout* raw) {
  if (raw) return openRaw(path, *raw);
  if (classifyFile(path) == InputKind::dicom)  // read whole: GDCM decodes whole frames
    return std::make_unique<OwnedVolumeSlabs>(loadDicom(path).volume);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec) || path.find('%') != std::string::npos ||
      base::endsWithNoCase(path, ".png") || base::endsWithNoCase(path, ".tif") ||
      base::endsWithNoCase(path, ".tiff"))
    return detail::openSliceStack(path);
  switch (classifyFile(path)) {
    case InputKind::nrrd:
      return openNrrd(path);
    case InputKind::nifti:
      return openNifti(path);
    case InputKind::vdb:
      return openVdb(path);
    default:
      break;
  }
  if (!std::filesystem::exists(path, ec))
    throw InputError("cannot open " + path + ": no such file or folder");
  throw InputError(path +
                   ": not a volume the slab reader knows (NRRD .nrrd/.nhdr, NIfTI-1 .nii, a "
                   "raw file with its layout, DICOM, OpenVDB, or PNG/TIFF slices)");
}

}  // namespace gs::formats
