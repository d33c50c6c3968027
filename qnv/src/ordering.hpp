// Selection of the largest vectors and the largest-first stream order (paper section 2:
// "vectors sorted by magnitude"), private to qnv/src.
#pragma once

#include <cstdint>
#include <vector>

#include "qnv/encoder.hpp"

namespace gs::qnv::detail {

/// An element that may become a vector: its exact magnitude and its source index.
struct Candidate {
  float magnitude;
  std::uint32_t index;
};

/// Keeps the `keep` largest candidates (ties broken by lower index, so the result is
/// deterministic), in no particular order. O(n).
void keepLargest(std::vector<Candidate>& candidates, std::uint64_t keep);

/// Reorders packed records by A code, largest first; records with equal codes keep their
/// relative order (a stable counting sort, O(n)).
void sortLargestFirst(std::vector<std::uint64_t>& records);

/// The stream of `selected`: each vector quantized with its header (quantizeVector), the
/// records then sorted largest first. What encodeSurface and encodeVolume write.
EncodedVectors quantizeLargestFirst(const SelectedVectors& selected);

}  // namespace gs::qnv::detail
