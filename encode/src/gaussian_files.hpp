// What the in-memory and the out-of-core encodes of a Gaussian tileset share
// (encode/src/gaussian_tileset.cpp, encode/src/ooc_gaussian.cpp). Private to encode/src.
#pragma once

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "encode/tileset.hpp"
#include "qnv/tileset_writer.hpp"
#include "splats/qnv_gaussians.hpp"

namespace gs::encode {

/// The path of node `node`'s merged brick in a tileset folder: "merged/L/X_Y_Z.qnv".
std::string mergedPathOf(const qnv::TilesetCell& node);

/// After the bricks are written (their bytes counted in result.merged.totalBytes): writes
/// `mergedBricks` (each node's merged brick, at mergedPathOf), then, whole, the checked
/// index.qnvt (result.merged.index becomes `index`), or, a share, its parts (leaves.qnvt,
/// an interior.qnvp without entries, gaussian.txt). Sets result's sizes and seconds since
/// `t0`; Failure::write and the sentence naming the file when one is not written.
TilesetResult& finishGaussianTileset(
    const TilesetTarget& target, const splats::GaussianStreamOptions& options,
    qnv::TilesetIndex index,
    const std::vector<std::pair<qnv::TilesetCell, std::string>>& mergedBricks,
    std::chrono::steady_clock::time_point t0, TilesetResult& result);

}  // namespace gs::encode
