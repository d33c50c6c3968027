// The share side of the out-of-core tileset encodes (volumes: ooc_tileset.cpp, meshes:
// ooc_mesh.cpp): vectors buffered by leaf under a memory bound and spilled to the share's
// part folder past it, leaves finished a row at a time on worker threads, and the share's
// parts written (docs/out-of-core.md, "Tileset encoding"). Private to encode/src.
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "encode/tileset.hpp"
#include "qnv/error.hpp"
#include "qnv/tileset_writer.hpp"
#include "splats/merged_levels.hpp"

namespace gs::encode::ooc {

namespace fs = std::filesystem;

// A file of raw records appended in chunks and read back by offset (pread: several
// threads may read at once). Removed when destroyed.
class SpillFile {
 public:
  explicit SpillFile(fs::path path) : path_(std::move(path)) {}
  ~SpillFile() {
    if (fd_ >= 0) {
      ::close(fd_);
      std::error_code ec;
      fs::remove(path_, ec);
    }
  }
  SpillFile(const SpillFile&) = delete;
  SpillFile& operator=(const SpillFile&) = delete;

  std::uint64_t append(const void* data, std::size_t bytes) {
    if (fd_ < 0) {
      std::error_code ec;
      fs::create_directories(path_.parent_path(), ec);
      fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
      if (fd_ < 0) fail("cannot create");
    }
    const std::uint64_t at = size_;
    const char* p = static_cast<const char*>(data);
    for (std::size_t done = 0; done < bytes;) {
      const ssize_t n = ::pwrite(fd_, p + done, bytes - done, static_cast<off_t>(size_ + done));
      if (n <= 0) fail("cannot write");
      done += static_cast<std::size_t>(n);
    }
    size_ += bytes;
    return at;
  }
  void read(std::uint64_t offset, void* data, std::size_t bytes) const {
    char* p = static_cast<char*>(data);
    for (std::size_t done = 0; done < bytes;) {
      const ssize_t n = ::pread(fd_, p + done, bytes - done, static_cast<off_t>(offset + done));
      if (n <= 0) fail("cannot read back");
      done += static_cast<std::size_t>(n);
    }
  }
  std::uint64_t size() const { return size_; }

 private:
  [[noreturn]] void fail(const char* what) const {
    throw qnv::InputError(std::string(what) + " the spill file '" + path_.string() +
                          "': " + std::strerror(errno));
  }
  fs::path path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

struct Chunk {
  std::uint64_t offset = 0, count = 0;
};

template <typename T>
void readChunks(const SpillFile& file, const std::vector<Chunk>& chunks, std::vector<T>& out) {
  for (const Chunk& c : chunks) {
    const std::size_t at = out.size();
    out.resize(at + c.count);
    file.read(c.offset, out.data() + at, c.count * sizeof(T));
  }
}

// One share's vector pass: buffers, spills and finishes leaves, writes their bricks.
class ShareEncoder {
 public:
  ShareEncoder(const fs::path& dir, const fs::path& part, const qnv::TilesetLayout& layout,
               std::uint32_t share, std::uint32_t shares, std::uint64_t memoryBytes,
               unsigned threads)
      : dir_(dir),
        layout_(layout),
        writer_(layout, share, shares),
        range_(writer_.leafRange()),
        leafBudget_(memoryBytes - memoryBytes / 4),
        interiorBudget_(memoryBytes / 8),
        threads_(threads),
        leafSpill_(part / "leaves.spill"),
        interiorSpill_(part / "interior.spill") {
    if (layout.options().mergedCellsLog2 > 0 && layout.depth() > 0)
      merged_.emplace(layout, layout.options().mergedCellsLog2);
  }

  void add(std::uint64_t leaf, const qnv::SourceVector& v) {
    if (merged_) merged_->add(v);
    if (!last_ || lastLeaf_ != leaf) {  // consecutive vectors mostly share a leaf
      last_ = &open_[leaf];
      lastLeaf_ = leaf;
    }
    std::vector<qnv::SourceVector>& b = *last_;
    const std::size_t capacity = b.capacity();
    b.push_back(v);
    openBytes_ += (b.capacity() - capacity) * sizeof(qnv::SourceVector);
    if (openBytes_ + finishingBytes_ + interiorBytes_ > leafBudget_) spillLeaves();
  }

  // Starts finishing every leaf of leaf row `row` (z) in this share, on a thread of its
  // own (with --threads workers) while the vector pass goes on; the previous row's
  // finishing is collected first, so at most one row is in flight.
  void finishRow(std::uint32_t row) {
    collect();
    const std::uint64_t perRow = std::uint64_t{layout_.leafGrid().x} * layout_.leafGrid().y;
    const std::uint64_t first = std::max(range_.first, perRow * row);
    const std::uint64_t last = std::min(range_.second, perRow * (row + 1));
    auto batch = std::make_unique<Batch>();
    last_ = nullptr;
    for (std::uint64_t leaf = first; leaf < last; ++leaf) {
      Job job{leaf, {}, {}, {}};
      if (auto o = open_.find(leaf); o != open_.end()) {
        job.vectors = std::move(o->second);
        open_.erase(o);
      }
      if (auto s = spilled_.find(leaf); s != spilled_.end()) {
        job.chunks = std::move(s->second);
        spilled_.erase(s);
      }
      batch->bytes += job.vectors.capacity() * sizeof(qnv::SourceVector);
      if (!job.vectors.empty() || !job.chunks.empty()) batch->jobs.push_back(std::move(job));
    }
    openBytes_ = 0;
    for (const auto& [leaf, vectors] : open_)
      openBytes_ += vectors.capacity() * sizeof(qnv::SourceVector);
    finishingBytes_ = batch->bytes;
    const unsigned workers = static_cast<unsigned>(
        std::max<std::size_t>(1, std::min<std::size_t>(threads_, batch->jobs.size())));
    batch->interior.resize(workers);
    batch->errors.resize(workers);
    Batch* b = batch.get();
    batch->runner = std::jthread([this, b, workers] {
      const auto work = [this, b](unsigned w) {
        try {
          for (std::size_t j; (j = b->next++) < b->jobs.size();) {
            Job& job = b->jobs[j];
            readChunks(leafSpill_, job.chunks, job.vectors);
            std::optional<qnv::BrickFile> brick =
                writer_.rankLeaf(layout_.leafAt(job.leaf), std::move(job.vectors), b->interior[w]);
            job.vectors = {};
            if (!brick) continue;
            if (std::string e = writeFile(dir_ / brick->brick.path(), brick->bytes); !e.empty())
              throw qnv::InputError(e);
            job.brick = std::move(brick->brick);
          }
        } catch (...) {
          b->errors[w] = std::current_exception();
        }
      };
      std::vector<std::thread> pool;
      for (unsigned w = 1; w < workers; ++w) pool.emplace_back(work, w);
      work(0);
      for (std::thread& t : pool) t.join();
    });
    inFlight_ = std::move(batch);
  }

  // Waits for the row in flight and takes its bricks and interior contributions.
  void collect() {
    if (!inFlight_) return;
    std::unique_ptr<Batch> batch = std::move(inFlight_);
    batch->runner.join();
    finishingBytes_ = 0;
    for (const std::exception_ptr& e : batch->errors)
      if (e) std::rethrow_exception(e);
    for (Job& job : batch->jobs)
      if (job.brick) {
        brickBytes_ += job.brick->fileBytes;
        bricks_.push_back(std::move(*job.brick));
      }
    for (qnv::InteriorParts& parts : batch->interior) {
      for (const auto& [node, entries] : parts)
        interiorBytes_ += entries.size() * sizeof(qnv::InteriorEntry);
      writer_.addInterior(std::move(parts));
    }
    if (interiorBytes_ > interiorBudget_) spillInterior();
  }

  // leaves.qnvt and interior.qnvp of the share; "" or the error.
  std::string writeParts(const fs::path& part, const qnv::TilesetOptions& cut) {
    collect();
    const std::string index =
        qnv::serializeTilesetIndex(qnv::assembleTilesetIndex(layout_, std::move(bricks_)));
    if (std::string e = writeFile(part / "leaves.qnvt", index); !e.empty()) return e;
    partBytes_ += index.size();
    const qnv::InteriorParts held = writer_.takeInterior();
    std::map<qnv::TilesetCell,
             std::pair<const std::vector<qnv::InteriorEntry>*, const std::vector<Chunk>*>>
        nodes;
    for (const auto& [node, entries] : held) nodes[node].first = &entries;
    for (const auto& [node, chunks] : interiorChunks_) nodes[node].second = &chunks;
    std::vector<qnv::TilesetCell> cells;
    std::vector<std::pair<const std::vector<qnv::InteriorEntry>*, const std::vector<Chunk>*>>
        sources;
    for (const auto& [node, from] : nodes) {
      cells.push_back(node);
      sources.push_back(from);
    }
    const fs::path path = part / "interior.qnvp";
    std::FILE* out = std::fopen(path.c_str(), "wb");
    if (!out) return "cannot write '" + path.string() + "'";
    bool ok = true;
    qnv::writeInteriorParts(
        cells,
        [&](std::size_t i) {
          std::vector<qnv::InteriorEntry> entries;
          if (sources[i].second) readChunks(interiorSpill_, *sources[i].second, entries);
          if (sources[i].first)
            entries.insert(entries.end(), sources[i].first->begin(), sources[i].first->end());
          return entries;
        },
        cut,
        [&](std::string_view bytes) {
          ok = ok && std::fwrite(bytes.data(), 1, bytes.size(), out) == bytes.size();
          partBytes_ += bytes.size();
        });
    ok = std::fclose(out) == 0 && ok;
    if (!ok) return "cannot write '" + path.string() + "'";
    if (merged_) {
      const std::string bytes = merged_->serialize();
      partBytes_ += bytes.size();
      return writeFile(part / "merged.qnvm", bytes);
    }
    return {};
  }

  std::uint64_t bytesWritten() const { return brickBytes_ + partBytes_; }
  std::uint64_t leafSpillBytes() const { return leafSpill_.size(); }
  std::uint64_t interiorSpillBytes() const { return interiorSpill_.size(); }
  std::pair<std::uint64_t, std::uint64_t> range() const { return range_; }

 private:
  void spillLeaves() {
    for (auto& [leaf, vectors] : open_) {
      if (vectors.empty()) continue;
      const std::uint64_t at =
          leafSpill_.append(vectors.data(), vectors.size() * sizeof(qnv::SourceVector));
      spilled_[leaf].push_back({at, vectors.size()});
    }
    open_.clear();
    last_ = nullptr;
    openBytes_ = 0;
  }
  void spillInterior() {
    for (const auto& [node, entries] : writer_.takeInterior()) {
      if (entries.empty()) continue;
      const std::uint64_t at =
          interiorSpill_.append(entries.data(), entries.size() * sizeof(qnv::InteriorEntry));
      interiorChunks_[node].push_back({at, entries.size()});
    }
    interiorBytes_ = 0;
  }

  struct Job {
    std::uint64_t leaf;
    std::vector<qnv::SourceVector> vectors;
    std::vector<Chunk> chunks;
    std::optional<qnv::TilesetBrick> brick;
  };
  // A row of leaves being finished.
  struct Batch {
    std::vector<Job> jobs;
    std::vector<qnv::InteriorParts> interior;
    std::vector<std::exception_ptr> errors;
    std::atomic<std::size_t> next{0};
    std::uint64_t bytes = 0;  // the jobs' vectors held in memory
    std::jthread runner;
  };

  fs::path dir_;
  const qnv::TilesetLayout& layout_;
  // The merged levels' sums (held whole: about 300 bytes per cell with vectors).
  std::optional<splats::MergedLevelBuilder> merged_;
  qnv::TilesetShareWriter writer_;
  std::pair<std::uint64_t, std::uint64_t> range_;
  std::uint64_t leafBudget_, interiorBudget_;
  unsigned threads_;
  std::map<std::uint64_t, std::vector<qnv::SourceVector>> open_;
  std::map<std::uint64_t, std::vector<Chunk>> spilled_;
  std::vector<qnv::SourceVector>* last_ = nullptr;
  std::uint64_t lastLeaf_ = 0;
  std::map<qnv::TilesetCell, std::vector<Chunk>> interiorChunks_;
  std::uint64_t openBytes_ = 0, interiorBytes_ = 0, brickBytes_ = 0, partBytes_ = 0;
  std::vector<qnv::TilesetBrick> bricks_;
  std::uint64_t finishingBytes_ = 0;
  SpillFile leafSpill_, interiorSpill_;
  std::unique_ptr<Batch> inFlight_;  // last: joined before the members it uses go
};

// Seconds since `t0` (the encodes' progress lines).
inline double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The worker count of `ooc`: its threads, else the hardware's.
inline unsigned workerThreads(const OutOfCoreOptions& ooc) {
  return ooc.threads > 0 ? ooc.threads : std::max(1u, std::thread::hardware_concurrency());
}

// Removes what a whole run replaces: bricks/, parts/ and index.qnvt of `dir`.
inline void removeStale(const fs::path& dir) {
  std::error_code ec;
  fs::remove_all(dir / "bricks", ec);
  fs::remove_all(dir / "parts", ec);
  fs::remove_all(dir / "merged", ec);
  fs::remove(dir / "index.qnvt", ec);
}

}  // namespace gs::encode::ooc
