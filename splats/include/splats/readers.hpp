// Readers of 3D Gaussian splatting scenes (docs/splats.md, "Formats"): INRIA .ply,
// PlayCanvas .compressed.ply, .splat, Niantic .spz (v2-v4), PlayCanvas SOG and glTF
// KHR_gaussian_splatting. Each reads bytes already in memory, is safe for untrusted input
// (every count and size checked before it is used; allocations bounded by the input's
// size and kMaxSplats) and returns the cloud in the axes splat-transform 3.7 gives it
// (docs/splats.md, "Axes"): the INRIA .ply's own axes, which the scene turns 180 degrees
// about Z as SuperSplat and Spark show a capture.
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "splats/gaussian.hpp"

namespace gs::splats {

/// Thrown by every reader: what() names the input and says what is wrong, e.g.
/// "scene.ply: property 'scale_2' missing", "garden.spz: unsupported SPZ version 9".
struct FormatError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The most splats a reader accepts (a larger count is a FormatError, not an allocation).
inline constexpr std::size_t kMaxSplats = std::size_t{1} << 28;

/// The splat scene formats.
enum class SplatFormat { unknown, ply, compressedPly, splat, spz, sog, sogMeta, gltf, qnv, las };

/// The format the leading bytes `head` and the name `name` say: a PLY header whose
/// vertex element has Gaussian properties (f_dc_0 / scale_0 / rot_0 / opacity) is `ply`;
/// one with the chunk element of PlayCanvas is `compressedPly`; gzip whose content starts
/// with SPZ's magic, or NGSP (v4), is `spz`; a zip holding meta.json is `sog`; a JSON
/// object with SOG's "means" is `sogMeta`; a QNV stream of kind 3 (Gaussians, byte 10 of
/// its header; splats/qnv_gaussians.hpp) is `qnv`; "LASF" (an ASPRS LAS or LAZ point
/// cloud) is `las`; a glTF using KHR_gaussian_splatting is `gltf`;
/// `.splat` by name only (it has no magic). unknown otherwise (a mesh PLY is unknown).
SplatFormat detectSplatFormat(std::string_view head, std::string_view name);

/// Whether the glTF asset whose first bytes are `head` (a GLB's header and whole JSON
/// chunk, or the whole JSON text) draws Gaussian splats alone: it has a mesh primitive and
/// every primitive of every mesh carries KHR_gaussian_splatting. Such an asset opens as a
/// capture, as a .ply does; one that also has other primitives opens as a glTF world
/// whose splats one GaussianSplats node draws (docs/gltf.md). False for JSON that is cut,
/// malformed or nested deeper than 64 levels. Never throws.
bool gltfDrawsOnlyGaussians(std::string_view head);

/// Reads further files a scene refers to (SOG's meta.json names its WebP images, a .gltf
/// its buffers): `relative` is the name as the scene writes it. Returns false with `error`
/// set when it cannot be read (the reader then throws FormatError naming it). Callers
/// resolve names against the scene's folder and refuse what may not be read
/// (base::mayReference).
using SideFileReader =
    std::function<bool(const std::string& relative, std::string& bytes, std::string& error)>;

/// A Gaussian splatting scene read piecewise, a batch of splats at a time, for scenes
/// larger than memory (an out-of-core tileset encode: encode/src/ooc_gaussian.cpp). Each
/// batch holds exactly the splats the whole-file reader gives at those places.
class GaussianBatchReader {
 public:
  virtual ~GaussianBatchReader() = default;
  /// The scene's splats (<= kMaxSplats) and SH degree (0..3).
  virtual std::uint64_t size() const = 0;
  virtual int shDegree() const = 0;
  /// Bytes of one splat's row in the file (a read of n splats holds n of them at once).
  virtual std::size_t rowBytes() const = 0;
  /// Reads the next min(max, left) splats into `batch` (resized to them; its shDegree the
  /// scene's) and returns how many; 0 at the end. Throws FormatError on a short, damaged
  /// or unreadable file (the last batch also checks that compressed data end as the
  /// whole-file reader requires); after that only rewind() may follow.
  virtual std::size_t read(GaussianCloud& batch, std::size_t max) = 0;
  /// Back to the first splat, for another pass.
  virtual void rewind() = 0;
};

/// The splats of a scene whose splats are rows of a fixed size (a binary INRIA .ply's
/// vertex element, a .splat's 32-byte records), decoded from its bytes as they arrive: a
/// capture fetched over HTTP drawn while it arrives (session/src/gaussian_scene_load.hpp).
class GaussianRowDecoder {
 public:
  virtual ~GaussianRowDecoder() = default;
  /// Byte offset of the first row in the file.
  virtual std::uint64_t dataOffset() const = 0;
  /// Bytes of one row.
  virtual std::size_t rowBytes() const = 0;
  /// The scene's splats (1..kMaxSplats).
  virtual std::uint64_t size() const = 0;
  /// SH degree (0..3).
  virtual int shDegree() const = 0;
  /// Decodes the `n` rows at `rows` (n * rowBytes() bytes), rows `first` to first + n - 1
  /// of the scene, into `batch`, resized to them: exactly the splats the whole-file reader
  /// gives for those rows (without their SH where wholeFileAtEnd()). Throws FormatError
  /// for rows past size().
  virtual void decode(const char* rows, std::uint64_t first, std::size_t n,
                      GaussianCloud& batch) const = 0;
  /// Whether the rows give each splat without all it holds: a PlayCanvas compressed PLY's
  /// rows are its vertex records, its SH lie in an element after the last of them. The
  /// rows are then a preview (SH degree 0) and the scene is the whole file read by
  /// readGaussians once it arrived: keep its bytes.
  virtual bool wholeFileAtEnd() const { return false; }
};

/// What openGaussianRows found in a scene's first bytes.
struct GaussianRows {
  /// The decoder, or null: not (yet) known to be a row format.
  std::unique_ptr<GaussianRowDecoder> decoder;
  /// With no decoder: true when more bytes may still show a PLY header (its end_header
  /// line has not arrived); false when the scene is not read by rows (read it whole).
  bool needMore = false;
};

/// The row decoder of the scene `name` whose first bytes are `head` and whose size is
/// `fileBytes` (the most it may be when not known): a binary INRIA .ply, a PlayCanvas
/// compressed PLY once `head` holds its chunk table (its rows a preview without SH:
/// GaussianRowDecoder::wholeFileAtEnd; none when the chunk element follows the vertex
/// element), or a .splat (by name, as detectSplatFormat; its size must be known and whole
/// records); not an ascii PLY. Throws FormatError naming `name` for a PLY header that
/// readPlyGaussians refuses (a property missing, too many splats, an element past
/// `fileBytes`).
GaussianRows openGaussianRows(std::string_view head, const std::string& name,
                              std::uint64_t fileBytes);

/// A scene whose attributes lie in columns of its file or of files beside it, each a run of
/// bytes that decodes, in order, to one fixed-size record per splat (an SPZ v4 file's zstd
/// streams, a GLB's or .gltf's accessors, an SOG's WebP images). Fetched
/// column by column side by side (one HTTP request each: a range, or an SOG's image
/// whole), its splats are decoded as
/// soon as every column's records for them arrived, with all they hold: a remote SPZ drawn
/// while it arrives (session/src/gaussian_columns_fetch.hpp; docs/splats.md, "Opening a
/// scene").
class GaussianColumnDecoder {
 public:
  /// Where one column lies and what it decodes to.
  struct Column {
    std::uint64_t offset = 0;  // its first byte in the file
    /// Its bytes in the file (0 only in a damaged file, or for a WebP side file whose size
    /// the scene does not state: fetched whole, its RIFF header then says).
    std::uint64_t bytes = 0;
    std::size_t recordBytes = 0;  // one splat's record once decoded (>= 1)
    bool zstd = false;            // one zstd frame of the records; else the records themselves
    /// Empty: the column lies in the scene's own file. Else in a file beside it (a glTF's
    /// buffer file, an SOG's image): its name relative to the scene's (a glTF's uri
    /// percent-decoded, an SOG's as meta.json writes it), never with "..", a scheme or a
    /// leading '/'; `fileBytes` its size as the scene states it (a buffer's byteLength; 0:
    /// not stated).
    std::string file;
    std::uint64_t fileBytes = 0;
    /// A WebP image (an SOG's) whose texels, RGBA row-major, are the records (recordBytes
    /// 4), decoded a band of rows at a time as its bytes arrive (libwebp's incremental
    /// decoder); texels past the scene's splats are padding. At most `maxTexels` texels.
    bool webp = false;
    std::uint64_t maxTexels = 0;
    /// Needed whole before any splat (an SOG's SH centroids, `width` texels wide): decoded
    /// whole, then given to takeWhole; its records are not the splats'.
    bool whole = false;
    std::uint32_t width = 0;
  };
  virtual ~GaussianColumnDecoder() = default;
  /// The columns, each within its file: 5 or 6 for an SPZ, up to 20 for a glTF, 5 or 7
  /// for an SOG.
  virtual const std::vector<Column>& columns() const = 0;
  /// The scene's splats (1..kMaxSplats).
  virtual std::uint64_t size() const = 0;
  /// SH degree (0..3).
  virtual int shDegree() const = 0;
  /// Decodes splats `first` to first + n - 1 into `batch` (resized to them) from
  /// `records[k]`, column k's n records of them (null for a whole column): exactly the
  /// whole-file reader's splats. Throws FormatError for splats past size(), or before a
  /// whole column was taken.
  virtual void decode(const std::vector<const char*>& records, std::uint64_t first, std::size_t n,
                      GaussianCloud& batch) const = 0;
  /// Takes whole column `k` (Column::whole) once decoded: `texels` its image's RGBA texels,
  /// `width` x `height`. Called once, before decode() needs it.
  virtual void takeWhole(std::size_t k, std::string_view texels, int width, int height) {
    (void)k, (void)texels, (void)width, (void)height;
  }
};

/// The most JSON a scene read by columns waits for (a GLB's JSON chunk, a .gltf, an SOG's
/// meta.json): a larger one is read with the whole file.
inline constexpr std::uint64_t kMaxColumnsJsonBytes = std::uint64_t{1} << 20;

/// Whether `name` (a side file as a scene names it: a glTF buffer, an SOG image) names a
/// file beside the scene or below it: not empty, without "..", a scheme (':') or a
/// leading '/'. Remote content names nothing else (docs/progressive-loading.md).
inline bool isFileBesideScene(std::string_view name) {
  return !name.empty() && name.find("..") == std::string_view::npos &&
         name.find(':') == std::string_view::npos && name.front() != '/';
}

/// What openGaussianColumns found in a scene's first bytes.
struct GaussianColumns {
  /// The decoder, or null: not (yet) known to be a column format.
  std::unique_ptr<GaussianColumnDecoder> decoder;
  /// With no decoder: true when more bytes may still show one (the head of an SPZ v4 file
  /// or its table of contents, a GLB's JSON chunk, or the rest of a JSON object of at most
  /// 1 MiB, which may be a .gltf or an SOG's meta.json, has not arrived); false when the
  /// scene is not read by columns.
  bool needMore = false;
};

/// The column decoder of the scene `name` whose first bytes are `head` and whose size is
/// `fileBytes` (0 when not known: then none): an SPZ v4 file (its header and table of
/// contents in `head`), or a GLB or .gltf of one KHR_gaussian_splatting primitive instance
/// whose accessors lie tightly packed in its BIN chunk or its buffer files (Column::file;
/// its header and JSON chunk in `head`, a .gltf's whole JSON of at most 1 MiB; one column
/// per attribute read, COLOR_0 only where it is the colour; data: buffers, interleaved
/// accessors or more primitives are read whole). Throws FormatError naming `name` for what
/// the whole-file readers refuse in the header, table of contents or JSON (a stream outside
/// the file, a stream of the wrong size for its splats, an accessor past its buffer, a
/// buffer file named with "..", a scheme or a leading '/'). An SOG's meta.json (whole, at
/// most 1 MiB) gives its WebP images as columns (Column::webp; its SH centroids whole
/// first, Column::whole), as readSogGaussians reads them.
GaussianColumns openGaussianColumns(std::string_view head, const std::string& name,
                                    std::uint64_t fileBytes);

/// A scene whose splats come out of one compressed stream read forward, decoded as its
/// bytes arrive: an SPZ v2/v3 file, gzip data of a header and the attribute blocks one
/// after another (positions, alphas, colours, scales, rotations, SH). A splat is given,
/// with all it holds, once its record of the last block has come: the blocks before it are
/// held decompressed (about 20 bytes a splat), the last one's records go as they are
/// decoded. A remote SPZ v2/v3 drawn while it arrives (docs/splats.md, "Opening a scene").
class GaussianStreamDecoder {
 public:
  virtual ~GaussianStreamDecoder() = default;
  /// The scene's splats (1..kMaxSplats).
  virtual std::uint64_t size() const = 0;
  /// SH degree (0..3).
  virtual int shDegree() const = 0;
  /// Takes the file's next bytes, from its first on (any split). Throws FormatError naming
  /// the scene for damaged data or data past the blocks by more than the whole reader
  /// allows (1 MiB).
  virtual void feed(std::string_view bytes) = 0;
  /// Decodes into `batch` (resized to them) up to `max` of the splats that came and that
  /// next() did not give yet, in file order: exactly the whole-file reader's splats.
  /// Returns how many (0 when none is waiting).
  virtual std::size_t next(GaussianCloud& batch, std::size_t max) = 0;
  /// Splats given by next() so far.
  virtual std::uint64_t decoded() const = 0;
  /// Bytes the data fed so far decompressed to (a caller may pace its feeding by them: a
  /// block of zeros inflates up to 1032 times).
  virtual std::uint64_t inflated() const = 0;
  /// After the file's last byte: FormatError naming the scene unless its data ended as
  /// readGaussians requires (every block complete, the last gzip member ended).
  virtual void finish() = 0;
};

/// What openGaussianStream found in a scene's first bytes.
struct GaussianStream {
  /// The decoder (nothing fed yet: feed it the file from its first byte), or null.
  std::unique_ptr<GaussianStreamDecoder> decoder;
  /// With no decoder: true when more bytes may still show one (fewer than the 16
  /// decompressed bytes of an SPZ header have come); false when the scene is not read as
  /// a stream.
  bool needMore = false;
};

/// The stream decoder of the scene `name` whose first bytes are `head` and whose size is
/// `fileBytes` (0 when not known): an SPZ v2/v3 file (gzip whose first decompressed bytes
/// are the NGSP magic). Throws FormatError naming `name` for what readSpzGaussians refuses
/// in the header (a version, an SH degree, header extensions, more splats than kMaxSplats
/// or than `fileBytes` of gzip data can hold).
GaussianStream openGaussianStream(std::string_view head, const std::string& name,
                                  std::uint64_t fileBytes);

/// One column's bytes turned, as they arrive in order, into its records (a zstd column
/// decompressed forward, a WebP image decoded a band of rows at a time): what
/// GaussianColumnDecoder::decode reads. Memory: the compressed bytes not yet decompressed,
/// and the records decompressed ahead of the last decodeUpTo's target (a WebP image: its
/// whole RGBA picture too, inside libwebp's decoder).
class ColumnRecords {
 public:
  /// Column `index` of `column` for `splats` splats of the scene `name` (named by errors).
  ColumnRecords(const GaussianColumnDecoder::Column& column, std::uint64_t splats, std::string name,
                int index);
  ~ColumnRecords();
  ColumnRecords(const ColumnRecords&) = delete;
  ColumnRecords& operator=(const ColumnRecords&) = delete;
  /// Takes the column's next bytes (FormatError past its size in the file, or, of unknown
  /// size, past 1 GiB).
  void feed(std::string_view bytes);
  /// Decodes the bytes fed so far until records up to (not including) `record`, counted
  /// from the column's first, are available, or the bytes fed run out (a WebP image: every
  /// row the bytes give; a whole column: all of them). FormatError for damaged data, more
  /// records than the scene's splats, or an image larger than maxTexels or of another
  /// width than a whole column's.
  void decodeUpTo(std::uint64_t record);
  /// A whole column's image, once decoded whole (complete()): its texels and size.
  bool complete() const { return complete_; }
  std::string_view texels() const { return records_; }
  int imageWidth() const { return width_; }
  int imageHeight() const { return height_; }
  /// True the first time it is called once complete() (decodeColumns hands a whole column
  /// to its decoder once).
  bool handOver() { return complete_ && !handedOver_ && (handedOver_ = true); }
  /// The first record held (records before it were dropped) and how many follow it.
  std::uint64_t first() const { return first_; }
  std::uint64_t available() const { return records_.size() / recordBytes_; }
  /// Record first(), followed by available() - 1 more.
  const char* data() const { return records_.data(); }
  /// Forgets the first `n` records held (n <= available()).
  void drop(std::uint64_t n);
  /// Whether all its bytes were fed (of unknown size: whether its image was decoded whole).
  bool fed() const {
    return column_.bytes == 0 && column_.webp ? complete_ : fed_ == column_.bytes;
  }
  /// Once fed() and decoded to the end: FormatError naming the scene and column unless its
  /// bytes decoded to exactly one record per splat (a zstd frame complete, nothing after;
  /// a WebP image complete with a texel for each splat at least).
  void finish();

 private:
  struct Zstd;
  struct Webp;
  /// decodeUpTo for a WebP image; `last`: no more bytes will come (finish).
  void decodeWebp(bool last);
  /// A WebP column's name in errors: its file quoted, or "'column K'".
  std::string webpName() const;
  GaussianColumnDecoder::Column column_;
  std::uint64_t splats_;
  std::string name_;
  int index_;
  std::size_t recordBytes_;
  std::uint64_t fed_ = 0, first_ = 0, produced_ = 0;  // produced_: bytes of records made
  std::string pending_;                               // bytes fed, not yet decompressed
  std::string records_;  // whole records from first_, and a record's bytes begun after them
  std::unique_ptr<Zstd> zstd_;
  std::size_t hint_ = 1;  // ZSTD_decompressStream's last return: 0 when the frame ended
  std::unique_ptr<Webp> webp_;
  int width_ = 0, height_ = 0;  // a WebP image's, once its header came
  bool complete_ = false;       // a WebP image decoded whole
  bool handedOver_ = false;
};

/// One step of reading a scene by columns: decodes each column's records up to splat
/// `decoded + max` (at most the decoder's size()), gives the decoder each whole column once
/// complete (takeWhole), then decodes into `batch` (resized to them) the splats from
/// `decoded` on whose every record came, drops their records and returns how many (0: none
/// yet). `columns[k]` reads the decoder's column k. FormatError for damaged data.
std::size_t decodeColumns(GaussianColumnDecoder& decoder,
                          const std::vector<ColumnRecords*>& columns, std::uint64_t decoded,
                          std::size_t max, GaussianCloud& batch);

/// openGaussianBatches's error for a scene of a format it does not read piecewise (which
/// the whole-file readers do read).
struct NotPiecewiseError : FormatError {
  using FormatError::FormatError;
};

/// Opens the scene at `path` for piecewise reading (docs/out-of-core.md, "Gaussian
/// splatting scenes"):
/// - a binary INRIA .ply (either byte order; the vertex element after no element with a
///   list) and a .splat: a batch's rows read by offset;
/// - a PlayCanvas .compressed.ply: the batch's chunk, vertex and sh records by offset;
/// - an .spz: each attribute block decompressed forward side by side (v2-v3: one inflate
///   per block over the same gzip data, each skipping the blocks before it; v4: one zstd
///   stream per block);
/// - SOG (a .sog bundle, or a meta.json whose WebP images `sideFiles` reads): the textures
///   decoded whole (about 28 bytes a splat), the splats converted a batch at a time;
/// - glTF KHR_gaussian_splatting (a .glb, or a .gltf whose buffer files lie beside it):
///   the JSON parsed alone, each batch's accessor elements read by offset.
/// Each batch holds exactly the splats the whole-file reader gives at those places.
/// Throws NotPiecewiseError naming the file for an ascii PLY, a glTF of sparse accessors
/// or compressed buffers, a QNV stream, LAS and what is no splat scene ("PATH: read
/// piecewise are ..., not a LAS point cloud"), and
/// FormatError for what the whole-file readers refuse in the header or size (or a file
/// that cannot be opened); read() throws FormatError for damage found later (a truncated
/// or corrupt compressed stream, naming the file).
std::unique_ptr<GaussianBatchReader> openGaussianBatches(const std::string& path,
                                                         const SideFileReader& sideFiles = {});

/// INRIA 3DGS .ply (binary little-endian or ascii; Kerbl et al.'s output): x y z,
/// f_dc_0..2, f_rest_0..(3k-1) channel-major (k = 0, 3, 8 or 15), opacity (logit),
/// scale_0..2 (log), rot_0..3 (w x y z, normalised here). Missing f_rest: degree 0; a
/// missing scale_2 (a 2DGS surfel) gives a flat Gaussian. Any numeric property type, either
/// byte order. A PlayCanvas compressed PLY given here is read as readCompressedPlyGaussians.
GaussianCloud readPlyGaussians(std::string_view bytes, std::string_view name);
/// PlayCanvas .compressed.ply: chunk element (min/max of position, scale, colour) and
/// packed vertex element (11-10-11 position and scale, 2-10-10-10 smallest-three rotation,
/// 8888 colour and opacity), optional sh element (8-bit).
GaussianCloud readCompressedPlyGaussians(std::string_view bytes, std::string_view name);
/// antimatter15 .splat: 32 bytes per splat (float x y z, float linear scales,
/// uint8 RGBA, uint8 rotation w x y z mapped from -1..1).
GaussianCloud readSplatGaussians(std::string_view bytes, std::string_view name);
/// Niantic .spz versions 2 to 4: gzip of a 16-byte header and packed attributes (v2-v3),
/// or the NGSP header of v4 with zstd-compressed attribute streams. Decoded raw, as
/// splat-transform does (no coordinate conversion; SH bytes as (b - 128) / 128, Adobe's SH
/// quantisation extension not applied). SH degree 4 keeps degrees 1-3; the header
/// extensions of v4 are skipped; a v2/v3 file with extensions (flag 0x2) is refused.
GaussianCloud readSpzGaussians(std::string_view bytes, std::string_view name);
/// PlayCanvas SOG version 2: `bytes` is a .sog zip bundle (stored or deflated entries), or
/// a meta.json whose WebP images `sideFiles` reads. WebP through libwebp. The legacy
/// version 1 layout (no "version" in meta.json) is refused.
GaussianCloud readSogGaussians(std::string_view bytes, std::string_view name,
                               const SideFileReader& sideFiles);
/// glTF 2.0 (.gltf or .glb) with KHR_gaussian_splatting POINTS primitives: every such
/// primitive of every mesh instance in the default scene, placed by its node's world
/// transform (SH rotated with it), converted from glTF's axes to the .ply axes above (180
/// degrees about Z). SCALE is linear and OPACITY 0..1 (the ratified extension; what
/// splat-transform writes); COLOR_0 stands in for a missing SH_DEGREE_0_COEF_0.
/// colorSpace "srgb_rec709_display" or "lin_rec709_display" (another is a FormatError);
/// every kernel is read as "ellipse" (the extension's fallback). At most one splat per
/// byte of the file and its buffers (instancing cannot multiply memory).
GaussianCloud readGltfGaussians(std::string_view bytes, std::string_view name,
                                const SideFileReader& sideFiles);

/// An ASPRS LAS 1.0-1.4 point cloud (point formats 0-10, uncompressed): one opaque,
/// isotropic Gaussian per point, as wide (standard deviation) as half the points' mean
/// spacing over the bounding box's largest face, coloured by its RGB (8- or 16-bit, as
/// the file holds them) or, without RGB, by its intensity as grey. Positions are
/// X * scale + offset in double precision, minus the header's minimum corner (written to
/// `origin` when given), in the file's axes (z up, metres as the file says). A LAZ file
/// (point format with bit 7 or 6 set) is a FormatError that says how to decompress it:
/// no Debian library decodes LAZ here. Throws FormatError for a truncated file, an
/// unknown version or format, or impossible scales.
GaussianCloud readLasPoints(std::string_view bytes, std::string_view name,
                            glm::dvec3* origin = nullptr);

/// Any of the above by detectSplatFormat(bytes, name). Throws FormatError for an
/// unknown format ("NAME: not a Gaussian splatting scene") and whatever the reader throws.
GaussianCloud readGaussians(std::string_view bytes, std::string_view name,
                            const SideFileReader& sideFiles);

}  // namespace gs::splats
