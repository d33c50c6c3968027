// Whole local files into memory (worlds, meshes, volumes, textures, .qnv files read at
// once; streamed reading is net::startTransfer's).
#pragma once

#include <cstddef>
#include <string>

namespace gs::base {

/// Reads the file at the local path `path` into `bytes`. Returns false with a message
/// naming the path and the reason in `error`: "cannot open 'x.wrl': No such file or
/// directory", "'x' is larger than the limit of N bytes", "cannot read 'x': ...". Never
/// holds more than `maxBytes` bytes (`bytes` is empty after a failure).
bool readFile(const std::string& path, std::string& bytes, std::string& error,
              std::size_t maxBytes = std::size_t{1} << 31);

}  // namespace gs::base
