// Records of a fixed number of 32-bit words by a 64-bit key, held in a bounded buffer and
// spilled to a file past it, then taken back key by key in ascending order: the buckets of
// the out-of-core Gaussian tileset encode (encode/src/ooc_gaussian.cpp; docs/out-of-core.md,
// "Gaussian splatting scenes"). Private to encode/src.
#pragma once

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "ooc_share.hpp"

namespace gs::encode {

/// A spill file that could not be written or read back (a full disk, a damaged file): the
/// encode's write failure, not its input's.
struct SpillFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Records appended into one buffer of a fixed size (the bound), allocated once, so the
/// memory held is the bound whatever the keys (a vector per key fragmented glibc's heap
/// to 9 times it). When the buffer is full its records are written to the spill file as
/// one spill: runs in ascending key, each a header of 4 words (key low and high, record
/// count low and high) and then its records in the order they came. Keys are taken back
/// in ascending order, each spill read front to back through a cursor of its own, so what
/// is held beside the buffer is a cursor a spill and the set of keys spilled: it does not
/// grow with the spills times the keys (the thirtieth session's index of runs did: about
/// 400 MB for a 100 M-splat capture under `--memory 64`).
class SpillBuckets {
 public:
  /// At most `bound` bytes held, for at most `most` records of `words` words in all; the
  /// spill file at `spill` is made at the first spill and removed with this.
  SpillBuckets(const std::filesystem::path& spill, std::uint64_t bound, std::size_t words,
               std::uint64_t most)
      : spill_(spill),
        words_(words),
        capacity_(static_cast<std::size_t>(std::clamp<std::uint64_t>(
            bound / (4 * words + sizeof(Held)), 1, std::max<std::uint64_t>(most, 1)))) {}

  /// Adds the `count` records at `records` (count x words words) under `key`. Throws
  /// SpillFailure when a spill is not written.
  void add(std::uint64_t key, const std::uint32_t* records, std::size_t count) {
    for (std::size_t r = 0; r < count; ++r) {
      if (keys_.size() == capacity_) spill();
      if (arena_.empty()) {  // once: the buffer and its keys, then reused
        arena_.reserve(capacity_ * words_);
        keys_.reserve(capacity_);
      }
      keys_.push_back({key, static_cast<std::uint32_t>(keys_.size())});
      arena_.insert(arena_.end(), records + r * words_, records + (r + 1) * words_);
    }
  }

  /// Every key with records, ascending; ends the adding (what is held is sorted by key).
  std::vector<std::uint64_t> keys() {
    std::stable_sort(keys_.begin(), keys_.end(), byKey);
    std::vector<std::uint64_t> out = spilledKeys_;
    for (const Held& h : keys_) out.push_back(h.key);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  /// Key's records, after keys(): those spilled first, in the order they came, then those
  /// held. Keys are taken in ascending order (a key skipped is passed over unread);
  /// std::logic_error for a key not above the last taken; SpillFailure when a spill cannot
  /// be read back or its runs do not fit it.
  std::vector<std::uint32_t> take(std::uint64_t key) {
    if (taken_ && key <= lastTaken_)
      throw std::logic_error("SpillBuckets: keys are taken in ascending order");
    taken_ = true;
    lastTaken_ = key;
    std::vector<std::uint32_t> out;
    try {
      for (Spill& s : spills_) readRun(s, key, out);
    } catch (const qnv::InputError& e) {
      throw SpillFailure(e.what());
    }
    auto h = std::lower_bound(keys_.begin(), keys_.end(), Held{key, 0}, byKey);
    for (; h != keys_.end() && h->key == key; ++h)
      out.insert(out.end(), arena_.begin() + static_cast<std::ptrdiff_t>(h->at * words_),
                 arena_.begin() + static_cast<std::ptrdiff_t>((h->at + 1) * words_));
    return out;
  }

  std::uint64_t spilledBytes() const { return spill_.size(); }
  std::size_t spills() const { return spills_.size(); }

 private:
  struct Held {
    std::uint64_t key;
    std::uint32_t at;  // record index in arena_
  };
  static bool byKey(const Held& a, const Held& b) { return a.key < b.key; }
  static constexpr std::size_t kRunHeaderWords = 4;

  // One spill's bytes [next, end) still to read; the header at `next` when peeked.
  struct Spill {
    std::uint64_t next = 0, end = 0;
    bool peeked = false;
    std::uint64_t key = 0, count = 0;
  };

  // Appends spill `s`'s run of `key`, if it has one, to `out`, passing runs of smaller keys.
  // A run's data is read with the next run's header behind it (one read a run).
  void readRun(Spill& s, std::uint64_t key, std::vector<std::uint32_t>& out) {
    const std::uint64_t runHeaderBytes = 4 * kRunHeaderWords;
    while (s.next < s.end) {
      if (!s.peeked) {
        std::uint32_t header[kRunHeaderWords];
        if (s.end - s.next < runHeaderBytes) damaged();
        spill_.read(s.next, header, sizeof header);
        peek(s, header);
      }
      if (s.key > key) return;
      const std::uint64_t bytes = s.count * words_ * 4;
      const std::uint64_t after = s.next + runHeaderBytes + bytes;  // the next run
      if (s.key == key) {
        const bool ahead = s.end - after >= runHeaderBytes;
        const std::size_t at = out.size();
        out.resize(at + s.count * words_ + (ahead ? kRunHeaderWords : 0));
        spill_.read(s.next + runHeaderBytes, out.data() + at, bytes + (ahead ? runHeaderBytes : 0));
        s.next = after;
        s.peeked = false;
        if (ahead) {
          std::uint32_t header[kRunHeaderWords];
          std::copy(out.end() - kRunHeaderWords, out.end(), header);
          out.resize(out.size() - kRunHeaderWords);
          peek(s, header);
        }
        return;  // one run a key in a spill
      }
      s.next = after;
      s.peeked = false;
    }
  }
  // Takes `header` as spill `s`'s next run's, checking that the run fits the spill.
  void peek(Spill& s, const std::uint32_t* header) {
    s.key = header[0] | std::uint64_t{header[1]} << 32;
    s.count = header[2] | std::uint64_t{header[3]} << 32;
    if (s.count == 0 || s.count > (s.end - s.next - 4 * kRunHeaderWords) / (4 * words_)) damaged();
    s.peeked = true;
  }
  [[noreturn]] void damaged() const {
    throw SpillFailure("a spill file of this encode is damaged (its runs do not fit it)");
  }

  // Writes what is held as one spill, sorted by key, through a 1 MiB buffer.
  void spill() {
    std::stable_sort(keys_.begin(), keys_.end(), byKey);
    std::vector<std::uint32_t> out;
    out.reserve(std::max<std::size_t>(words_ + kRunHeaderWords, (1u << 18) / words_ * words_));
    Spill s;
    s.next = spill_.size();
    const auto flush = [&] {
      try {
        if (!out.empty()) spill_.append(out.data(), out.size() * 4);
      } catch (const qnv::InputError& e) {
        throw SpillFailure(e.what());
      }
      out.clear();
    };
    std::vector<std::uint64_t> keys;
    for (std::size_t i = 0; i < keys_.size();) {
      std::size_t j = i;
      while (j < keys_.size() && keys_[j].key == keys_[i].key) ++j;
      const std::uint64_t key = keys_[i].key, count = j - i;
      if (out.size() + kRunHeaderWords > out.capacity()) flush();
      for (const std::uint64_t word : {key, count}) {
        out.push_back(static_cast<std::uint32_t>(word));
        out.push_back(static_cast<std::uint32_t>(word >> 32));
      }
      for (std::size_t k = i; k < j; ++k) {
        if (out.size() + words_ > out.capacity()) flush();
        const std::uint32_t* r = arena_.data() + std::size_t{keys_[k].at} * words_;
        out.insert(out.end(), r, r + words_);
      }
      keys.push_back(key);
      i = j;
    }
    flush();
    s.end = spill_.size();
    spills_.push_back(s);
    std::vector<std::uint64_t> merged;
    merged.reserve(spilledKeys_.size() + keys.size());
    std::set_union(spilledKeys_.begin(), spilledKeys_.end(), keys.begin(), keys.end(),
                   std::back_inserter(merged));
    spilledKeys_ = std::move(merged);
    keys_.clear();
    arena_.clear();
  }

  ooc::SpillFile spill_;
  std::size_t words_, capacity_;
  std::vector<std::uint32_t> arena_;
  std::vector<Held> keys_;
  std::vector<Spill> spills_;
  std::vector<std::uint64_t> spilledKeys_;  // ascending, distinct
  bool taken_ = false;
  std::uint64_t lastTaken_ = 0;
};

}  // namespace gs::encode
