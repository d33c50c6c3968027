#include "base/file.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

namespace gs::base {

bool readFile(const std::string& path, std::string& bytes, std::string& error,
              std::size_t maxBytes) {
  bytes.clear();
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return false;
  }
  char buf[1 << 16];
  for (;;) {
    const std::size_t n = std::fread(buf, 1, sizeof buf, f.get());
    if (n == 0) break;
    if (bytes.size() + n > maxBytes) {
      error = "'" + path + "' is larger than the limit of " + std::to_string(maxBytes) + " bytes";
      bytes.clear();
      return false;
    }
    bytes.append(buf, n);
  }
  if (std::ferror(f.get())) {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    bytes.clear();
    return false;
  }
  return true;
}

}  // namespace gs::base
