// `ghostspace encode --tileset OUT/` and `ghostspace tileset index OUT/`: the command-line
// side of QNV tilesets (docs/qnv-format.md, "Tilesets"). Private to app/src.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

#include "app/options.hpp"
#include "qnv/encoder.hpp"

namespace gs::app {

/// Declares --tileset, --brick-voxels, --brick-vectors and --bricks on `encode`.
void addTilesetOptions(CLI::App& encode, EncodeOptions& options);

/// Declares `tileset index OUT/` on `cli`; returns the `tileset` subcommand.
CLI::App* addTilesetCommand(CLI::App& cli, std::string& folder);

/// Writes `selected` as the tileset options.encode.tileset asks for: share I of N with
/// --bricks (leaf bricks plus OUT/parts/I-of-N/), else the whole tileset (share 0 of 1,
/// then the merge). Prints the sizes; returns the exit code (0, 1 on an unwritable
/// folder, 2 on bad options).
int writeTileset(const Options& options, const qnv::SelectedVectors& selected,
                 const qnv::WriteOptions& write, const std::string& input, double seconds);

}  // namespace gs::app
