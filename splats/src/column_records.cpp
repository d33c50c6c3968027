// One column of a scene read by columns (readers.hpp, ColumnRecords): its bytes, as they
// arrive, decompressed forward into records.
#include <zstd.h>

#include <algorithm>
#include <bit>
#include <memory>
#include <string>

#include "reader_support.hpp"
#include "splats/readers.hpp"

namespace gs::splats {

struct ColumnRecords::Zstd {
  struct Free {
    void operator()(ZSTD_DStream* s) const { ZSTD_freeDStream(s); }
  };
  std::unique_ptr<ZSTD_DStream, Free> stream{ZSTD_createDStream()};
};

ColumnRecords::ColumnRecords(const GaussianColumnDecoder::Column& column, std::uint64_t splats,
                             std::string name, int index)
    : column_(column),
      splats_(splats),
      name_(std::move(name)),
      index_(index),
      recordBytes_(std::max<std::size_t>(column.recordBytes, 1)) {
  if (!column.zstd) return;
  zstd_ = std::make_unique<Zstd>();
  if (!zstd_->stream) detail::fail(name_, "zstd: out of memory");
  ZSTD_initDStream(zstd_->stream.get());
  // As the piecewise reader's streams (spz.cpp, ZstdBlock): no larger window than the
  // column could use (at least 8 MiB, at most 128 MiB, zstd's own limit), so that a small
  // hostile file cannot make each column take 128 MiB.
  const std::uint64_t whole = splats * recordBytes_;
  const int windowLog = std::clamp(static_cast<int>(std::bit_width(whole)) + 1, 23, 27);
  ZSTD_DCtx_setParameter(zstd_->stream.get(), ZSTD_d_windowLogMax, windowLog);
}

ColumnRecords::~ColumnRecords() = default;

void ColumnRecords::feed(std::string_view bytes) {
  if (bytes.size() > column_.bytes - fed_)
    detail::fail(name_, "column " + std::to_string(index_) + ": more than its " +
                            std::to_string(column_.bytes) + " bytes arrived");
  fed_ += bytes.size();
  pending_.append(bytes);
}

void ColumnRecords::decodeUpTo(std::uint64_t record) {
  const std::uint64_t whole = splats_ * recordBytes_;
  const std::uint64_t want = std::min(record, splats_) * recordBytes_;
  if (!zstd_) {  // raw records: the bytes fed are the records
    if (produced_ + pending_.size() > whole)
      detail::fail(name_, "column " + std::to_string(index_) + " holds more than " +
                              std::to_string(splats_) + " records");
    records_.append(pending_);
    produced_ += pending_.size();
    pending_.clear();
    return;
  }
  std::size_t used = 0;
  bool filled = false;  // the last call filled its output: zstd may hold more for it
  while (produced_ < want && (used < pending_.size() || filled)) {
    constexpr std::size_t kChunk = std::size_t{1} << 18;
    const std::size_t grow =
        static_cast<std::size_t>(std::min<std::uint64_t>(kChunk, whole - produced_ + 1));
    const std::size_t old = records_.size();
    records_.resize(old + grow);
    ZSTD_outBuffer out{records_.data() + old, grow, 0};
    ZSTD_inBuffer in{pending_.data(), pending_.size(), used};
    const std::size_t rc = ZSTD_decompressStream(zstd_->stream.get(), &out, &in);
    records_.resize(old + out.pos);
    used = in.pos;
    if (ZSTD_isError(rc))
      detail::fail(name_, "stream " + std::to_string(index_) + ": zstd: " + ZSTD_getErrorName(rc));
    hint_ = rc;
    produced_ += out.pos;
    filled = out.pos == grow;
    if (produced_ > whole)
      detail::fail(name_, "stream " + std::to_string(index_) + " decompresses to more than " +
                              std::to_string(whole) + " bytes");
    if (out.pos == 0 && in.pos == in.size) break;
  }
  pending_.erase(0, used);
}

void ColumnRecords::drop(std::uint64_t n) {
  n = std::min(n, available());
  records_.erase(0, static_cast<std::size_t>(n * recordBytes_));
  first_ += n;
}

void ColumnRecords::finish() {
  const std::uint64_t whole = splats_ * recordBytes_;
  // The rest decoded 65,536 records at a time and dropped: nothing needs them now (a
  // column that ended short must not make the others hold all theirs).
  while (true) {
    const std::uint64_t before = produced_;
    decodeUpTo(first_ + available() + 65536);
    drop(available());
    if (produced_ == before || produced_ == whole) break;
  }
  const std::string which = (zstd_ ? "stream " : "column ") + std::to_string(index_);
  if (!fed())
    detail::fail(name_, which + ": expected " + std::to_string(column_.bytes) +
                            " bytes in the file, got " + std::to_string(fed_));
  // Its bytes all used and the frame still open: cut short, as the whole-file reader says.
  if (zstd_ && produced_ < whole && hint_ != 0 && pending_.empty())
    detail::fail(name_, which + ": truncated zstd data");
  if (zstd_ && produced_ == whole) {
    // The rest of its bytes, as the whole-file reader decompresses them: not a byte more
    // than its records, the last frame complete.
    std::size_t used = 0;
    while (used < pending_.size()) {
      char extra = 0;
      ZSTD_outBuffer out{&extra, 1, 0};
      ZSTD_inBuffer in{pending_.data(), pending_.size(), used};
      hint_ = ZSTD_decompressStream(zstd_->stream.get(), &out, &in);
      if (ZSTD_isError(hint_)) detail::fail(name_, which + ": zstd: " + ZSTD_getErrorName(hint_));
      const bool stuck = in.pos == used && out.pos == 0;
      used = in.pos;
      if (out.pos > 0)
        detail::fail(name_,
                     which + " decompresses to more than " + std::to_string(whole) + " bytes");
      if (in.pos == in.size || stuck) break;
    }
    pending_.clear();
    if (hint_ != 0) detail::fail(name_, which + ": truncated zstd data");
  }
  if (produced_ != whole)
    detail::fail(name_, which + ": expected " + std::to_string(whole) + " bytes, got " +
                            std::to_string(produced_));
}

}  // namespace gs::splats
