// File access for the slab readers (formats/volume_slabs.hpp), private to formats/src:
// positioned reads of a file and a gzip stream inflated sequentially with zlib (never
// whole), both throwing InputError that names the file and the byte offset.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/inflate_stream.hpp"

namespace gs::formats::detail {

/// A file open for positioned reads.
class RandomFile {
 public:
  /// Throws InputError "cannot open PATH: REASON".
  explicit RandomFile(std::string path);
  ~RandomFile();
  RandomFile(const RandomFile&) = delete;
  RandomFile& operator=(const RandomFile&) = delete;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  /// Reads exactly `n` bytes at `offset`; throws InputError "PATH: short read at byte
  /// offset O: expected N bytes, got M" (or the system's reason).
  void readAt(std::uint64_t offset, char* dst, std::size_t n) const;
  /// Up to `n` bytes at `offset` (fewer at the end of the file).
  std::size_t readSome(std::uint64_t offset, char* dst, std::size_t n) const;

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// The offset just after the first `lines` lines ("\n", "\r\n" or "\r" ended) of `file`
/// from `start` (teem's "line skip"). Throws InputError "PATH: expected N lines to skip,
/// got M" when the file ends sooner.
std::uint64_t offsetAfterLines(const RandomFile& file, std::uint64_t start, std::uint64_t lines);

/// The decompressed bytes of the gzip (or zlib) data of a file from a compressed offset
/// on, read forward (base::InflateStream over the file); concatenated gzip members are one
/// stream. Memory: zlib's state plus a 256 KiB input buffer.
class GzipStream {
 public:
  GzipStream(std::string path, std::uint64_t compressedOffset);
  ~GzipStream();
  GzipStream(const GzipStream&) = delete;
  GzipStream& operator=(const GzipStream&) = delete;

  const std::string& path() const { return file_.path(); }
  /// Decompressed bytes handed out (or skipped) so far.
  std::uint64_t position() const { return inflate_.position(); }
  /// Up to `n` decompressed bytes; fewer only at the end of the data. Throws InputError
  /// "PATH: corrupt gzip data at compressed byte offset O: REASON".
  std::size_t read(char* dst, std::size_t n);
  /// Skips `n` decompressed bytes; returns how many there were (fewer at the end).
  std::uint64_t skip(std::uint64_t n);
  /// Back to the start of the data.
  void rewind();

 private:
  RandomFile file_;
  base::InflateStream inflate_;
};

/// `relative` resolved against the folder of `headerPath`; absolute paths and ".."
/// components are refused (InputError naming the header), so that a header from
/// elsewhere cannot read arbitrary local files.
std::string resolveBeside(const std::string& headerPath, const std::string& relative);

}  // namespace gs::formats::detail
