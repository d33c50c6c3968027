// Shared by the splat scene readers (splats/readers.hpp): errors naming the input, bounds
// checked little-endian reads, the PLY header parser of readPlyGaussians and
// readCompressedPlyGaussians (and of detectSplatFormat), and the conversions every reader
// ends with (rotations normalised, PLY's channel-major f_rest made splat-major).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "splats/readers.hpp"

namespace gs::splats::detail {

/// The start of openGaussianBatches's NotPiecewiseError: the formats it reads piecewise.
inline constexpr const char* kPiecewiseFormats =
    "read piecewise are binary INRIA .ply, .compressed.ply, .splat, .spz, SOG and glTF";

/// Throws FormatError("NAME: WHAT").
[[noreturn]] void fail(std::string_view name, const std::string& what);

/// Throws FormatError "NAME: COUNT splats exceed the limit of kMaxSplats" when count is
/// above kMaxSplats, and "NAME: expected BYTES bytes of WHAT, got HAVE" when
/// count * recordBytes (overflow checked) exceeds `have`.
void checkCount(std::string_view name, std::uint64_t count, std::uint64_t recordBytes,
                std::uint64_t have, const char* what);

/// `v` as a float, clamped to +-FLT_MAX (converting a double outside float's range is
/// undefined behaviour); NaN stays NaN.
float toFloat(double v);

/// SH degree (0..3) of `restPerChannel` higher coefficients per channel (0, 3, 8, 15);
/// -1 for any other count.
int shDegreeForRest(std::size_t restPerChannel);

/// `q` (w, x, y, z) normalised; the identity when its length is 0 or not finite.
glm::quat unitQuat(float w, float x, float y, float z);

/// Sizes every array of `cloud` for `count` splats of SH degree `degree` (0..3).
void allocate(GaussianCloud& cloud, std::size_t count, int degree);

/// Stores splat `i`'s higher SH coefficients given channel-major (Kerbl et al.'s
/// f_rest order: all red coefficients, then green, then blue; `rest` holds
/// 3 * cloud.shRestPerSplat() values) as the cloud's splat-major RGB triples.
void setChannelMajorRest(GaussianCloud& cloud, std::size_t i, const float* rest);

/// The scalar types of a PLY property (PLY's char..double and their int8..float64 aliases).
enum class PlyType : std::uint8_t { i8, u8, i16, u16, i32, u32, f32, f64 };

/// Bytes of one value of type `t`.
std::size_t plyTypeSize(PlyType t);

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::f32;
  bool isList = false;  // a list property (faces); its count has countType
  PlyType countType = PlyType::u8;
  std::size_t offset = 0;  // bytes from the start of the record (fixed-size elements)
};

struct PlyElement {
  std::string name;
  std::uint64_t count = 0;
  std::vector<PlyProperty> properties;
  std::size_t rowBytes = 0;  // bytes of one record when no property is a list
  bool hasList = false;
  /// Index of the property `name`, -1 when absent.
  int find(std::string_view property) const;
};

enum class PlyFormat : std::uint8_t { ascii, binaryLittleEndian, binaryBigEndian };

struct PlyHeader {
  PlyFormat format = PlyFormat::binaryLittleEndian;
  std::vector<PlyElement> elements;
  std::size_t dataOffset = 0;  // first byte after "end_header\n"
  /// The element `name`, null when absent.
  const PlyElement* find(std::string_view element) const;
};

/// Parses the PLY header at the start of `bytes` (at most its first 1 MiB). False with
/// `error` set ("missing end_header", "bad element count 'x'", ...) when it is not one.
/// Never throws.
bool parsePlyHeader(std::string_view bytes, PlyHeader& header, std::string& error);

/// The value of type `t` at `p` (little- or big-endian) as a double.
double plyValue(const char* p, PlyType t, bool bigEndian);

/// For binary PLY: the byte offset of `element`'s first record (elements before it must
/// have no list property, else FormatError) and a check that its records lie within
/// `bytes` (FormatError "NAME: expected N bytes of element 'E', got M").
std::size_t plyElementOffset(std::string_view bytes, std::string_view name, const PlyHeader& header,
                             const PlyElement& element);
/// The same for a file of `fileBytes` bytes whose header `header` is (read piecewise).
std::uint64_t plyElementOffset(std::uint64_t fileBytes, std::string_view name,
                               const PlyHeader& header, const PlyElement& element);

/// For GaussianRowDecoder::decode: FormatError unless rows [first, first + n) lie within
/// the scene's `count`.
void checkRows(std::uint64_t first, std::size_t n, std::uint64_t count);

/// A file read by offset, piece by piece (the piecewise readers, GaussianBatchReader).
/// Closed when destroyed.
class PieceFile {
 public:
  /// Throws FormatError "PATH: cannot open: REASON".
  explicit PieceFile(const std::string& path);
  ~PieceFile();
  PieceFile(const PieceFile&) = delete;
  PieceFile& operator=(const PieceFile&) = delete;
  /// The file's size, bytes.
  std::uint64_t size() const { return size_; }
  /// Reads `bytes` bytes at `offset` into `out`; FormatError "PATH: expected N bytes at
  /// byte OFFSET, got M" when the file ends before (or "cannot read: REASON").
  void read(std::uint64_t offset, char* out, std::size_t bytes) const;
  /// The file's first min(size(), `max`) bytes (a header to parse: a PLY's takes at most
  /// 1 MiB, parsePlyHeader's limit).
  std::string head(std::size_t max = std::size_t{1} << 20) const;
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

}  // namespace gs::splats::detail

namespace gs::splats {
/// openGaussianBatches for a .ply (ply_gaussians.cpp) and a .splat (splat_format.cpp).
std::unique_ptr<GaussianBatchReader> openPlyGaussianBatches(const std::string& path);
std::unique_ptr<GaussianBatchReader> openSplatGaussianBatches(const std::string& path);
/// openGaussianBatches for a PlayCanvas .compressed.ply (compressed_ply.cpp) and an .spz
/// (spz.cpp).
std::unique_ptr<GaussianBatchReader> openCompressedPlyGaussianBatches(const std::string& path);
std::unique_ptr<GaussianBatchReader> openSpzGaussianBatches(const std::string& path);
/// openGaussianBatches for a glTF KHR_gaussian_splatting scene (gltf_batches.cpp): a GLB,
/// or a .gltf whose buffer files lie beside it (read by offset, never whole).
std::unique_ptr<GaussianBatchReader> openGltfGaussianBatches(const std::string& path);
/// openGaussianColumns for an SPZ v4 file (spz.cpp) and a GLB or .gltf (gltf_batches.cpp:
/// one splat primitive instance whose accessors lie tightly packed in its BIN chunk or
/// buffer files; none for any other glTF), `fileBytes` known.
GaussianColumns openSpzColumns(std::string_view head, const std::string& name,
                               std::uint64_t fileBytes);
GaussianColumns openGltfColumns(std::string_view head, const std::string& name,
                                std::uint64_t fileBytes);
/// openGaussianColumns of an SOG's meta.json (sog.cpp): `head` the whole meta.json (at most
/// 1 MiB: else none), its textures the columns (Column::webp, in side files).
GaussianColumns openSogColumns(std::string_view head, const std::string& name,
                               std::uint64_t fileBytes);
/// openGaussianRows for a PlayCanvas .compressed.ply whose header is `header` (parsed from
/// `head`, the file's first bytes; compressed_ply.cpp): a decoder once `head` holds the
/// whole chunk table (needMore before), none when its chunk element follows its vertex
/// element (read whole then). Throws FormatError as readCompressedPlyGaussians for the header.
GaussianRows openCompressedPlyRows(const detail::PlyHeader& header, std::string_view head,
                                   const std::string& name, std::uint64_t fileBytes);
/// openGaussianBatches for an SOG bundle or meta.json (sog.cpp); `sideFiles` reads a
/// meta.json's textures.
std::unique_ptr<GaussianBatchReader> openSogGaussianBatches(const std::string& path,
                                                            const SideFileReader& sideFiles);
}  // namespace gs::splats
