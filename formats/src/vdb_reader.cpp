// OpenVDB grids read by a child process and served slab by slab (formats/vdb_reader.hpp).
#include "formats/vdb_reader.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

#include "base/isolated_process.hpp"
#include "qnv/error.hpp"
#include "vdb_internal.hpp"

namespace gs::formats {

namespace {

using qnv::InputError;

class IsolatedVdbReader final : public VdbSlabReader {
 public:
  IsolatedVdbReader(std::function<void(base::FrameWriter&)> work, std::string name,
                    base::IsolationLimits limits)
      : work_(std::move(work)), name_(std::move(name)), limits_(limits) {
    start();
  }

  const qnv::VolumeGridInfo& info() const override { return info_; }
  const VdbGridSummary& summary() const override { return summary_; }

  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    if (!(z0 < z1 && z1 <= info_.dims.z))
      throw InputError(name_ + ": slices [" + std::to_string(z0) + ", " + std::to_string(z1) +
                       ") are outside the grid's " + std::to_string(info_.dims.z));
    const std::size_t slice = static_cast<std::size_t>(info_.sliceVoxels());
    out.resize(slice * (z1 - z0));
    for (std::uint32_t z = z0; z < z1; ++z) {
      if (!(frameZ0_ <= z && z < frameZ1_)) {
        if (z < frameZ1_ || !process_) start();  // backwards: the child begins again
        while (!(z < frameZ1_)) pull();
      }
      std::memcpy(out.data() + slice * (z - z0), frame_.data() + (z - frameZ0_) * slice,
                  slice * sizeof(float));
    }
  }

 private:
  [[noreturn]] void fail(const base::IsolationError& e) {
    process_.reset();
    throw InputError(name_ + ": " + e.what());
  }

  void start() {
    process_.reset();
    frame_.clear();
    frameZ0_ = frameZ1_ = 0;
    try {
      process_ = std::make_unique<base::IsolatedProcess>(work_, limits_);
      const std::string header = process_->next(sizeof(detail::VdbHeaderFrame) + 4096);
      if (header.size() < sizeof(detail::VdbHeaderFrame))
        throw base::IsolationError("the OpenVDB reader sent a short header");
      detail::VdbHeaderFrame h;
      std::memcpy(&h, header.data(), sizeof h);
      info_.dims = {h.dims[0], h.dims[1], h.dims[2]};
      info_.spacing = {h.spacing[0], h.spacing[1], h.spacing[2]};
      info_.origin = {h.origin[0], h.origin[1], h.origin[2]};
      info_.sourceType = h.isDouble ? qnv::ScalarType::float64 : qnv::ScalarType::float32;
      info_.valueRange = std::make_pair(h.range[0], h.range[1]);
      const std::uint64_t slice = info_.sliceVoxels();
      if (slice == 0 || info_.dims.z == 0 || slice > qnv::kMaxSliceVoxels ||
          info_.voxelCount() > qnv::kMaxSlabVolumeVoxels || h.slabSlices == 0)
        throw base::IsolationError("the OpenVDB reader sent a grid outside the limits");
      slabSlices_ = h.slabSlices;
      summary_.name = header.substr(sizeof h);
      summary_.valueType = h.isDouble ? "double" : "float";
      summary_.levelSet = h.levelSet != 0;
      summary_.activeVoxels = h.activeVoxels;
      summary_.grids = h.grids;
    } catch (const base::IsolationError& e) {
      fail(e);
    }
  }

  // The next frame of slices.
  void pull() {
    if (frameZ1_ >= info_.dims.z) throw InputError(name_ + ": read past the grid's last slice");
    const std::uint32_t z0 = frameZ1_;
    const std::uint32_t z1 = static_cast<std::uint32_t>(
        std::min<std::uint64_t>(info_.dims.z, std::uint64_t{z0} + slabSlices_));
    const std::uint64_t bytes = info_.sliceVoxels() * (z1 - z0) * sizeof(float);
    try {
      const std::string data = process_->next(bytes);
      if (data.size() != bytes)
        throw base::IsolationError("the OpenVDB reader sent " + std::to_string(data.size()) +
                                   " bytes for slices " + std::to_string(z0) + ".." +
                                   std::to_string(z1) + ", expected " + std::to_string(bytes));
      frame_.resize(static_cast<std::size_t>(bytes / sizeof(float)));
      std::memcpy(frame_.data(), data.data(), data.size());
    } catch (const base::IsolationError& e) {
      fail(e);
    }
    frameZ0_ = z0;
    frameZ1_ = z1;
  }

  std::function<void(base::FrameWriter&)> work_;
  std::string name_;
  base::IsolationLimits limits_;
  std::unique_ptr<base::IsolatedProcess> process_;
  qnv::VolumeGridInfo info_;
  VdbGridSummary summary_;
  std::uint32_t slabSlices_ = 1;
  std::vector<float> frame_;
  std::uint32_t frameZ0_ = 0, frameZ1_ = 0;
};

}  // namespace

bool hasVdbMagic(std::string_view head) {
  return head.size() >= 8 && head.substr(0, 8) == std::string_view("\x20\x42\x44\x56\0\0\0\0", 8);
}

std::unique_ptr<VdbSlabReader> openVdb(const std::string& path, const std::string& gridName,
                                       std::uint64_t memoryBytes) {
  std::ifstream probe(path, std::ios::binary | std::ios::ate);
  if (!probe) throw InputError("cannot open " + path + ": no such file or not readable");
  const auto size = static_cast<std::uint64_t>(std::max<std::streamoff>(0, probe.tellg()));
  if (memoryBytes == 0) memoryBytes = base::isolationMemoryFor(size);
  auto work = [path, gridName](base::FrameWriter& out) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open the file");
    detail::sendVdbGrid(in, gridName, out);
  };
  base::IsolationLimits limits;
  limits.memoryBytes = memoryBytes;
  return std::make_unique<IsolatedVdbReader>(work, path, limits);
}

std::unique_ptr<VdbSlabReader> openVdbBytes(std::string bytes, const std::string& name,
                                            const std::string& gridName,
                                            base::IsolationLimits limits) {
  if (limits.memoryBytes == 0) limits.memoryBytes = base::isolationMemoryFor(bytes.size());
  auto shared = std::make_shared<const std::string>(std::move(bytes));
  auto work = [shared, gridName](base::FrameWriter& out) {
    std::istringstream in(*shared, std::ios::binary);
    detail::sendVdbGrid(in, gridName, out);
  };
  return std::make_unique<IsolatedVdbReader>(work, name, limits);
}

}  // namespace gs::formats
