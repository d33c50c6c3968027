// A remote Gaussian splatting scene read by columns (splats::GaussianColumnDecoder: an SPZ
// v4 file's zstd streams, a GLB or .gltf capture's accessors, in its own file or in buffer
// files beside it, an SOG meta.json's WebP images): one HTTP request per column (a range,
// or an SOG's image whole),
// side by side, each column decoded as its bytes arrive, and the splats whose every record
// came handed over in file order, with all they hold (docs/splats.md, "Opening a scene").
// Columns of at most four zstd blocks of records come first (zstd gives a block's records
// only once all its bytes came), then the others side by side. A server that ignores
// ranges is seen at its first answer (rangesIgnored): its caller then reads the file once
// whole. Private to the session (gaussian_scene_load.hpp).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "net/transfer.hpp"
#include "splats/readers.hpp"

namespace gs::session::detail {

class GaussianColumnsFetch {
 public:
  /// Starts fetching `decoder`'s columns of the scene `name`: `request` is the loader's
  /// request for the whole file (Loader::requestFor); each column's transfer asks for its
  /// own bytes and gets a share of its maxRate in proportion to them (an emulated link
  /// stays as slow, and every column ends when the whole file would have).
  /// `head` holds the file's first bytes, already fetched: the columns' bytes within it
  /// are not fetched again. `fileBytes`: the file's size (for the Streams panel).
  /// `sideRequests`: the request for each buffer file a column lies in (Column::file, as
  /// Loader::requestFor makes it for the file's URL); std::out_of_range for one missing.
  GaussianColumnsFetch(std::unique_ptr<splats::GaussianColumnDecoder> decoder,
                       const net::FetchRequest& request, std::string_view head,
                       std::uint64_t fileBytes, std::string name,
                       const std::map<std::string, net::FetchRequest>& sideRequests = {});
  /// Cancels the transfers still running.
  ~GaussianColumnsFetch();
  GaussianColumnsFetch(const GaussianColumnsFetch&) = delete;
  GaussianColumnsFetch& operator=(const GaussianColumnsFetch&) = delete;

  /// Takes what arrived at each transfer, as much of it as `grant(bytes)` allows
  /// (Loader::grant: --snapshot-at counts every byte); false when grant refused some (the
  /// load stops there). FormatError for a column that got more bytes than it holds.
  bool take(const std::function<std::uint64_t(std::uint64_t)>& grant);
  /// Decodes the next splats, at most `max`, whose records all arrived into `batch`
  /// (resized to them) and returns how many (0: none yet). FormatError for damaged data.
  std::size_t next(splats::GaussianCloud& batch, std::size_t max);
  /// Whether every transfer ended; `failure()` is the first one's error that did not end
  /// done, or a buffer file whose size is not the one its scene states (empty when none).
  bool finished() const;
  std::string failure() const;
  /// Once finished() and every splat handed over: FormatError unless each column ends as
  /// the whole-file reader requires (readSpzGaussians: a zstd frame complete, nothing more).
  void finish();
  /// Splats handed over, of size().
  std::uint64_t decoded() const { return decoded_; }
  std::uint64_t size() const { return decoder_->size(); }
  /// Bytes received over every transfer and the head (for the Streams panel), the file's
  /// bytes and the transfers' summed rate.
  net::TransferStatus status() const;
  /// Stops every transfer.
  void cancel();
  /// Whether a server answered a column's range request with the whole file: then each
  /// column would read the file up to itself (its caller reads the file whole instead).
  bool rangesIgnored() const;

 private:
  struct Column;
  /// Starts the transfers of wave `wave` (0: the columns of a few zstd blocks, fetched
  /// first; 1: the others).
  void start(int wave);
  /// Whether `c`'s transfer ended and every byte it delivered was taken.
  static bool ended(const Column& c);
  std::unique_ptr<splats::GaussianColumnDecoder> decoder_;
  std::string name_;
  std::vector<std::unique_ptr<Column>> columns_;
  std::uint64_t headBytes_ = 0, fileBytes_ = 0, decoded_ = 0;
  std::uint64_t sideBytes_ = 0;  // the bytes of the columns in buffer files
  int wave_ = 0;
};

}  // namespace gs::session::detail
