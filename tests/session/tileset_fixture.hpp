// A synthetic QNV tileset index for viewer tests: a full octree of `depth` levels over the
// unit cube, every brick holding `perBrick` vectors in plain packets (no brick files).
#pragma once

#include <algorithm>
#include <cmath>
#include <tuple>

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

#include <filesystem>
#include <fstream>
#include <map>

#include "qnv/encoder.hpp"
#include "qnv/record.hpp"
#include "qnv/volume.hpp"

namespace gs::test {

/// Writes a depth-1 tileset of `vectors` (encoder output, largest first) into `dir`
/// after the pinned rule (docs/qnv-format.md): the first ceil(K / 8) vectors of every
/// octant go to the root, the rest stay in their octant's brick. Every brick keeps the
/// whole box as its quantization box (the index gives each octant's box), so it decodes to exactly
/// the single stream's vectors. Returns the index written to dir/index.qnvt.
inline qnv::TilesetIndex writeTestTileset(const qnv::EncodedVectors& vectors,
                                          const std::filesystem::path& dir, std::uint64_t K) {
  const std::uint64_t quota = (K + 7) / 8;
  std::map<std::uint32_t, std::vector<std::uint64_t>> cells;  // 0: root, 1 + octant
  std::map<std::uint32_t, std::uint64_t> ranks;
  for (std::uint64_t r : vectors.records) {
    const qnv::RecordFields f = qnv::unpackRecord(r);
    const std::uint32_t octant = (f.x >> 9) | ((f.y >> 9) << 1) | ((f.z >> 9) << 2);
    cells[ranks[octant]++ < quota ? 0 : 1 + octant].push_back(r);
  }
  qnv::TilesetIndex index;
  index.depth = 1;
  index.header = vectors.header;
  index.header.vectorCount = vectors.records.size();
  const auto& h = vectors.header;
  for (const auto& [cell, records] : cells) {
    qnv::TilesetBrick b;
    b.level = cell == 0 ? 0 : 1;
    if (cell > 0) {
      b.x = (cell - 1) & 1;
      b.y = ((cell - 1) >> 1) & 1;
      b.z = ((cell - 1) >> 2) & 1;
    }
    // The index holds the cell's box (what the viewer culls and measures); the brick
    // file keeps the whole box as its quantization box.
    const glm::vec3 half = (h.boundsMax - h.boundsMin) * 0.5f;
    b.boundsMin = h.boundsMin;
    b.boundsMax = h.boundsMax;
    if (cell > 0) {
      b.boundsMin = h.boundsMin + half * glm::vec3(b.x, b.y, b.z);
      b.boundsMax = b.boundsMin + half;
    }
    b.vectorCount = records.size();
    for (std::uint64_t r : records) ++b.histogram[qnv::tilesetBand(qnv::unpackRecord(r).a)];
    qnv::EncodedVectors part{vectors.header, records};
    qnv::WriteOptions options;
    options.packetBytes = h.packetBytes;
    const std::string bytes = qnv::writeStream(part, options);
    const std::uint64_t per = h.recordsPerPacket();
    std::uint64_t end = qnv::kHeaderBytes;
    for (std::uint64_t left = records.size(); left > 0;) {
      const std::uint64_t n = std::min(left, per);
      end += qnv::kPacketHeaderBytes + n * 8;
      b.packetEnds.push_back(end);
      left -= n;
    }
    b.fileBytes = bytes.size();
    const auto path = dir / b.path();
    std::filesystem::create_directories(path.parent_path());
    std::ofstream(path, std::ios::binary) << bytes;
    index.bricks.push_back(b);
  }
  // Sorted by (level, z, y, x) as the index wants.
  std::sort(index.bricks.begin(), index.bricks.end(), [](const auto& a, const auto& b) {
    return std::tie(a.level, a.z, a.y, a.x) < std::tie(b.level, b.z, b.y, b.x);
  });
  std::ofstream(dir / "index.qnvt", std::ios::binary) << qnv::serializeTilesetIndex(index);
  return index;
}

/// The vectors of an n^3 volume holding a ball with a soft edge (every vector kept).
inline qnv::EncodedVectors ballVolumeVectors(int n) {
  qnv::Volume v;
  v.dims = glm::uvec3(static_cast<unsigned>(n));
  v.samples.resize(v.voxelCount());
  for (int z = 0; z < n; ++z)
    for (int y = 0; y < n; ++y)
      for (int x = 0; x < n; ++x) {
        const double dx = x - n / 2.0, dy = y - n / 2.0, dz = z - n / 2.0;
        const double r = std::sqrt(dx * dx + dy * dy + dz * dz) / (n / 2.0);
        v.samples[static_cast<std::size_t>((z * n + y) * n + x)] =
            static_cast<float>(std::clamp(255.0 * (1.2 - r), 0.0, 255.0));
      }
  return qnv::encodeVolume(v, {});
}

}  // namespace gs::test
