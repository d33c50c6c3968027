// Positioned file reads and streaming gzip for the slab readers (slab_io.hpp).
#include "slab_io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "base/gzip.hpp"
#include "qnv/error.hpp"

namespace gs::formats::detail {

using qnv::InputError;

RandomFile::RandomFile(std::string path) : path_(std::move(path)) {
  fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw InputError("cannot open " + path_ + ": " + std::strerror(errno));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode)) {
    ::close(fd_);
    throw InputError("cannot open " + path_ + ": not a regular file");
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

RandomFile::~RandomFile() {
  if (fd_ >= 0) ::close(fd_);
}

std::size_t RandomFile::readSome(std::uint64_t offset, char* dst, std::size_t n) const {
  std::size_t done = 0;
  while (done < n) {
    const ssize_t got = ::pread(fd_, dst + done, n - done, static_cast<off_t>(offset + done));
    if (got < 0) {
      if (errno == EINTR) continue;
      throw InputError(path_ + ": read error at byte offset " + std::to_string(offset + done) +
                       ": " + std::strerror(errno));
    }
    if (got == 0) break;
    done += static_cast<std::size_t>(got);
  }
  return done;
}

void RandomFile::readAt(std::uint64_t offset, char* dst, std::size_t n) const {
  const std::size_t got = readSome(offset, dst, n);
  if (got < n)
    throw InputError(path_ + ": short read at byte offset " + std::to_string(offset) +
                     ": expected " + std::to_string(n) + " bytes, got " + std::to_string(got));
}

std::uint64_t offsetAfterLines(const RandomFile& file, std::uint64_t start, std::uint64_t lines) {
  std::uint64_t pos = start, done = 0;
  std::vector<char> buffer(64 * 1024);
  bool afterCr = false;  // the last byte seen ended a line with '\r'
  while (done < lines) {
    const std::size_t got = file.readSome(pos, buffer.data(), buffer.size());
    if (got == 0) break;
    for (std::size_t i = 0; i < got && done < lines; ++i) {
      const char c = buffer[i];
      ++pos;
      if (c == '\n' && afterCr) {  // the rest of a "\r\n" line end
        afterCr = false;
        continue;
      }
      afterCr = c == '\r';
      if (c == '\n' || c == '\r') ++done;
    }
  }
  if (done < lines)
    throw InputError(file.path() + ": expected " + std::to_string(lines) + " lines to skip, got " +
                     std::to_string(done));
  // A "\r\n" line end: the '\n' belongs to the last line.
  if (afterCr) {
    char next = 0;
    if (file.readSome(pos, &next, 1) == 1 && next == '\n') ++pos;
  }
  return pos;
}

GzipStream::GzipStream(std::string path, std::uint64_t compressedOffset)
    : file_(std::move(path)),
      inflate_([this](std::uint64_t offset, char* dst,
                      std::size_t n) { return file_.readSome(offset, dst, n); },
               compressedOffset) {}

GzipStream::~GzipStream() = default;

void GzipStream::rewind() {
  inflate_.rewind();
}

std::size_t GzipStream::read(char* dst, std::size_t n) {
  try {
    return inflate_.read(dst, n);
  } catch (const base::GzipError& e) {
    throw InputError(file_.path() + ": " + e.what());
  }
}

std::uint64_t GzipStream::skip(std::uint64_t n) {
  try {
    return inflate_.skip(n);
  } catch (const base::GzipError& e) {
    throw InputError(file_.path() + ": " + e.what());
  }
}

std::string resolveBeside(const std::string& headerPath, const std::string& relative) {
  const std::filesystem::path rel(relative);
  if (rel.is_absolute() || rel.has_root_path())
    throw InputError(headerPath + ": data file '" + relative +
                     "' is an absolute path; only files beside the header are read");
  for (const auto& part : rel)
    if (part == "..")
      throw InputError(headerPath + ": data file '" + relative +
                       "' leaves the header's folder ('..'); only files beside the header are "
                       "read");
  std::filesystem::path dir = std::filesystem::path(headerPath).parent_path();
  if (dir.empty()) dir = ".";
  return (dir / rel).string();
}

}  // namespace gs::formats::detail
