// One column of a scene read by columns (readers.hpp, ColumnRecords): its bytes, as they
// arrive, decompressed forward into records.
#include <webp/decode.h>
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

struct ColumnRecords::Webp {
  struct Free {
    void operator()(WebPIDecoder* d) const { WebPIDelete(d); }
  };
  std::unique_ptr<WebPIDecoder, Free> decoder;
  std::uint64_t rowsCopied = 0;  // rows of the picture whose texels went to records_
};

namespace {

/// The most bytes of a WebP image of unknown size (as the whole reader's, sog.cpp).
constexpr std::uint64_t kMaxWebpBytes = std::uint64_t{1} << 30;

}  // namespace

ColumnRecords::ColumnRecords(const GaussianColumnDecoder::Column& column, std::uint64_t splats,
                             std::string name, int index)
    : column_(column),
      splats_(splats),
      name_(std::move(name)),
      index_(index),
      recordBytes_(std::max<std::size_t>(column.recordBytes, 1)) {
  if (column.webp) {
    recordBytes_ = 4;
    webp_ = std::make_unique<Webp>();
    return;
  }
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

std::string ColumnRecords::webpName() const {
  return "'" + (column_.file.empty() ? "column " + std::to_string(index_) : column_.file) + "'";
}

void ColumnRecords::feed(std::string_view bytes) {
  if (webp_ && column_.bytes == 0) {  // a side file of unknown size
    if (bytes.size() > kMaxWebpBytes - fed_)
      detail::fail(name_, webpName() + " is larger than 1 GiB");
  } else if (bytes.size() > column_.bytes - fed_) {
    detail::fail(name_, "column " + std::to_string(index_) + ": more than its " +
                            std::to_string(column_.bytes) + " bytes arrived");
  }
  fed_ += bytes.size();
  pending_.append(bytes);
}

void ColumnRecords::decodeWebp(bool last) {
  if (complete_ || (pending_.empty() && !last)) return;
  if (!webp_->decoder) {
    // The header first (WebPGetInfo, as the whole reader): its size bounded before the
    // decoder allocates the picture.
    const auto* data = reinterpret_cast<const std::uint8_t*>(pending_.data());
    if (!WebPGetInfo(data, pending_.size(), &width_, &height_) || width_ <= 0 || height_ <= 0) {
      // Not enough of a header yet (a VP8X's extended header is 30 bytes), or none.
      if (pending_.size() < 64 && !last) return;
      detail::fail(name_, webpName() + " is not a WebP image");
    }
    const std::uint64_t texels =
        static_cast<std::uint64_t>(width_) * static_cast<std::uint64_t>(height_);
    if (column_.maxTexels > 0 && texels > column_.maxTexels)
      detail::fail(name_, webpName() + " is " + std::to_string(width_) + "x" +
                              std::to_string(height_) + ", more than the " +
                              std::to_string(column_.maxTexels) + " pixels the scene needs");
    if (column_.whole && column_.width != 0 && static_cast<std::uint32_t>(width_) != column_.width)
      detail::fail(name_, "expected " + webpName() + " " + std::to_string(column_.width) +
                              " texels wide, got " + std::to_string(width_));
    webp_->decoder.reset(WebPINewRGB(MODE_RGBA, nullptr, 0, 0));
    if (!webp_->decoder) detail::fail(name_, webpName() + ": out of memory");
  }
  if (pending_.empty()) return;
  const VP8StatusCode status =
      WebPIAppend(webp_->decoder.get(), reinterpret_cast<const std::uint8_t*>(pending_.data()),
                  pending_.size());
  pending_.clear();
  if (status != VP8_STATUS_OK && status != VP8_STATUS_SUSPENDED)
    detail::fail(name_, webpName() + ": damaged WebP data");
  int rows = 0, width = 0, height = 0, stride = 0;
  const std::uint8_t* rgba = WebPIDecGetRGB(webp_->decoder.get(), &rows, &width, &height, &stride);
  if (!rgba || rows <= 0) return;
  if (width != width_ || height != height_) detail::fail(name_, webpName() + ": damaged WebP data");
  // The rows decoded since, their texels up to the splats' (all of a whole column's).
  const auto w = static_cast<std::uint64_t>(width_);
  const std::uint64_t limit = column_.whole ? w * static_cast<std::uint64_t>(height_) : splats_;
  for (auto y = webp_->rowsCopied; y < static_cast<std::uint64_t>(rows); ++y) {
    const std::uint64_t from = y * w, to = std::min(from + w, limit);
    if (from < to)
      records_.append(reinterpret_cast<const char*>(rgba + y * static_cast<std::uint64_t>(stride)),
                      static_cast<std::size_t>((to - from) * 4));
    produced_ += from < to ? (to - from) * 4 : 0;
  }
  webp_->rowsCopied = static_cast<std::uint64_t>(rows);
  if (status == VP8_STATUS_OK) {
    complete_ = true;
    webp_->decoder.reset();  // the picture's memory goes: its texels were copied
  }
}

void ColumnRecords::decodeUpTo(std::uint64_t record) {
  if (webp_) {
    decodeWebp(false);
    return;
  }
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
  if (webp_) {
    const std::string file = webpName();
    if (column_.bytes != 0 && fed_ != column_.bytes)
      detail::fail(name_, file + ": expected " + std::to_string(column_.bytes) +
                              " bytes in the file, got " + std::to_string(fed_));
    decodeWebp(true);
    if (!complete_) detail::fail(name_, file + ": damaged WebP data");
    if (!column_.whole && produced_ < splats_ * 4)
      detail::fail(name_, file + " holds " +
                              std::to_string(static_cast<std::uint64_t>(width_) *
                                             static_cast<std::uint64_t>(height_)) +
                              " texels for " + std::to_string(splats_) + " splats");
    return;
  }
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

std::size_t decodeColumns(GaussianColumnDecoder& decoder,
                          const std::vector<ColumnRecords*>& columns, std::uint64_t decoded,
                          std::size_t max, GaussianCloud& batch) {
  const auto& specs = decoder.columns();
  if (specs.size() != columns.size())
    throw FormatError("expected " + std::to_string(specs.size()) + " columns, got " +
                      std::to_string(columns.size()));
  const std::uint64_t target = decoded + std::min<std::uint64_t>(max, decoder.size() - decoded);
  std::uint64_t ready = target;
  bool wholeMissing = false;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    ColumnRecords& c = *columns[k];
    c.decodeUpTo(target);
    if (specs[k].whole) {
      if (c.handOver()) decoder.takeWhole(k, c.texels(), c.imageWidth(), c.imageHeight());
      wholeMissing |= !c.complete();
    } else {
      ready = std::min(ready, c.first() + c.available());
    }
  }
  if (wholeMissing || ready <= decoded) return 0;
  const auto n = static_cast<std::size_t>(ready - decoded);
  std::vector<const char*> at;
  for (std::size_t k = 0; k < columns.size(); ++k)
    at.push_back(specs[k].whole ? nullptr : columns[k]->data());
  decoder.decode(at, decoded, n, batch);
  for (std::size_t k = 0; k < columns.size(); ++k)
    if (!specs[k].whole) columns[k]->drop(n);
  return n;
}

}  // namespace gs::splats
