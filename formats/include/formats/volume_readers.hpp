// Readers that turn the bytes of a volume file into a Volume: NRRD (attached or detached
// header), NIfTI-1 single files (.nii) and headerless raw grids. They work on bytes the
// caller has already read (and, for gzip, decompressed); session/volume_input.hpp does
// the file I/O.
// Every reader is safe for hostile input: a malformed header or short data gives
// InputError naming the input, never a crash, an out-of-bounds read or an allocation
// larger than the data in hand (at most kMaxVoxels floats).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/error.hpp"
#include "qnv/volume.hpp"

namespace gs::formats {

// The readers produce the volume encoder's input type and throw the codec's error type,
// so that a volume read here goes to qnv::encodeVolume as it is.
using qnv::InputError;
using qnv::kMaxVoxels;
using qnv::scalarBytes;
using qnv::ScalarType;
using qnv::Volume;

/// The short name of `type` as parseScalarType accepts it: "int8", "uint16", "float32"...
const char* scalarTypeName(ScalarType type);

/// Parses a sample type as written on the command line: int8 uint8 int16 uint16 int32
/// uint32 int64 uint64 float32 float64, plus the C names char (int8), uchar (uint8),
/// short (int16), ushort (uint16), float (float32) and double (float64). Case-insensitive.
/// Throws InputError ("unknown sample type 'x'; expected one of ...") otherwise.
ScalarType parseScalarType(std::string_view text);

// ---------------------------------------------------------------------------- NRRD

/// What a NRRD header (teem's format, magics NRRD0001..NRRD0005) says about its volume.
struct NrrdHeader {
  enum class Encoding { raw, gzip, ascii, hex };

  glm::uvec3 dims{0, 0, 0};  // samples along x, y, z; each >= 1, product <= kMaxVoxels
  /// Values per voxel (NrrdParseOptions::componentAxis): 2..4 when the first of 4 axes
  /// holds a voxel's components (grey-alpha, RGB, RGBA), folded into dims.x (which is
  /// then components x the voxels along x); 1 otherwise.
  ScalarType type = ScalarType::uint8;
  bool bigEndian = false;  // byte order of binary samples ("endian:", little when absent)
  Encoding encoding = Encoding::raw;
  glm::vec3 spacing{1, 1, 1};  // distance between samples (file units, > 0)
  glm::vec3 origin{0, 0, 0};   // "space origin", position of sample (0,0,0)
  /// The single file named by "data file:" as written (relative to the header's
  /// folder); empty when the data is attached to the header.
  std::string dataFile;
  /// Attached data: byte offset of the first data byte (just after the blank line that
  /// ends the header). Detached: the size of the header text.
  std::size_t dataOffset = 0;
  /// "line skip:": lines to skip at the start of the data file (or attached data) before
  /// reading. For gzip data teem skips them in the compressed bytes (see skipNrrdLines).
  std::size_t lineSkip = 0;
  /// "byte skip:": bytes to skip after the line skip; for gzip data, in the decompressed
  /// bytes. -1 means the data is the last dataBytes() bytes (raw and gzip only).
  std::int64_t byteSkip = 0;

  /// Multi-file data (only with NrrdParseOptions::multiFile): every data file in order,
  /// from "data file: LIST [SUBDIM]" (the names on the lines after it) or "data file:
  /// FORMAT MIN MAX STEP [SUBDIM]" (FORMAT holds one printf-style integer conversion,
  /// %d, %Nd or %0Nd, expanded for MIN, MIN + STEP, ... up to MAX). Each file holds
  /// samplesPerDataFile samples: the product of the sizes of the first SUBDIM axes
  /// (SUBDIM defaults to dimension - 1: one slice per file); line skip and byte skip
  /// apply to every file. Empty otherwise.
  std::vector<std::string> dataFiles;
  std::uint64_t samplesPerDataFile = 0;
  std::uint32_t components = 1;

  std::size_t voxelCount() const {
    return std::size_t{dims.x} * std::size_t{dims.y} * std::size_t{dims.z};
  }
  /// Bytes of binary sample data the header describes (voxelCount() * scalarBytes(type)).
  std::size_t dataBytes() const { return voxelCount() * scalarBytes(type); }
};

/// How parseNrrdHeader reads a header.
struct NrrdParseOptions {
  /// Accept the multi-file forms of "data file:" (LIST and FORMAT), filling
  /// NrrdHeader::dataFiles. Off: they are InputError "... not supported".
  bool multiFile = false;
  /// The most voxels the header may describe (kMaxVoxels for a whole volume in memory;
  /// slab readers allow qnv::kMaxSlabVolumeVoxels).
  std::uint64_t maxVoxels = kMaxVoxels;
  /// The most files a multi-file header may name.
  std::size_t maxDataFiles = std::size_t{1} << 20;
  /// Read the first axis of a 4-dimensional NRRD, when its size is 2..4, as each voxel's
  /// components (an X3D ImageTexture3D's RGB volume): NrrdHeader::components. Off: that
  /// axis must have size 1 unless the last one has (a volume of scalars is expected).
  bool componentAxis = false;
};

/// Parses the NRRD header at the start of `bytes` (a .nrrd file or a .nhdr detached
/// header; `name` names it in errors). The header is the magic line NRRD0001..NRRD0005,
/// then "field: value" lines up to a blank line or the end of `bytes`; "\n" and "\r\n"
/// line ends are accepted.
///
/// Fields read (names case-insensitive):
///   - type: every teem alias of the 8 integer and 2 floating types ("signed char",
///     "int8", "uchar", "unsigned short int", "int16_t", "long long", "uint64", "float",
///     "double", ...). "block" and unknown names are InputError.
///   - dimension: 3; 4 when the first (or last) axis has size 1 (e.g. one scalar
///     component), or with options.componentAxis the first has size 2..4; 2 for a single
///     slice (dims.z = 1).
///   - sizes: one integer >= 1 per axis, each < 2^32, product <= options.maxVoxels.
///   - spacings: one number per axis; nan/zero give 1, negatives their absolute value.
///   - space directions: one "(x,y,z)" vector (or "none") per axis; the vector lengths
///     become the spacings (they win over "spacings"). space origin "(x,y,z)" -> origin.
///   - endian: little | big.
///   - encoding: raw | gzip, gz | ascii, txt, text | hex (two hexadecimal digits per
///     byte, white space between them ignored). bzip2 and zrl are InputError.
///   - data file / datafile: one file name; the list forms ("LIST", "fmt%03d.raw min max
///     step") only with options.multiFile (see NrrdHeader::dataFiles), else InputError
///     "... not supported".
///   - line skip / lineskip (>= 0), byte skip / byteskip (>= -1).
/// Comment lines (#), "key:=value" pairs and other fields (content, kinds, labels,
/// units, space, ...) are ignored. type, dimension, sizes and encoding are required.
///
/// Throws InputError "name:LINE: expected ..., got ..." for a malformed line, and
/// "name: ..." for a missing magic, a missing required field, or a volume over limits.
NrrdHeader parseNrrdHeader(std::string_view bytes, const std::string& name,
                           const NrrdParseOptions& options = {});

/// Returns `bytes` without its first `lines` lines (each ended by "\n", "\r\n" or "\r"),
/// as teem applies "line skip:". For gzip data, call this on the compressed bytes before
/// decompressing them. Throws InputError "name: expected N lines to skip, got M" when
/// the bytes end sooner.
std::string_view skipNrrdLines(std::string_view bytes, std::size_t lines, const std::string& name);

/// Decodes the samples of a NRRD volume into a Volume (samples converted to float,
/// byte order honoured; dims, spacing, origin and sourceType from `header`).
///
/// `data` holds the data: for attached data, the header file's bytes from
/// header.dataOffset on; for detached data, the whole data file. For raw and ascii
/// encodings this function applies header.lineSkip, then header.byteSkip. For gzip the
/// caller applies the line skip to the compressed bytes (skipNrrdLines), decompresses,
/// and passes the decompressed bytes; this function then applies only the byte skip.
/// Byte skip -1 takes the last dataBytes() bytes. Bytes beyond the samples are ignored.
///
/// ascii data is numbers separated by whitespace or commas (integers or decimals).
/// Throws InputError "name: expected N bytes of voxel data, got M" when the data is
/// short, "name: expected N values of ascii voxel data, got M" or "name: expected a
/// number in ascii voxel data, got 'x'" for bad text.
Volume decodeNrrdData(const NrrdHeader& header, std::string_view data, const std::string& name);

// ---------------------------------------------------------------------------- NIfTI-1

/// Reads a NIfTI-1 single file (.nii, magic "n+1"; decompress .nii.gz first): the
/// 348-byte header in either byte order (detected from sizeof_hdr), then the samples
/// from vox_offset (values below 352 are taken as 352).
///   - dim[0] 3 (also 1 or 2, a line or slice; 4..7 when every dim beyond the third
///     is 1); dim[1..dim[0]] >= 1.
///   - datatype 2 uint8, 4 int16, 8 int32, 16 float32, 64 float64, 256 int8, 512 uint16,
///     768 uint32, 1024 int64, 1280 uint64; other codes (RGB, complex, ...) are
///     InputError naming the code.
///   - spacing = |pixdim[1..3]| (0 or non-finite -> 1), in the file's units.
///   - value = stored * scl_slope + scl_inter when scl_slope is finite and non-zero.
///   - origin = (qoffset_x, qoffset_y, qoffset_z) when qform_code > 0, else the
///     translation column of the sform when sform_code > 0, else (0,0,0).
/// Throws InputError for a short or non-NIfTI-1 header ("not a NIfTI-1 file"), NIfTI-2
/// and header/image pairs (magic "ni1": "... not supported; convert to a single .nii"),
/// and "name: expected N bytes of voxel data, got M" for short data.
Volume readNifti(std::string_view bytes, const std::string& name);

struct RawLayout;

/// What the header of a NIfTI-1 file says (readNifti's rules above), for readers that
/// fetch the samples themselves: the samples are laid out as `layout` says from
/// layout.headerBytes (the effective vox_offset) on; value = stored * slope + inter
/// when `scaled`.
struct NiftiHeader;

/// Parses the first 348 bytes of `bytes` as readNifti does. `fileBytes` is the size of
/// the whole (decompressed) file when known, for the vox_offset check; pass
/// UINT64_MAX when it is not (a .nii.gz read as a stream). Throws InputError as
/// readNifti does for the header.
NiftiHeader parseNiftiHeader(std::string_view bytes, const std::string& name,
                             std::uint64_t fileBytes);

// ---------------------------------------------------------------------------- raw

/// How the samples of a headerless raw file are laid out (x fastest, then y, then z).
struct RawLayout {
  glm::uvec3 dims{0, 0, 0};  // samples along x, y, z; each >= 1
  ScalarType type = ScalarType::uint8;
  bool bigEndian = false;
  glm::vec3 spacing{1, 1, 1};   // file units, each finite and > 0
  std::size_t headerBytes = 0;  // bytes to skip before the first sample
};

/// Decodes `bytes` laid out as `layout` says, converting samples to float. Bytes after
/// the samples are ignored. Throws InputError "name: ..." for a dim of 0, more than
/// kMaxVoxels voxels, a spacing that is not finite and positive, and "name: expected N
/// bytes of voxel data, got M" when `bytes` (after headerBytes) is short.
Volume decodeRaw(std::string_view bytes, const RawLayout& layout, const std::string& name);

/// See parseNiftiHeader.
struct NiftiHeader {
  RawLayout layout;  // dims, type, byte order, spacing, headerBytes = vox_offset
  bool scaled = false;
  float slope = 1.0f, inter = 0.0f;
  glm::vec3 origin{0, 0, 0};
};

/// Converts `count` packed samples of `type` at `src` (byte order `bigEndian`) to float.
void convertSamples(const char* src, std::size_t count, ScalarType type, bool bigEndian,
                    float* out);

}  // namespace gs::formats
