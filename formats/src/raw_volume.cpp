// Sample types and the one conversion loop every volume reader shares: packed samples of
// any ScalarType, either byte order, to float.
#include <algorithm>
#include <array>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>

#include "base/byte_order.hpp"
#include "base/text.hpp"
#include "formats/volume_readers.hpp"

namespace gs::formats {

namespace {

struct TypeName {
  std::string_view name;
  ScalarType type;
};

constexpr std::array<TypeName, 16> kTypeNames{{
    {"int8", ScalarType::int8},
    {"uint8", ScalarType::uint8},
    {"int16", ScalarType::int16},
    {"uint16", ScalarType::uint16},
    {"int32", ScalarType::int32},
    {"uint32", ScalarType::uint32},
    {"int64", ScalarType::int64},
    {"uint64", ScalarType::uint64},
    {"float32", ScalarType::float32},
    {"float64", ScalarType::float64},
    {"char", ScalarType::int8},
    {"uchar", ScalarType::uint8},
    {"short", ScalarType::int16},
    {"ushort", ScalarType::uint16},
    {"float", ScalarType::float32},
    {"double", ScalarType::float64},
}};

// Unsigned integer of N bytes, the unit a sample is loaded and byte-swapped as.
template <std::size_t N>
using Bits = std::conditional_t<
    N == 1, std::uint8_t,
    std::conditional_t<N == 2, std::uint16_t,
                       std::conditional_t<N == 4, std::uint32_t, std::uint64_t>>>;

template <typename T, bool Swap>
void convert(const char* src, std::size_t count, float* out) {
  using U = Bits<sizeof(T)>;
  for (std::size_t i = 0; i < count; ++i) {
    U u;
    std::memcpy(&u, src + i * sizeof(T), sizeof(T));
    if constexpr (Swap) u = base::byteSwap(u);
    out[i] = static_cast<float>(std::bit_cast<T>(u));
  }
}

template <typename T>
void convertOrder(const char* src, std::size_t count, bool swap, float* out) {
  if (swap)
    convert<T, true>(src, count, out);
  else
    convert<T, false>(src, count, out);
}

}  // namespace

const char* scalarTypeName(ScalarType type) {
  for (const TypeName& t : kTypeNames)
    if (t.type == type) return t.name.data();  // the first ten are NUL-terminated literals
  return "unknown";
}

ScalarType parseScalarType(std::string_view text) {
  const std::string lower = base::toLower(text);
  for (const TypeName& t : kTypeNames)
    if (t.name == lower) return t.type;
  std::string shown;
  for (char c : text.substr(0, 40))
    shown += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
  throw InputError("unknown sample type '" + shown +
                   "'; expected one of int8 uint8 int16 uint16 int32 uint32 int64 uint64 "
                   "float32 float64 (or char uchar short ushort float double)");
}

Volume decodeRaw(std::string_view bytes, const RawLayout& layout, const std::string& name) {
  const glm::uvec3 d = layout.dims;
  if (d.x == 0 || d.y == 0 || d.z == 0)
    throw InputError(name + ": expected volume dimensions >= 1, got " + std::to_string(d.x) +
                     " x " + std::to_string(d.y) + " x " + std::to_string(d.z));
  // Each factor is < 2^32, so x * y fits 64 bits; stop before a product could overflow.
  const std::uint64_t xy = std::uint64_t{d.x} * d.y;
  if (xy > kMaxVoxels || xy * d.z > kMaxVoxels)
    throw InputError(name + ": volume of " + std::to_string(d.x) + " x " + std::to_string(d.y) +
                     " x " + std::to_string(d.z) + " voxels exceeds the limit of " +
                     std::to_string(kMaxVoxels) + " voxels");
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(layout.spacing[i]) || !(layout.spacing[i] > 0.0f))
      throw InputError(name + ": expected spacings > 0, got " + std::to_string(layout.spacing[i]));
  const std::size_t count = static_cast<std::size_t>(xy * d.z);
  const std::size_t need = count * scalarBytes(layout.type);
  const std::size_t have =
      bytes.size() > layout.headerBytes ? bytes.size() - layout.headerBytes : 0;
  if (have < need)
    throw InputError(name + ": expected " + std::to_string(need) + " bytes of voxel data, got " +
                     std::to_string(have));

  Volume v;
  v.dims = d;
  v.spacing = layout.spacing;
  v.sourceType = layout.type;
  v.samples.resize(count);
  convertSamples(bytes.data() + layout.headerBytes, count, layout.type, layout.bigEndian,
                 v.samples.data());
  return v;
}

void convertSamples(const char* src, std::size_t count, ScalarType type, bool bigEndian,
                    float* out) {
  const bool swap = bigEndian != (std::endian::native == std::endian::big);
  switch (type) {
    case ScalarType::int8:
      convertOrder<std::int8_t>(src, count, false, out);
      break;
    case ScalarType::uint8:
      convertOrder<std::uint8_t>(src, count, false, out);
      break;
    case ScalarType::int16:
      convertOrder<std::int16_t>(src, count, swap, out);
      break;
    case ScalarType::uint16:
      convertOrder<std::uint16_t>(src, count, swap, out);
      break;
    case ScalarType::int32:
      convertOrder<std::int32_t>(src, count, swap, out);
      break;
    case ScalarType::uint32:
      convertOrder<std::uint32_t>(src, count, swap, out);
      break;
    case ScalarType::int64:
      convertOrder<std::int64_t>(src, count, swap, out);
      break;
    case ScalarType::uint64:
      convertOrder<std::uint64_t>(src, count, swap, out);
      break;
    case ScalarType::float32:
      convertOrder<float>(src, count, swap, out);
      break;
    case ScalarType::float64:
      convertOrder<double>(src, count, swap, out);
      break;
  }
}

}  // namespace gs::formats
