// NIfTI-1 single files (.nii): the 348-byte header of nifti1.h in either byte order, then
// the samples from vox_offset.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "base/byte_order.hpp"
#include "formats/volume_readers.hpp"

namespace gs::formats {

namespace {

constexpr std::size_t kHeaderBytes = 348;
constexpr std::size_t kMinVoxOffset = 352;  // header + 4 extension bytes

// Byte offsets of the nifti_1_header fields used here.
constexpr std::size_t kSizeofHdr = 0, kDim = 40, kDatatype = 70, kPixdim = 76, kVoxOffset = 108,
                      kSclSlope = 112, kSclInter = 116, kQformCode = 252, kSformCode = 254,
                      kQoffset = 268, kSrowX = 280, kSrowY = 296, kSrowZ = 312, kMagic = 344;

// Reads fields of a header whose byte order may differ from the machine's.
struct HeaderView {
  const char* p;
  bool swap;

  template <typename U>
  U load(std::size_t offset) const {
    U v;
    std::memcpy(&v, p + offset, sizeof v);
    return swap ? base::byteSwap(v) : v;
  }
  std::int16_t i16(std::size_t offset) const {
    return std::bit_cast<std::int16_t>(load<std::uint16_t>(offset));
  }
  std::int32_t i32(std::size_t offset) const {
    return std::bit_cast<std::int32_t>(load<std::uint32_t>(offset));
  }
  float f32(std::size_t offset) const { return std::bit_cast<float>(load<std::uint32_t>(offset)); }
};

bool typeOfCode(int code, ScalarType& type) {
  switch (code) {
    case 2:
      type = ScalarType::uint8;
      return true;
    case 4:
      type = ScalarType::int16;
      return true;
    case 8:
      type = ScalarType::int32;
      return true;
    case 16:
      type = ScalarType::float32;
      return true;
    case 64:
      type = ScalarType::float64;
      return true;
    case 256:
      type = ScalarType::int8;
      return true;
    case 512:
      type = ScalarType::uint16;
      return true;
    case 768:
      type = ScalarType::uint32;
      return true;
    case 1024:
      type = ScalarType::int64;
      return true;
    case 1280:
      type = ScalarType::uint64;
      return true;
    default:
      return false;
  }
}

const char* codeMeaning(int code) {
  switch (code) {
    case 1:
      return " (1-bit binary)";
    case 32:
      return " (complex64)";
    case 128:
      return " (RGB24)";
    case 1536:
      return " (float128)";
    case 1792:
      return " (complex128)";
    case 2048:
      return " (complex256)";
    case 2304:
      return " (RGBA32)";
    default:
      return "";
  }
}

float usableSpacing(float s) {
  s = std::fabs(s);
  return std::isfinite(s) && s > 0.0f ? s : 1.0f;
}

float finiteOr0(float v) {
  return std::isfinite(v) ? v : 0.0f;
}

}  // namespace

NiftiHeader parseNiftiHeader(std::string_view bytes, const std::string& name,
                             std::uint64_t fileBytes) {
  if (bytes.size() < kHeaderBytes)
    throw InputError(name + ": not a NIfTI-1 file (expected a 348-byte header, got " +
                     std::to_string(bytes.size()) + " bytes)");
  std::uint32_t sizeofHdr;
  std::memcpy(&sizeofHdr, bytes.data() + kSizeofHdr, sizeof sizeofHdr);
  const std::uint32_t swapped = base::byteSwap(sizeofHdr);
  if (sizeofHdr == 540 || swapped == 540)
    throw InputError(name + ": NIfTI-2 files are not supported; save the volume as NIfTI-1");
  if (sizeofHdr != kHeaderBytes && swapped != kHeaderBytes)
    throw InputError(name + ": not a NIfTI-1 file (sizeof_hdr is neither 348 nor 348 swapped)");
  const HeaderView h{bytes.data(), sizeofHdr != kHeaderBytes};

  const std::string_view magic = bytes.substr(kMagic, 4);
  if (magic == std::string_view("ni1\0", 4))
    throw InputError(name +
                     ": NIfTI-1 header/image pairs (.hdr/.img) are not supported; convert the "
                     "volume to a single .nii file");
  if (magic != std::string_view("n+1\0", 4))
    throw InputError(name + ": not a NIfTI-1 file (expected the magic 'n+1', found none)");

  // Dimensions: dim[0] axes, dim[1..3] x y z; any further axes must have size 1.
  const int rank = h.i16(kDim);
  if (rank < 1 || rank > 7)
    throw InputError(name + ": expected dim[0] between 1 and 7, got " + std::to_string(rank));
  glm::uvec3 dims{1, 1, 1};
  for (int i = 1; i <= rank; ++i) {
    const int d = h.i16(kDim + 2 * static_cast<std::size_t>(i));
    if (d < 1)
      throw InputError(name + ": expected dim[" + std::to_string(i) + "] >= 1, got " +
                       std::to_string(d));
    if (i <= 3)
      dims[i - 1] = static_cast<std::uint32_t>(d);
    else if (d != 1)
      throw InputError(name + ": expected a 3-dimensional volume, got dim[" + std::to_string(i) +
                       "] = " + std::to_string(d) +
                       " (time series and vector volumes are "
                       "not supported)");
  }

  const int code = h.i16(kDatatype);
  RawLayout layout;
  if (!typeOfCode(code, layout.type))
    throw InputError(name + ": unsupported NIfTI datatype " + std::to_string(code) +
                     codeMeaning(code));
  layout.dims = dims;
  layout.bigEndian = (std::endian::native == std::endian::big) != h.swap;
  for (int i = 0; i < 3; ++i)
    layout.spacing[i] = usableSpacing(h.f32(kPixdim + 4 * static_cast<std::size_t>(i + 1)));

  const float voxOffset = h.f32(kVoxOffset);
  // A bound on vox_offset that keeps the cast below defined when the size is unknown.
  const double limit = std::min(static_cast<double>(fileBytes), 0x1p62);
  if (!std::isfinite(voxOffset) || voxOffset < 0.0f || static_cast<double>(voxOffset) > limit)
    throw InputError(name + ": expected vox_offset within the file's " + std::to_string(fileBytes) +
                     " bytes, got " + std::to_string(voxOffset));
  layout.headerBytes = voxOffset < static_cast<float>(kMinVoxOffset)
                           ? kMinVoxOffset
                           : static_cast<std::size_t>(voxOffset);

  NiftiHeader out;
  out.layout = layout;
  const float slope = h.f32(kSclSlope);
  if (std::isfinite(slope) && slope != 0.0f) {
    out.scaled = true;
    out.slope = slope;
    out.inter = finiteOr0(h.f32(kSclInter));
  }
  if (h.i16(kQformCode) > 0) {
    for (int i = 0; i < 3; ++i)
      out.origin[i] = finiteOr0(h.f32(kQoffset + 4 * static_cast<std::size_t>(i)));
  } else if (h.i16(kSformCode) > 0) {
    out.origin = {finiteOr0(h.f32(kSrowX + 12)), finiteOr0(h.f32(kSrowY + 12)),
                  finiteOr0(h.f32(kSrowZ + 12))};
  }
  return out;
}

Volume readNifti(std::string_view bytes, const std::string& name) {
  const NiftiHeader header = parseNiftiHeader(bytes, name, bytes.size());
  Volume v = decodeRaw(bytes, header.layout, name);
  if (header.scaled)
    for (float& s : v.samples) s = s * header.slope + header.inter;
  v.origin = header.origin;
  return v;
}

}  // namespace gs::formats
