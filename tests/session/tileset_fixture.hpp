// A synthetic QNV tileset index for viewer tests: a full octree of `depth` levels over the
// unit cube, every brick holding `perBrick` vectors in plain packets (no brick files).
#pragma once

#include "qnv/tileset.hpp"

namespace gs::test {

inline qnv::TilesetIndex syntheticTileset(int depth, std::uint64_t perBrick) {
  qnv::TilesetIndex index;
  index.depth = static_cast<std::uint8_t>(depth);
  index.header.boundsMin = glm::vec3(0.0f);
  index.header.boundsMax = glm::vec3(1.0f);
  const std::uint64_t per = index.header.recordsPerPacket();
  for (int level = 0; level <= depth; ++level) {
    const std::uint32_t n = 1u << level;
    const float side = 1.0f / static_cast<float>(n);
    for (std::uint32_t z = 0; z < n; ++z)
      for (std::uint32_t y = 0; y < n; ++y)
        for (std::uint32_t x = 0; x < n; ++x) {
          qnv::TilesetBrick b;
          b.level = static_cast<std::uint8_t>(level);
          b.x = x;
          b.y = y;
          b.z = z;
          b.boundsMin = glm::vec3(x, y, z) * side;
          b.boundsMax = glm::vec3(x + 1, y + 1, z + 1) * side;
          b.vectorCount = perBrick;
          b.histogram[static_cast<std::size_t>(15 - level)] = static_cast<std::uint32_t>(perBrick);
          std::uint64_t end = qnv::kHeaderBytes;
          for (std::uint64_t left = perBrick; left > 0;) {
            const std::uint64_t r = std::min(left, per);
            end += qnv::kPacketHeaderBytes + r * 8;
            b.packetEnds.push_back(end);
            left -= r;
          }
          b.fileBytes = end;
          index.bricks.push_back(b);
          index.header.vectorCount += perBrick;
        }
  }
  return index;
}

}  // namespace gs::test
