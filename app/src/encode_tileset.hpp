// `ghostspace encode --tileset OUT/` and `ghostspace tileset index OUT/`: the command-line
// side of QNV tilesets (docs/qnv-format.md, "Tilesets"). Private to app/src.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>
#include <string_view>

#include "app/options.hpp"
#include "qnv/encoder.hpp"
#include "qnv/tileset.hpp"
#include "qnv/tileset_writer.hpp"

namespace gs::app {

/// Declares `tileset index OUT/` on `cli`; returns the `tileset` subcommand.
CLI::App* addTilesetCommand(CLI::App& cli, std::string& folder);

/// Writes `selected` as the tileset options.encode.tileset asks for: share I of N with
/// --bricks (leaf bricks plus OUT/parts/I-of-N/), else the whole tileset (share 0 of 1,
/// then the merge). Prints the sizes; returns the exit code (0, 1 on an unwritable
/// folder, 2 on bad options).
int writeTileset(const Options& options, const qnv::SelectedVectors& selected,
                 const qnv::WriteOptions& write, const std::string& input, double seconds);

/// Parses --bricks "I/N" (0 <= I < N <= qnv::kMaxTilesetShares); false when malformed.
bool parseShare(const std::string& text, std::uint32_t& share, std::uint32_t& shares);
/// The share of `encode` (its --bricks, 0 of 1 without) and the brick options of its
/// tileset. False, with the error printed on stderr, on a malformed --bricks.
bool tilesetShareOptions(const EncodeOptions& encode, const qnv::WriteOptions& write,
                         std::uint32_t& share, std::uint32_t& shares, qnv::TilesetOptions& cut);
/// "I-of-N", the share's folder under OUT/parts/.
std::string shareName(std::uint32_t share, std::uint32_t shares);
/// Writes `bytes` to `path` (folders made as needed); "" or a sentence naming the path.
std::string writeFile(const std::filesystem::path& path, std::string_view bytes);

/// What the merge wrote.
struct Merged {
  qnv::TilesetIndex index;
  std::uint64_t indexBytes = 0;
  std::uint64_t totalBytes = 0;
};
/// Merges OUT/parts/*: the interior bricks and OUT/index.qnvt; removes OUT/parts.
/// "" or the error.
std::string mergeShares(const std::filesystem::path& dir, Merged& merged);
/// Prints the merged tileset's sizes on stdout.
void printMerged(const std::filesystem::path& dir, const Merged& merged);

}  // namespace gs::app
