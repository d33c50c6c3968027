// A Gaussian splatting scene read in the background and drawn while it arrives
// (gaussian_scene_load.hpp).
#include "gaussian_scene_load.hpp"

#include <algorithm>
#include <chrono>
#include <deque>
#include <limits>
#include <map>
#include <mutex>
#include <new>
#include <thread>

#include "base/fetch.hpp"
#include "base/file.hpp"
#include "base/url.hpp"
#include "net/transfer.hpp"
#include "session/splat_inputs.hpp"

namespace gs::session::detail {

struct GaussianSceneLoad::Pipe {
  std::mutex mutex;
  std::deque<splats::GaussianCloud> batches;           // read, not yet taken
  std::uint64_t total = 0;                             // the scene's splats, once known
  std::shared_ptr<const splats::GaussianCloud> whole;  // a scene read whole, sorted
  std::string error;
  bool ended = false;
  std::atomic<bool> cancelled{false};
};

namespace {

/// Splats a local scene is read by at a time, and the most rows of a remote one decoded
/// in one pump (about 25 ms of a frame at 5 M rows a second).
constexpr std::size_t kBatchSplats = 65536;
constexpr std::size_t kRowsPerPump = 131072;
/// Compressed bytes of a scene read as one stream (SPZ v2/v3) inflated in one pump, fed
/// kStreamSlice at a time until about kStreamOutputPerPump came out (a few ms of zlib's
/// time: 300 MB/s of output and more).
constexpr std::size_t kStreamBytesPerPump = std::size_t{1} << 20;
constexpr std::size_t kStreamSlice = std::size_t{16} << 10;
constexpr std::uint64_t kStreamOutputPerPump = std::uint64_t{32} << 20;

/// The scene in `bytes` read (splats::readGaussians) and sorted by importance; never throws.
std::shared_ptr<const splats::GaussianCloud> decodeScene(std::string bytes, const std::string& name,
                                                         const splats::SideFileReader& sideFiles,
                                                         std::string& error) {
  try {
    splats::GaussianCloud cloud = splats::readGaussians(bytes, name, sideFiles);
    std::string().swap(bytes);  // the file's bytes go before the sorted copy is made
    return std::make_shared<const splats::GaussianCloud>(splats::sortByImportance(cloud));
  } catch (const splats::FormatError& e) {
    error = e.what();
  } catch (const std::bad_alloc&) {
    error = name + ": out of memory";
  } catch (const std::exception& e) {  // a library's own (zlib that cannot start, ...)
    error = name + ": " + e.what();
  }
  return nullptr;
}

/// `job` run on a detached thread of its own, its result in the future returned: a
/// session closed while a large scene is still being read does not wait for it (the job
/// holds only its own copies and shared pointers).
template <typename Job>
auto detached(Job job) {
  using Result = decltype(job());
  std::promise<Result> promise;
  auto future = promise.get_future();
  std::thread([job = std::move(job), promise = std::move(promise)]() mutable {
    try {
      promise.set_value(job());
    } catch (...) {  // never std::terminate from a thread of a session
      promise.set_exception(std::current_exception());
    }
  }).detach();
  return future;
}

template <typename T>
std::future<T> readyFuture(T value) {
  std::promise<T> promise;
  promise.set_value(std::move(value));
  return promise.get_future();
}

bool ready(const auto& future) {
  return future.valid() && future.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

/// A local scene read on its reading thread into `pipe`: a batch at a time where the
/// format allows (splats::openGaussianBatches), else whole and sorted.
void readLocal(const std::shared_ptr<GaussianSceneLoad::Pipe>& pipe, const std::string& path,
               const std::string& url) {
  std::string error;
  std::shared_ptr<const splats::GaussianCloud> whole;
  try {
    base::LocalFetcher fetcher;  // SOG's meta.json names its images beside it
    std::unique_ptr<splats::GaussianBatchReader> reader;
    try {
      reader = splats::openGaussianBatches(path, sideFileReader(fetcher, url));
    } catch (const splats::NotPiecewiseError&) {
    }
    if (reader) {
      {
        std::lock_guard lock(pipe->mutex);
        pipe->total = reader->size();
      }
      splats::GaussianCloud batch;
      while (!pipe->cancelled && reader->read(batch, kBatchSplats) > 0) {
        std::lock_guard lock(pipe->mutex);
        pipe->batches.push_back(std::move(batch));
      }
    } else {
      std::string bytes;
      if (base::readFile(path, bytes, error, std::size_t{16} << 30))
        whole = decodeScene(std::move(bytes), url, sideFileReader(fetcher, url), error);
    }
  } catch (const splats::FormatError& e) {
    error = e.what();
  } catch (const std::bad_alloc&) {
    error = url + ": out of memory";
  } catch (const std::exception& e) {
    error = url + ": " + e.what();
  }
  std::lock_guard lock(pipe->mutex);
  pipe->whole = std::move(whole);
  pipe->error = std::move(error);
  pipe->ended = true;
}

}  // namespace

GaussianSceneLoad::GaussianSceneLoad(net::Loader& loader, std::string url, std::string referrer)
    : loader_(loader), url_(std::move(url)), referrer_(std::move(referrer)) {
  const std::string path = base::localPathOfUrl(url_);
  if (path.empty()) return;  // remote: its transfer starts at the first pump
  pipe_ = std::make_shared<Pipe>();
  std::thread([pipe = pipe_, path, url = url_] { readLocal(pipe, path, url); }).detach();
}

GaussianSceneLoad::~GaussianSceneLoad() {
  cancelTree_->store(true);
  if (pipe_) pipe_->cancelled = true;
  if (transfer_) transfer_->cancel();
}

void GaussianSceneLoad::fail(const std::string& error) {
  set_->loadError = error;
  ++set_->revision;
  stage_ = Stage::done;
  if (transfer_) transfer_->cancel();
  if (columns_) columns_->cancel();
  if (pipe_) pipe_->cancelled = true;
}

void GaussianSceneLoad::grow(const splats::GaussianCloud& batch, std::uint64_t total) {
  if (batch.size() == 0) return;
  if (!growing_) {
    growing_ = std::make_shared<splats::GaussianCloud>();
    growing_->setShDegree(batch.shDegree);
    growing_->colorSpace = batch.colorSpace;  // a glTF capture's may be linear
    growing_->kernel = batch.kernel;
    set_->gaussians = growing_;
  }
  growing_->appendRange(batch, 0, batch.size());
  set_->expectedVectors = std::max<std::uint64_t>(total, growing_->size());
  // The bounds frame the view: again each time the splats doubled, not at every batch.
  if (growing_->size() >= 2 * boundsAt_) {
    set_->computeBounds();
    boundsAt_ = growing_->size();
  }
}

void GaussianSceneLoad::arrived(std::shared_ptr<const splats::GaussianCloud> cloud, bool sorted) {
  stage_ = Stage::sorting;
  if (sorted) {
    sort_ = readyFuture(Sorted{std::move(cloud), {}});
    return;
  }
  // The splats drawn meanwhile change no more: the sort reads them beside the drawing.
  sort_ = detached([cloud = std::move(cloud), url = url_]() {
    Sorted s;
    try {
      s.cloud = std::make_shared<const splats::GaussianCloud>(splats::sortByImportance(*cloud));
    } catch (const std::bad_alloc&) {
      s.error = url + ": out of memory";
    } catch (const std::exception& e) {
      s.error = url + ": " + e.what();
    }
    return s;
  });
}

void GaussianSceneLoad::decodeWhole(std::string bytes) {
  // Side files (SOG's images, a .gltf's buffers) come through a loader of the decoding
  // thread's own, under the session's options: the session's loader belongs to this thread.
  sort_ = detached([bytes = std::move(bytes), url = url_, options = loader_.options()]() mutable {
    Sorted s;
    net::Loader sideLoader(options);
    s.cloud = decodeScene(std::move(bytes), url, sideFileReader(sideLoader, url), s.error);
    return s;
  });
  stage_ = Stage::sorting;
}

void GaussianSceneLoad::stopWithWhatArrived() {
  if (growing_) {
    stopped_ = true;
    arrived(growing_, false);
  } else {
    fail(url_ + ": " + (loader_.stopReason().empty() ? "stopped" : loader_.stopReason()));
  }
}

bool GaussianSceneLoad::pumpColumns() {
  bool changed = false;
  if (columns_->rangesIgnored()) {
    // A server that ignores ranges: one transfer reads the file whole instead of each
    // column reading it up to itself.
    // (The next pump starts it.)
    columns_.reset();
    transfer_.reset();
    buffer_.clear();
    bufferStart_ = 0;
    wholeRead_ = true;
    return false;
  }
  try {
    const bool allowed = columns_->take([this](std::uint64_t n) { return loader_.grant(n); });
    if (!allowed || !loader_.stopReason().empty()) {  // --snapshot-at: what came is drawn
      columns_->cancel();
      splats::GaussianCloud batch;
      while (columns_->next(batch, kRowsPerPump) > 0) grow(batch, columns_->size());
      stopWithWhatArrived();
      return true;
    }
    splats::GaussianCloud batch;
    if (columns_->next(batch, kRowsPerPump) > 0) {
      grow(batch, columns_->size());
      changed = true;
    }
    if (!columns_->finished()) return changed;
    if (const std::string failure = columns_->failure(); !failure.empty()) {
      fail(failure);
      return true;
    }
    // Every byte came: more splats than a pump decodes may still wait (the next pump
    // goes on), or a column ended short, which finish() names.
    if (changed && columns_->decoded() < columns_->size()) return true;
    columns_->finish();
    if (columns_->decoded() < columns_->size())
      throw splats::FormatError(url_ + ": expected " + std::to_string(columns_->size()) +
                                " splats, got " + std::to_string(columns_->decoded()));
    arrived(growing_, false);
    return true;
  } catch (const splats::FormatError& e) {
    fail(e.what());
  } catch (const std::bad_alloc&) {
    fail(url_ + ": out of memory");
  } catch (const std::exception& e) {  // a thread that cannot start
    fail(url_ + ": " + e.what());
  }
  return true;
}

bool GaussianSceneLoad::pumpStream(bool stopped) {
  // A pump inflates at most kStreamBytesPerPump compressed bytes and about
  // kStreamOutputPerPump of their output (a block of zeros inflates up to 1032 times):
  // a frame's share; all that came when --snapshot-at stops the scene.
  const std::uint64_t outputBefore = stream_->inflated();
  std::size_t fed = 0;
  while (streamFed_ < buffer_.size() &&
         (stopped || (fed < kStreamBytesPerPump &&
                      stream_->inflated() - outputBefore < kStreamOutputPerPump))) {
    const std::size_t n = std::min(buffer_.size() - streamFed_, kStreamSlice);
    stream_->feed(std::string_view(buffer_).substr(streamFed_, n));
    streamFed_ += n;
    fed += n;
  }
  // The bytes fed go once they are half the buffer (not at every pump: a fast server may
  // have put much more in it than a pump inflates).
  if (streamFed_ > 0 && streamFed_ >= buffer_.size() / 2) {
    buffer_.erase(0, streamFed_);
    bufferStart_ += streamFed_;
    streamFed_ = 0;
  }
  bool changed = false;
  splats::GaussianCloud batch;
  while (stream_->next(batch, kRowsPerPump) > 0) {
    grow(batch, stream_->size());
    changed = true;
    if (!stopped) break;
  }
  return changed;
}

bool GaussianSceneLoad::inBufferFiles(const splats::GaussianColumnDecoder& decoder) {
  const auto& columns = decoder.columns();
  return std::any_of(columns.begin(), columns.end(), [](const auto& c) { return !c.file.empty(); });
}

std::unique_ptr<GaussianColumnsFetch> GaussianSceneLoad::fetchColumns(
    std::unique_ptr<splats::GaussianColumnDecoder> decoder, std::uint64_t fileBytes) {
  // The resource limit is each file's: a file past it is left to the transfer that reads
  // the scene whole, which fails naming the limit, as does a buffer file the rules of
  // what content may reference refuse.
  std::string error;
  const net::FetchRequest request = loader_.requestFor(url_, referrer_, error);
  if (request.url.empty() || request.maxBytes < fileBytes) return nullptr;
  std::map<std::string, net::FetchRequest> sideRequests;
  for (const auto& c : decoder->columns()) {
    if (c.file.empty() || sideRequests.count(c.file)) continue;
    const std::string url = sideFileUrl(url_, c.file, error);
    net::FetchRequest side =
        url.empty() ? net::FetchRequest{} : loader_.requestFor(url, url_, error);
    if (side.url.empty() || side.maxBytes < c.fileBytes) return nullptr;
    sideRequests.emplace(c.file, std::move(side));
  }
  return std::make_unique<GaussianColumnsFetch>(std::move(decoder), request, buffer_, fileBytes,
                                                url_, sideRequests);
}

bool GaussianSceneLoad::pumpTransfer() {
  if (columns_) return pumpColumns();
  if (!transfer_) {
    std::string error;
    net::FetchRequest request = loader_.requestFor(url_, referrer_, error);
    if (request.url.empty()) {
      fail(error);
      return true;
    }
    transfer_ = net::startTransfer(std::move(request));
  }
  const std::size_t before = buffer_.size();
  transfer_->take(buffer_);
  const net::TransferStatus s = transfer_->status();  // after the take: its size is known
  // --snapshot-at BYTES counts these bytes too (Loader::grant); past it the scene stops.
  const std::uint64_t got = buffer_.size() - before;
  const std::uint64_t granted = got > 0 ? loader_.grant(got) : 0;
  bool stopped = !loader_.stopReason().empty();
  if (granted < got) {
    buffer_.resize(before + static_cast<std::size_t>(granted));
    stopped = true;
  }
  bool changed = false;
  try {
    if (!rows_ && !stream_ && !wholeRead_ && (!buffer_.empty() || s.finished())) {
      const std::uint64_t size = s.resourceSize > 0 ? static_cast<std::uint64_t>(s.resourceSize)
                                 : s.finished()     ? bufferStart_ + buffer_.size()
                                                    : std::numeric_limits<std::uint64_t>::max() / 4;
      splats::GaussianRows found = splats::openGaussianRows(buffer_, url_, size);
      rows_ = std::move(found.decoder);
      bool needMore = found.needMore;
      // A scene read by columns (SPZ v4, GLB) while most of it is still to come, or whose
      // columns lie in buffer files (.gltf): its columns are fetched side by side from
      // here (its size must be known).
      const std::uint64_t known = s.resourceSize > 0 ? static_cast<std::uint64_t>(s.resourceSize)
                                  : s.state == net::TransferState::done ? buffer_.size()
                                                                        : 0;
      // (A scene that came whole is read whole, but for a .gltf's columns.)
      const bool glb = buffer_.starts_with("glTF"), spz = buffer_.starts_with("NGSP");
      if (!rows_ && known > 0 && !stopped && bufferStart_ == 0 &&
          (!s.finished() || (!glb && !spz))) {
        splats::GaussianColumns columns = splats::openGaussianColumns(buffer_, url_, known);
        if (columns.decoder && (!s.finished() || inBufferFiles(*columns.decoder))) {
          if (auto fetch = fetchColumns(std::move(columns.decoder), known)) {
            transfer_->cancel();
            columns_ = std::move(fetch);
            std::string().swap(buffer_);
            return pumpColumns() || changed;
          }
        }
        needMore |= columns.needMore;
      }
      // A JSON scene (.gltf, an SOG's meta.json) of a size not told (gzip or chunked) waits
      // until it came whole, up to 1 MiB, for the columns of its side files.
      if (!rows_ && known == 0 && !stopped && bufferStart_ == 0 &&
          buffer_.size() <= splats::kMaxColumnsJsonBytes) {
        const auto at = buffer_.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
        needMore |= at != std::string::npos && buffer_[at] == '{';
      }
      // A scene in one compressed stream (SPZ v2/v3): decoded as its bytes come.
      if (!rows_) {
        splats::GaussianStream stream = splats::openGaussianStream(
            buffer_, url_, s.resourceSize > 0 ? static_cast<std::uint64_t>(s.resourceSize) : 0);
        stream_ = std::move(stream.decoder);
        needMore |= stream.needMore;
      }
      wholeRead_ = !rows_ && !stream_ && (!needMore || s.finished());
    }
    if (stream_) changed |= pumpStream(stopped);
    if (rows_) {
      const std::uint64_t end = bufferStart_ + buffer_.size(), first = rows_->dataOffset();
      const std::size_t rowBytes = rows_->rowBytes();
      const std::uint64_t whole =
          end > first ? std::min<std::uint64_t>((end - first) / rowBytes, rows_->size()) : 0;
      const auto n =
          static_cast<std::size_t>(std::min<std::uint64_t>(whole - rowsDecoded_, kRowsPerPump));
      if (n > 0) {
        const std::uint64_t from = first + rowsDecoded_ * rowBytes;
        splats::GaussianCloud batch;
        rows_->decode(buffer_.data() + (from - bufferStart_), rowsDecoded_, n, batch);
        grow(batch, rows_->size());
        rowsDecoded_ += n;
        // The decoded rows' bytes go once they are half the buffer (not at every pump:
        // a fast server may have put much more in it than a pump decodes), unless the
        // whole file is read at its end (a compressed PLY's rows are a preview).
        const std::uint64_t consumed = first + rowsDecoded_ * rowBytes;
        if (!rows_->wholeFileAtEnd() && consumed - bufferStart_ >= buffer_.size() / 2) {
          buffer_.erase(0, static_cast<std::size_t>(consumed - bufferStart_));
          bufferStart_ = consumed;
        }
        changed = true;
      }
    }
  } catch (const splats::FormatError& e) {
    fail(e.what());
    return true;
  } catch (const std::bad_alloc&) {
    fail(url_ + ": out of memory");
    return true;
  } catch (const std::exception& e) {  // a column's transfer thread that cannot start
    fail(url_ + ": " + e.what());
    return true;
  }
  if (stopped) {  // drawn with what arrived, as a stream stopped by --snapshot-at
    transfer_->cancel();
    stopWithWhatArrived();
    return true;
  }
  if (!s.finished() || s.received > bufferStart_ + buffer_.size()) return changed;
  if (s.state != net::TransferState::done) {
    fail(s.error.empty() ? url_ + ": cancelled" : s.error);
    return true;
  }
  if (stream_) {
    if (changed || streamFed_ < buffer_.size()) return true;  // the next pump goes on
    try {
      stream_->finish();
    } catch (const splats::FormatError& e) {
      fail(e.what());
      return true;
    }
    if (stream_->decoded() < stream_->size()) {
      fail(url_ + ": expected " + std::to_string(stream_->size()) + " splats, got " +
           std::to_string(stream_->decoded()));
      return true;
    }
    arrived(growing_, false);
    return true;
  }
  if (rows_ && !rows_->wholeFileAtEnd()) {
    const std::uint64_t end = bufferStart_ + buffer_.size();
    const std::uint64_t rowsThere = (end - std::min(end, rows_->dataOffset())) / rows_->rowBytes();
    if (rowsDecoded_ == rows_->size()) {
      arrived(growing_, false);
    } else if (rowsThere < rows_->size()) {
      fail(url_ + ": expected " + std::to_string(rows_->size()) + " splats, got " +
           std::to_string(rowsThere));
    }  // else more rows than one pump decodes are waiting: the next pump goes on
    return true;
  }
  decodeWhole(std::move(buffer_));
  buffer_.clear();
  return changed;
}

bool GaussianSceneLoad::pump() {
  bool changed = false;
  if (stage_ == Stage::arriving) {
    if (!pipe_) {
      changed |= pumpTransfer();
    } else {
      std::deque<splats::GaussianCloud> batches;
      std::uint64_t total = 0;
      bool ended = false;
      {
        std::lock_guard lock(pipe_->mutex);
        batches.swap(pipe_->batches);
        total = pipe_->total;
        ended = pipe_->ended;
      }
      try {
        for (const splats::GaussianCloud& b : batches) grow(b, total);
      } catch (const std::bad_alloc&) {
        fail(url_ + ": out of memory");
        return true;
      }
      changed |= !batches.empty();
      if (ended) {
        std::lock_guard lock(pipe_->mutex);
        if (!pipe_->error.empty()) {
          fail(pipe_->error);
          return true;
        }
        if (pipe_->whole) {
          arrived(pipe_->whole, true);
        } else if (growing_) {
          arrived(growing_, false);
        } else {
          fail(url_ + ": expected at least one splat, got 0");
          return true;
        }
      }
    }
  }
  if (stage_ == Stage::sorting) {
    if (!ready(sort_)) return changed;
    Sorted sorted;
    try {
      sorted = sort_.get();
    } catch (const std::exception& e) {
      sorted.error = url_ + ": " + e.what();
    }
    if (!sorted.cloud) {
      fail(sorted.error);
      return true;
    }
    set_->gaussians = sorted.cloud;
    growing_.reset();
    set_->expectedVectors = 0;
    set_->computeBounds();
    ++set_->revision;
    changed = true;
    stage_ = Stage::tree;
    if (sorted.cloud->size() > 1)
      tree_ = std::async(std::launch::async, buildTreeOf, sorted.cloud, cancelTree_, url_);
    else
      stage_ = Stage::done;
  }
  if (stage_ == Stage::tree && ready(tree_)) {
    auto [tree, problem] = tree_.get();
    if (!problem.empty()) messages_.push_back({false, problem + ": its views draw every splat"});
    if (tree) {
      set_->lodTree = std::move(tree);
      ++set_->revision;
      changed = true;
    }
    stage_ = Stage::done;
  }
  return changed;
}

net::StreamProgress GaussianSceneLoad::progress() const {
  net::StreamProgress p;
  p.url = url_;
  p.kind = net::StreamKind::splats;
  if (transfer_) {
    const net::TransferStatus t = columns_ ? columns_->status() : transfer_->status();
    p.bytes = t.received;
    p.expectedBytes = t.resourceSize >= 0 ? t.resourceSize : t.expected;
    p.bytesPerSecond = t.bytesPerSecond;
  }
  if (growing_) {
    p.vectors = growing_->size();
    p.expectedVectors = std::max<std::uint64_t>(set_->expectedVectors, p.vectors);
  } else if (set_->gaussians) {
    p.vectors = p.expectedVectors = set_->gaussians->size();
  }
  if (!set_->loadError.empty()) {
    p.state = net::StreamState::failed;
    p.error = set_->loadError;
  } else if (stage_ == Stage::done) {
    p.state = stopped_ ? net::StreamState::stopped : net::StreamState::done;
  } else {
    p.state = p.vectors > 0 || p.bytes > 0 ? net::StreamState::loading : net::StreamState::waiting;
    if (stage_ == Stage::sorting) p.stage = "sorting";
    if (stage_ == Stage::tree) p.stage = "building tree";
  }
  if (stopped_ && p.error.empty())
    p.error = url_ + ": " + (loader_.stopReason().empty() ? "stopped" : loader_.stopReason());
  return p;
}

void GaussianSceneLoad::drainMessages(std::vector<std::pair<bool, std::string>>& out) {
  for (auto& m : messages_) out.push_back(std::move(m));
  messages_.clear();
}

}  // namespace gs::session::detail
