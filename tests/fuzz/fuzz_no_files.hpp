// The fetcher of the fuzz targets that parse worlds (docs/fuzzing.md).
#pragma once

#include "base/fetch.hpp"

#include <string>

namespace gs::fuzz {

/// The fetcher of every fuzz target's parse: it reads nothing (a fuzz input naming
/// "/dev/zero" or a local file must not reach the file system).
inline base::Fetcher* noFiles() {
  static base::CallbackFetcher none([](const std::string&, const std::string&, base::FetchMode) {
    return base::fetchFailed("no files while fuzzing");
  });
  return &none;
}

}  // namespace gs::fuzz
