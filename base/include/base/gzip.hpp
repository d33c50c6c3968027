// gzip (RFC 1952) decompression through zlib, shared by the VRML parser (.wrl.gz, .wrz)
// and the mesh and volume readers (.ply.gz, .nii.gz, NRRD "encoding: gzip").
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace gs::base {

/// Whether `bytes` start with the gzip magic 1f 8b.
bool isGzip(std::string_view bytes);

/// Why gunzip failed. what() is the reason alone, without naming the input:
/// "corrupt gzip data: truncated", "decompressed data exceeds 1024 bytes".
struct GzipError : std::runtime_error {
  enum class Kind {
    corrupt,   // not gzip, damaged, truncated, or trailing bytes after the last member
    tooLarge,  // more than the caller's maxBytes once decompressed
  };
  GzipError(Kind k, const std::string& what) : std::runtime_error(what), kind(k) {}
  Kind kind;
};

/// Decompresses the gzip data `bytes` (one or more concatenated members, RFC 1952 2.2;
/// zero padding after the last member is tolerated). Throws GzipError: Kind::corrupt
/// ("corrupt gzip data: <zlib's reason>" or "... trailing bytes after the gzip data"),
/// Kind::tooLarge ("decompressed data exceeds N bytes") as soon as the output would
/// exceed `maxBytes`.
std::string gunzip(std::string_view bytes, std::size_t maxBytes);

/// gunzip(bytes, maxBytes) when `bytes` start with the gzip magic, else `bytes` as they
/// are (not limited by maxBytes).
std::string gunzipIfCompressed(std::string_view bytes, std::size_t maxBytes);

/// As much of the start of the gzip data `bytes` as decompresses, up to `maxBytes`
/// (for sniffing what a compressed file holds). Never throws; empty when `bytes` are not
/// gzip or are damaged at once.
std::string gunzipPrefix(std::string_view bytes, std::size_t maxBytes);

}  // namespace gs::base
