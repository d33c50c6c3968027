// A remote scene read by columns, side by side (gaussian_columns_fetch.hpp).
#include "gaussian_columns_fetch.hpp"

#include <algorithm>
#include <limits>

namespace gs::session::detail {

namespace {

/// Records a column may hold and still be fetched first: four zstd blocks (128 KiB of
/// records each). zstd gives a block's records only once all its bytes came, so a column
/// of few blocks (an SPZ's alphas of up to 131,072 splats are one) fetched beside the
/// others at their pace would hold every splat back until the end.
constexpr std::uint64_t kEarlyRecordBytes = std::uint64_t{4} << 17;

}  // namespace

struct GaussianColumnsFetch::Column {
  std::unique_ptr<net::Transfer> transfer;  // null until started, or when the head held it
  net::FetchRequest request;                // its range, while it waits for its wave
  bool waiting = false;
  int wave = 0;  // 0: fetched first (a few zstd blocks), 1: once wave 0 came
  splats::ColumnRecords records;
  std::string bytes;            // taken from the transfer, not yet fed
  std::uint64_t taken = 0;      // bytes taken from the transfer
  std::string url;              // a side file's URL (empty: the scene's own file)
  std::uint64_t fileBytes = 0;  // its size as the scene states it
  Column(const splats::GaussianColumnDecoder::Column& c, std::uint64_t splats,
         const std::string& name, int index)
      : records(c, splats, name, index) {}
};

GaussianColumnsFetch::GaussianColumnsFetch(
    std::unique_ptr<splats::GaussianColumnDecoder> decoder, const net::FetchRequest& request,
    std::string_view head, std::uint64_t fileBytes, std::string name,
    const std::map<std::string, net::FetchRequest>& sideRequests)
    : decoder_(std::move(decoder)),
      name_(std::move(name)),
      headBytes_(head.size()),
      fileBytes_(fileBytes) {
  const auto& columns = decoder_->columns();
  bool early = false, late = false;
  for (std::size_t k = 0; k < columns.size(); ++k) {
    const auto& c = columns[k];
    auto column = std::make_unique<Column>(c, decoder_->size(), name_, static_cast<int>(k));
    // A column's bytes already in the head are fed; a range request fetches the rest.
    const std::uint64_t have = !c.file.empty() || c.offset >= head.size()
                                   ? 0
                                   : std::min<std::uint64_t>(c.bytes, head.size() - c.offset);
    if (have > 0)
      column->records.feed(
          head.substr(static_cast<std::size_t>(c.offset), static_cast<std::size_t>(have)));
    const bool unknownSize = c.bytes == 0 && c.webp && !c.file.empty();  // fetched whole
    if (have < c.bytes || unknownSize) {
      column->request = c.file.empty() ? request : sideRequests.at(c.file);
      if (!c.file.empty()) {
        column->url = column->request.url;
        column->fileBytes = c.fileBytes;
        sideBytes_ += c.bytes;
      }
      column->request.offset = c.offset + have;
      column->request.length = c.bytes - have;
      column->waiting = true;
      // (And a column needed whole before any splat: an SOG's SH centroids.)
      column->wave =
          c.whole || (c.zstd && decoder_->size() * c.recordBytes <= kEarlyRecordBytes) ? 0 : 1;
      (column->wave == 0 ? early : late) = true;
    }
    columns_.push_back(std::move(column));
  }
  // Both waves at once when one is empty.
  if (!early || !late)
    for (auto& c : columns_) c->wave = 0;
  start(0);
}

void GaussianColumnsFetch::start(int wave) {
  // An emulated link's rate is shared in proportion to the bytes each column of the wave
  // fetches, so that they all end together (and their splats come evenly).
  // Columns whose size is not known (an SOG's images) share it evenly.
  std::uint64_t toFetch = 0;
  std::size_t count = 0;
  bool unknown = false;
  for (const auto& c : columns_)
    if (c->waiting && c->wave == wave) {
      toFetch += c->request.length;
      unknown |= c->request.length == 0;
      ++count;
    }
  for (auto& c : columns_) {
    if (!c->waiting || c->wave != wave) continue;
    net::FetchRequest r = c->request;
    const double share = unknown ? 1.0 / static_cast<double>(count)
                                 : static_cast<double>(r.length) / static_cast<double>(toFetch);
    // (At least 4 KB/s: curl's pauses that hold a low rate must stay far below the stall
    // timeout; a column that small adds little to the link's rate.)
    if (r.maxRate > 0) r.maxRate = std::max(std::min(r.maxRate, 4096.0), r.maxRate * share);
    c->transfer = net::startTransfer(std::move(r));
    c->waiting = false;
  }
  wave_ = wave;
}

bool GaussianColumnsFetch::ended(const Column& c) {
  if (c.waiting) return false;
  if (!c.transfer) return true;
  // Ended, and every byte it delivered taken (a transfer may end between take() and here).
  const net::TransferStatus s = c.transfer->status();
  return s.finished() && s.received <= c.taken;
}

GaussianColumnsFetch::~GaussianColumnsFetch() {
  cancel();
}

bool GaussianColumnsFetch::rangesIgnored() const {
  return std::any_of(columns_.begin(), columns_.end(), [](const auto& c) {
    return c->transfer && c->transfer->status().rangeIgnored;
  });
}

void GaussianColumnsFetch::cancel() {
  for (auto& c : columns_)
    if (c->transfer) c->transfer->cancel();
}

bool GaussianColumnsFetch::take(const std::function<std::uint64_t(std::uint64_t)>& grant) {
  bool allowed = true;
  for (auto& c : columns_) {
    if (!c->transfer) continue;
    c->bytes.clear();
    const std::uint64_t got = c->transfer->take(c->bytes);
    c->taken += got;
    const std::uint64_t granted = got > 0 ? grant(got) : 0;
    if (granted < got) {
      c->bytes.resize(static_cast<std::size_t>(granted));
      allowed = false;
    }
    c->records.feed(c->bytes);
  }
  // The second wave once the first came whole (and did not fail: failure() says so).
  if (allowed && wave_ == 0 &&
      std::all_of(columns_.begin(), columns_.end(),
                  [](const auto& c) { return c->wave != 0 || ended(*c); }) &&
      failure().empty())
    start(1);
  return allowed;
}

std::size_t GaussianColumnsFetch::next(splats::GaussianCloud& batch, std::size_t max) {
  std::vector<splats::ColumnRecords*> records;
  for (auto& c : columns_) records.push_back(&c->records);
  const std::size_t n = splats::decodeColumns(*decoder_, records, decoded_, max, batch);
  decoded_ += n;
  return n;
}

bool GaussianColumnsFetch::finished() const {
  if (!failure().empty()) return true;
  return std::all_of(columns_.begin(), columns_.end(), [](const auto& c) { return ended(*c); });
}

std::string GaussianColumnsFetch::failure() const {
  for (const auto& c : columns_) {
    if (!c->transfer) continue;
    const net::TransferStatus s = c->transfer->status();
    if (s.finished() && s.state != net::TransferState::done)
      return s.error.empty() ? name_ + ": cancelled" : s.error;
    // A buffer file of another size than its byteLength: refused as the whole reader does.
    if (!c->url.empty() && c->fileBytes > 0 && s.resourceSize >= 0 &&
        static_cast<std::uint64_t>(s.resourceSize) != c->fileBytes)
      return name_ + ": " + c->url + ": expected " + std::to_string(c->fileBytes) + " bytes, got " +
             std::to_string(s.resourceSize);
  }
  return {};
}

void GaussianColumnsFetch::finish() {
  for (auto& c : columns_) c->records.finish();
}

net::TransferStatus GaussianColumnsFetch::status() const {
  net::TransferStatus t;
  t.received = headBytes_;
  t.resourceSize = static_cast<std::int64_t>(fileBytes_ + sideBytes_);
  bool running = false;
  for (const auto& c : columns_) {
    if (!c->transfer) continue;
    const net::TransferStatus s = c->transfer->status();
    t.received += s.received;
    // A side file of unknown size counts once its size is known (or by what came).
    if (c->request.length == 0 && !c->url.empty())
      t.resourceSize +=
          std::max<std::int64_t>(s.resourceSize, static_cast<std::int64_t>(s.received));
    t.bytesPerSecond += s.state == net::TransferState::running ? s.bytesPerSecond : 0.0;
    running |= !s.finished();
  }
  t.expected = t.resourceSize;
  t.state = running ? net::TransferState::running : net::TransferState::done;
  return t;
}

}  // namespace gs::session::detail
