// What the OpenVDB child process (vdb_child.cpp) and the reader that starts it
// (vdb_reader.cpp) share: the frame that opens the child's answer.
#pragma once

#include <cstdint>
#include <istream>
#include <string>

#include "base/isolated_process.hpp"

namespace gs::formats::detail {

/// The first frame: the grid, then its name (the frame's bytes after the struct). Both
/// ends are the same program (the child is a fork), so the struct goes as it is.
struct VdbHeaderFrame {
  std::uint32_t dims[3] = {0, 0, 0};
  float spacing[3] = {1, 1, 1};
  float origin[3] = {0, 0, 0};
  float range[2] = {0, 0};  // finite values of the active voxels and the background
  std::uint64_t activeVoxels = 0;
  std::uint32_t grids = 0;
  std::uint32_t slabSlices = 1;  // slices per data frame after this one
  std::uint8_t levelSet = 0;
  std::uint8_t isDouble = 0;
};

/// In the child: reads the VDB file from `in` (io::Stream, no delayed loading), picks the
/// first float or double grid named `gridName` (any when empty), sends a VdbHeaderFrame
/// and then the slabs of slices of its active box in increasing z, each as floats (x
/// fastest). Throws std::runtime_error with a message that follows "file: " in an error.
void sendVdbGrid(std::istream& in, const std::string& gridName, base::FrameWriter& out);

}  // namespace gs::formats::detail
