// The OpenVDB side of formats/vdb_reader.hpp, run only in the child process that
// base::IsolatedProcess starts: OpenVDB allocates what a file asks before reading it.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetUtil.h>

#include "qnv/volume_slabs.hpp"
#include "vdb_internal.hpp"

namespace gs::formats::detail {

namespace {

// Frames of about this many bytes of samples.
constexpr std::uint64_t kFrameBytes = std::uint64_t{16} << 20;

std::string describe(const openvdb::GridBase& grid) {
  return grid.valueType() + " '" + grid.getName() + "'";
}

template <typename GridT>
void sendGrid(GridT& grid, std::uint32_t gridCount, base::FrameWriter& out) {
  VdbHeaderFrame h;
  h.grids = gridCount;
  h.isDouble = std::is_same_v<typename GridT::ValueType, double> ? 1 : 0;
  h.levelSet = grid.getGridClass() == openvdb::GRID_LEVEL_SET ? 1 : 0;
  h.activeVoxels = grid.activeVoxelCount();  // as stored, before a level set becomes fog
  if (h.levelSet) openvdb::tools::sdfToFogVolume(grid);
  const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
  if (box.empty()) throw std::runtime_error("grid '" + grid.getName() + "' has no active voxels");
  const openvdb::Coord lo = box.min(), hi = box.max();
  std::uint64_t dims[3];
  for (int i = 0; i < 3; ++i)
    dims[i] = static_cast<std::uint64_t>(static_cast<std::int64_t>(hi[i]) - lo[i] + 1);
  const std::uint64_t slice = dims[0] * dims[1];
  if (dims[0] > UINT32_MAX || dims[1] > UINT32_MAX || dims[2] > UINT32_MAX ||
      slice > qnv::kMaxSliceVoxels || slice * dims[2] > qnv::kMaxSlabVolumeVoxels)
    throw std::runtime_error("the active box of grid '" + grid.getName() + "' is " +
                             std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " +
                             std::to_string(dims[2]) +
                             " voxels, more than a volume may have (2^28 per slice, 2^40 in all)");
  for (int i = 0; i < 3; ++i) h.dims[i] = static_cast<std::uint32_t>(dims[i]);
  const openvdb::math::Transform& xf = grid.transform();
  const openvdb::Vec3d size = xf.voxelSize();
  const openvdb::Vec3d origin = xf.indexToWorld(lo);
  for (int i = 0; i < 3; ++i) {
    h.spacing[i] = static_cast<float>(size[i]);
    h.origin[i] = static_cast<float>(origin[i]);
    if (!std::isfinite(h.spacing[i]) || !(h.spacing[i] > 0) || !std::isfinite(h.origin[i]))
      throw std::runtime_error("grid '" + grid.getName() +
                               "' has a transform without a finite, positive voxel size");
  }
  float lowest = std::numeric_limits<float>::infinity(), highest = -lowest;
  auto take = [&](double v) {
    const float f = static_cast<float>(v);
    if (!std::isfinite(f)) return;
    lowest = std::min(lowest, f);
    highest = std::max(highest, f);
  };
  take(static_cast<double>(grid.background()));
  for (auto it = grid.cbeginValueOn(); it; ++it) take(static_cast<double>(*it));
  h.range[0] = lowest <= highest ? lowest : 0.0f;
  h.range[1] = lowest <= highest ? highest : 0.0f;
  h.slabSlices = static_cast<std::uint32_t>(
      std::clamp<std::uint64_t>(kFrameBytes / sizeof(float) / slice, 1, dims[2]));

  std::string header(sizeof h, '\0');
  std::memcpy(header.data(), &h, sizeof h);
  out.write(header + grid.getName());

  auto acc = grid.getConstAccessor();
  std::vector<float> samples;
  for (std::uint64_t z0 = 0; z0 < dims[2]; z0 += h.slabSlices) {
    const std::uint64_t z1 = std::min<std::uint64_t>(dims[2], z0 + h.slabSlices);
    samples.resize(static_cast<std::size_t>(slice * (z1 - z0)));
    std::size_t i = 0;
    for (std::uint64_t z = z0; z < z1; ++z)
      for (std::uint64_t y = 0; y < dims[1]; ++y)
        for (std::uint64_t x = 0; x < dims[0]; ++x)
          samples[i++] = static_cast<float>(acc.getValue(
              openvdb::Coord(lo.x() + static_cast<int>(x), lo.y() + static_cast<int>(y),
                             lo.z() + static_cast<int>(z))));
    out.write(std::string_view(reinterpret_cast<const char*>(samples.data()),
                               samples.size() * sizeof(float)));
  }
}

}  // namespace

void sendVdbGrid(std::istream& in, const std::string& gridName, base::FrameWriter& out) {
  openvdb::initialize();
  openvdb::GridPtrVecPtr grids;
  try {
    openvdb::io::Stream stream(in, /*delayLoad=*/false);
    grids = stream.getGrids();
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("cannot open as OpenVDB (") + e.what() + ")");
  }
  if (!grids || grids->empty())
    throw std::runtime_error("cannot open as OpenVDB (no grid could be read)");
  const auto count = static_cast<std::uint32_t>(grids->size());
  std::string seen;
  for (const openvdb::GridBase::Ptr& grid : *grids) {
    if (!grid) continue;
    if (!gridName.empty() && grid->getName() != gridName) {
      seen += (seen.empty() ? "" : ", ") + describe(*grid);
      continue;
    }
    if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) return sendGrid(*f, count, out);
    if (auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(grid)) return sendGrid(*d, count, out);
    seen += (seen.empty() ? "" : ", ") + describe(*grid);
  }
  throw std::runtime_error(std::string(gridName.empty()
                                           ? "no float or double grid"
                                           : "no float or double grid named '" + gridName + "'") +
                           " (the file has " + seen + ")");
}

}  // namespace gs::formats::detail
