#include <algorithm>
#include <unordered_map>

#include "qnv/encoder.hpp"

namespace gs::qnv {

namespace {

std::uint32_t key(const Rgba8& c) {
  return std::uint32_t{c.r} | (std::uint32_t{c.g} << 8) | (std::uint32_t{c.b} << 16) |
         (std::uint32_t{c.a} << 24);
}

struct Entry {
  Rgba8 color;
  std::uint64_t weight;
};

// One median-cut box: entries [begin, end) of the distinct-colour list.
struct Box {
  std::size_t begin, end;
  int channel;  // widest channel
  int range;
};

Box makeBox(const std::vector<Entry>& entries, std::size_t begin, std::size_t end) {
  Box box{begin, end, 0, -1};
  for (int ch = 0; ch < 4; ++ch) {
    int lo = 255, hi = 0;
    for (std::size_t i = begin; i < end; ++i) {
      lo = std::min<int>(lo, entries[i].color[ch]);
      hi = std::max<int>(hi, entries[i].color[ch]);
    }
    if (hi - lo > box.range) {
      box.range = hi - lo;
      box.channel = ch;
    }
  }
  return box;
}

}  // namespace

std::uint32_t paletteKey(const Rgba8& color) {
  return key(color);
}

CountedPalette buildPaletteFromCounts(std::vector<std::pair<std::uint32_t, std::uint64_t>> counts) {
  CountedPalette out;
  std::array<Rgba8, kPaletteSize>& palette = out.palette;
  palette.fill(Rgba8{0, 0, 0, 255});
  std::vector<Entry> entries;
  entries.reserve(counts.size());
  for (const auto& [k, n] : counts)
    entries.push_back({Rgba8(k & 255u, (k >> 8) & 255u, (k >> 16) & 255u, k >> 24), n});
  counts = {};
  std::sort(entries.begin(), entries.end(),
            [](const Entry& a, const Entry& b) { return key(a.color) < key(b.color); });

  std::vector<Box> boxes;
  if (!entries.empty()) boxes.push_back(makeBox(entries, 0, entries.size()));
  while (boxes.size() < kPaletteSize && entries.size() > kPaletteSize) {
    auto widest = std::max_element(boxes.begin(), boxes.end(),
                                   [](const Box& a, const Box& b) { return a.range < b.range; });
    if (widest->range <= 0) break;
    const Box box = *widest;
    auto first = entries.begin() + static_cast<std::ptrdiff_t>(box.begin);
    auto last = entries.begin() + static_cast<std::ptrdiff_t>(box.end);
    std::sort(first, last, [&](const Entry& a, const Entry& b) {
      return a.color[box.channel] < b.color[box.channel] ||
             (a.color[box.channel] == b.color[box.channel] && key(a.color) < key(b.color));
    });
    std::uint64_t total = 0, running = 0;
    for (auto it = first; it != last; ++it) total += it->weight;
    std::size_t split = box.begin + 1;
    for (std::size_t i = box.begin; i + 1 < box.end; ++i) {
      running += entries[i].weight;
      split = i + 1;
      if (2 * running >= total) break;
    }
    *widest = makeBox(entries, box.begin, split);
    boxes.push_back(makeBox(entries, split, box.end));
  }
  if (entries.size() <= kPaletteSize) {
    boxes.clear();
    for (std::size_t i = 0; i < entries.size(); ++i) boxes.push_back({i, i + 1, 0, 0});
  }

  for (std::size_t b = 0; b < boxes.size(); ++b) {
    double sum[4] = {0, 0, 0, 0}, weight = 0;
    for (std::size_t i = boxes[b].begin; i < boxes[b].end; ++i) {
      for (int ch = 0; ch < 4; ++ch)
        sum[ch] +=
            static_cast<double>(entries[i].color[ch]) * static_cast<double>(entries[i].weight);
      weight += static_cast<double>(entries[i].weight);
      out.keys.push_back(key(entries[i].color));
      out.indices.push_back(static_cast<std::uint8_t>(b));
    }
    for (int ch = 0; ch < 4; ++ch)
      palette[b][ch] = static_cast<std::uint8_t>(std::clamp(sum[ch] / weight + 0.5, 0.0, 255.0));
  }
  entries = {};
  // Keys in order, for indexOf's binary search.
  std::vector<std::uint32_t> order(out.keys.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return out.keys[a] < out.keys[b]; });
  std::vector<std::uint32_t> keys(order.size());
  std::vector<std::uint8_t> indices(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    keys[i] = out.keys[order[i]];
    indices[i] = out.indices[order[i]];
  }
  out.keys = std::move(keys);
  out.indices = std::move(indices);
  return out;
}

std::uint8_t CountedPalette::indexOf(const Rgba8& color) const {
  const std::uint32_t k = key(color);
  const auto it = std::lower_bound(keys.begin(), keys.end(), k);
  return it != keys.end() && *it == k ? indices[static_cast<std::size_t>(it - keys.begin())] : 0;
}

std::array<Rgba8, kPaletteSize> buildPalette(std::span<const Rgba8> colors,
                                             std::vector<std::uint8_t>& indices) {
  std::unordered_map<std::uint32_t, std::uint64_t> counts;
  for (const Rgba8& c : colors) ++counts[key(c)];
  const CountedPalette palette = buildPaletteFromCounts({counts.begin(), counts.end()});
  counts = {};
  std::unordered_map<std::uint32_t, std::uint8_t> indexOf;
  for (std::size_t i = 0; i < palette.keys.size(); ++i)
    indexOf[palette.keys[i]] = palette.indices[i];
  indices.resize(colors.size());
  for (std::size_t i = 0; i < colors.size(); ++i) indices[i] = indexOf[key(colors[i])];
  return palette.palette;
}

std::array<Rgba8, kPaletteSize> defaultTransferFunction() {
  std::array<Rgba8, kPaletteSize> palette;
  for (std::uint32_t c = 0; c < kPaletteSize; ++c) {
    const double t = c / 255.0;
    auto channel = [&](double from) {
      return static_cast<std::uint8_t>(255.0 * (from + (1.0 - from) * t) + 0.5);
    };
    palette[c] = Rgba8(channel(0.55), channel(0.25), channel(0.2), static_cast<std::uint8_t>(c));
  }
  return palette;
}

}  // namespace gs::qnv
