// Private to qnv/: the step shared by the out-of-core selections of volumes
// (volume_tileset.cpp) and meshes (surface_tileset.cpp), which find the exact kept-vectors
// threshold from a coarse and a fine magnitude histogram (docs/out-of-core.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "qnv/error.hpp"

namespace gs::qnv::detail {

/// The bin (from the top) where the running count from the largest reaches `need`, and
/// the count strictly above it. Throws InputError (an internal error naming `what`, e.g.
/// "magnitude histogram holds fewer vectors") when the bins hold fewer than `need`.
inline std::pair<std::size_t, std::uint64_t> histogramCrossing(
    const std::vector<std::uint64_t>& bins, std::uint64_t need, const char* what) {
  std::uint64_t above = 0;
  for (std::size_t b = bins.size(); b-- > 0;) {
    if (above + bins[b] >= need) return {b, above};
    above += bins[b];
  }
  throw InputError(std::string("internal error: the ") + what + " than counted");
}

}  // namespace gs::qnv::detail
