// ZIP archives in memory (zip_reader.hpp).
#include "zip_reader.hpp"

#include <zlib.h>

#include <algorithm>
#include <limits>

#include "base/byte_order.hpp"
#include "reader_support.hpp"

namespace gs::splats::detail {

namespace {

std::uint16_t u16(std::string_view b, std::size_t at) {
  return base::loadLe<std::uint16_t>(b.data() + at);
}
std::uint32_t u32(std::string_view b, std::size_t at) {
  return base::loadLe<std::uint32_t>(b.data() + at);
}

}  // namespace

bool ZipArchive::isZip(std::string_view bytes) {
  return bytes.substr(0, 4) == std::string_view("PK\3\4", 4);
}

ZipArchive::ZipArchive(std::string_view bytes, std::string_view name) : bytes_(bytes), name_(name) {
  // End of central directory record: 22 bytes and a comment of up to 65535.
  constexpr std::size_t kEocd = 22;
  if (bytes.size() < kEocd)
    fail(name, "ZIP archive too short (" + std::to_string(bytes.size()) + " bytes)");
  std::size_t eocd = std::string_view::npos;
  const std::size_t lowest =
      bytes.size() - kEocd - std::min<std::size_t>(bytes.size() - kEocd, 65535);
  for (std::size_t at = bytes.size() - kEocd + 1; at-- > lowest;) {
    if (u32(bytes, at) == 0x06054b50u && at + kEocd + u16(bytes, at + 20) == bytes.size()) {
      eocd = at;
      break;
    }
  }
  if (eocd == std::string_view::npos) fail(name, "ZIP end of central directory not found");
  const std::size_t count = u16(bytes, eocd + 10);
  const std::uint32_t cdSize = u32(bytes, eocd + 12), cdOffset = u32(bytes, eocd + 16);
  if (cdOffset == 0xffffffffu || count == 0xffff) fail(name, "ZIP64 archives are not supported");
  if (static_cast<std::uint64_t>(cdOffset) + cdSize > eocd)
    fail(name, "ZIP central directory lies outside the archive");
  std::size_t at = cdOffset;
  const std::size_t end = static_cast<std::size_t>(cdOffset) + cdSize;
  for (std::size_t i = 0; i < count; ++i) {
    if (end - at < 46 || u32(bytes, at) != 0x02014b50u) fail(name, "damaged ZIP central directory");
    Entry e;
    const std::uint16_t flags = u16(bytes, at + 8);
    e.method = u16(bytes, at + 10);
    e.crc = u32(bytes, at + 16);
    e.compressed = u32(bytes, at + 20);
    e.size = u32(bytes, at + 24);
    const std::size_t n = u16(bytes, at + 28), extra = u16(bytes, at + 30),
                      comment = u16(bytes, at + 32);
    e.localOffset = u32(bytes, at + 42);
    if (end - at - 46 < n + extra + comment) fail(name, "damaged ZIP central directory");
    e.name = std::string(bytes.substr(at + 46, n));
    if (flags & 1u) fail(name, "ZIP entry '" + e.name + "' is encrypted");
    entries_.push_back(std::move(e));
    at += 46 + n + extra + comment;
  }
}

bool ZipArchive::has(std::string_view entry) const {
  return std::any_of(entries_.begin(), entries_.end(),
                     [&](const Entry& e) { return e.name == entry; });
}

std::string ZipArchive::read(std::string_view entry, std::size_t maxBytes) const {
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const Entry& e) { return e.name == entry; });
  const std::string what = "ZIP entry '" + std::string(entry) + "'";
  if (it == entries_.end()) fail(name_, what + " missing");
  const Entry& e = *it;
  if (e.size > maxBytes)
    fail(name_,
         what + " is " + std::to_string(e.size) + " bytes, more than " + std::to_string(maxBytes));
  const std::uint64_t local = e.localOffset;
  if (local + 30 > bytes_.size() || u32(bytes_, static_cast<std::size_t>(local)) != 0x04034b50u)
    fail(name_, what + ": bad local header");
  const std::uint64_t data = local + 30 + u16(bytes_, static_cast<std::size_t>(local + 26)) +
                             u16(bytes_, static_cast<std::size_t>(local + 28));
  if (data > bytes_.size() || e.compressed > bytes_.size() - data)
    fail(name_,
         what + ": expected " + std::to_string(e.compressed) + " bytes, the archive ends first");
  const std::string_view in = bytes_.substr(static_cast<std::size_t>(data), e.compressed);
  auto checked = [&](std::string out) {
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(out.data()),
                            static_cast<uInt>(out.size()));
    if (crc != e.crc) fail(name_, what + ": CRC-32 mismatch (damaged data)");
    return out;
  };
  if (e.method == 0) {
    if (e.compressed != e.size) fail(name_, what + ": stored sizes differ");
    return checked(std::string(in));
  }
  if (e.method != 8)
    fail(name_, what + ": unsupported compression method " + std::to_string(e.method));
  // Deflate expands at most 1032:1 (RFC 1951 length codes): a larger claim is damage.
  if (e.size / 1032 > in.size() + 1) fail(name_, what + ": impossible inflated size");
  std::string out(e.size, '\0');
  z_stream zs{};
  if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) fail(name_, what + ": zlib could not start");
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(in.data()));
  zs.avail_in = static_cast<uInt>(in.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&zs, Z_FINISH);
  const std::size_t produced = out.size() - zs.avail_out;
  inflateEnd(&zs);
  if (rc != Z_STREAM_END || produced != e.size) fail(name_, what + ": damaged deflate data");
  return checked(std::move(out));
}

}  // namespace gs::splats::detail
