// A reader of ZIP archives (PKWARE APPNOTE 6.3, sections 4.3.7, 4.3.12, 4.3.16) held in
// memory, for SOG bundles: stored and deflated entries, no ZIP64, no encryption, every
// offset and size checked against the bytes, inflated sizes bounded, CRC-32 verified.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gs::splats::detail {

class ZipArchive {
 public:
  /// Reads the central directory of `bytes` (kept by view: they must outlive this).
  /// Throws FormatError "NAME: ..." when it is not a readable ZIP archive.
  ZipArchive(std::string_view bytes, std::string_view name);

  /// Whether the archive holds an entry called `entry` (exact, case-sensitive).
  bool has(std::string_view entry) const;
  /// The bytes of `entry`, inflated. FormatError when it is missing, uses an unsupported
  /// method, lies outside the archive, is damaged (CRC-32 included), or is larger than
  /// `maxBytes`.
  std::string read(std::string_view entry, std::size_t maxBytes) const;

  /// True when `bytes` start with a ZIP local file header ("PK\3\4").
  static bool isZip(std::string_view bytes);

 private:
  struct Entry {
    std::string name;
    std::uint16_t method = 0;
    std::uint32_t crc = 0, compressed = 0, size = 0, localOffset = 0;
  };
  std::string_view bytes_;
  std::string name_;
  std::vector<Entry> entries_;
};

}  // namespace gs::splats::detail
