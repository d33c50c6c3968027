#include "ordering.hpp"

#include <algorithm>
#include <utility>
#include <vector>

#include "morton.hpp"
#include "qnv/encoder.hpp"
#include "qnv/record.hpp"

namespace gs::qnv {

std::uint64_t Selection::keepOf(std::uint64_t elements) const {
  if (count > 0) return std::min(count, elements);
  if (!(fraction > 0.0)) return 0;
  if (fraction >= 1.0) return elements;
  return std::min<std::uint64_t>(
      elements, static_cast<std::uint64_t>(static_cast<double>(elements) * fraction + 0.5));
}

void coarsenMagnitudes(std::span<std::uint64_t> records, int bits) {
  if (bits >= kMagnitudeBits) return;
  roundMagnitudes(records, bits);
  // Largest code first, then Morton order; the records are sorted by code already, so this
  // only reorders each run of equal codes.
  std::vector<std::pair<std::uint64_t, std::uint64_t>> keyed(records.size());
  for (std::size_t i = 0; i < records.size(); ++i)
    keyed[i] = {(std::uint64_t{kMagnitudeSteps - 1 - magnitudeCode(records[i])} << 30) |
                    detail::recordMorton(records[i]),
                records[i]};
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < records.size(); ++i) records[i] = keyed[i].second;
}

namespace detail {

void keepLargest(std::vector<Candidate>& candidates, std::uint64_t keep) {
  if (keep >= candidates.size()) return;
  auto larger = [](const Candidate& a, const Candidate& b) {
    return a.magnitude > b.magnitude || (a.magnitude == b.magnitude && a.index < b.index);
  };
  std::nth_element(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep),
                   candidates.end(), larger);
  candidates.resize(keep);
}

void sortLargestFirst(std::vector<std::uint64_t>& records) {
  std::vector<std::size_t> start(kMagnitudeSteps + 1, 0);
  for (std::uint64_t r : records) ++start[kMagnitudeSteps - 1 - magnitudeCode(r) + 1];
  for (std::size_t i = 1; i <= kMagnitudeSteps; ++i) start[i] += start[i - 1];
  std::vector<std::uint64_t> sorted(records.size());
  for (std::uint64_t r : records) sorted[start[kMagnitudeSteps - 1 - magnitudeCode(r)]++] = r;
  records.swap(sorted);
}

}  // namespace detail
}  // namespace gs::qnv
