// Sources of bytes. This first version reads local files whole; HTTP and incremental
// delivery arrive with the progressive-loading issue.
#pragma once

#include <cstddef>
#include <string>

namespace gs::net {

/// Reads the file at `path` into `bytes`. Returns false with a message naming the path
/// and the reason ("cannot open 'x.wrl': No such file or directory", "'x' is larger than
/// the limit of N bytes") in `error`. Never reads more than `maxBytes` bytes.
bool readFile(const std::string& path, std::string& bytes, std::string& error,
              std::size_t maxBytes = std::size_t{1} << 31);

}  // namespace gs::net
