// `ghostspace encode --tileset OUT/` and `ghostspace tileset index OUT/`: the command-line
// side of QNV tilesets (docs/qnv-format.md, "Tilesets"; docs/out-of-core.md): options to
// an encode::TilesetTarget, the library's encodes (encode/tileset.hpp) called, their
// results printed. Private to app/src.
#pragma once

#include <CLI/CLI.hpp>

#include <filesystem>
#include <string>

#include "app/options.hpp"
#include "encode/tileset.hpp"
#include "qnv/encoder.hpp"
#include "qnv/volume_slabs.hpp"

namespace gs::app {

/// Declares `tileset index OUT/` on `cli`; returns the `tileset` subcommand.
CLI::App* addTilesetCommand(CLI::App& cli, std::string& folder);

/// The tileset `encode` asks for: its folder, brick options, `write`, and its --bricks
/// share (the whole tileset without). False, with the error printed on stderr, on a
/// malformed --bricks.
bool tilesetTarget(const EncodeOptions& encode, const qnv::WriteOptions& write,
                   encode::TilesetTarget& target);

/// Writes `selected` as the tileset options.encode.tileset asks for (encode::writeTileset).
/// Prints the sizes; returns the exit code (0, 1 on an unwritable folder, 2 on bad
/// options).
int writeTileset(const Options& options, const qnv::SelectedVectors& selected,
                 const qnv::WriteOptions& write, const std::string& input, double seconds);

/// `encode VOLUME --tileset OUT/ --memory MB`: encode::writeVolumeTilesetOutOfCore with
/// --memory and --threads. Prints the sizes and times; returns the exit code (0, 1 on a
/// read or write error, 2 on bad options).
int writeVolumeTilesetOutOfCore(const Options& options, qnv::VolumeSlabReader& reader,
                                const qnv::VolumeEncodeOptions& encode,
                                const qnv::WriteOptions& write, const std::string& input);

/// `encode MESH.ply --tileset OUT/ --memory MB`: encode::writeMeshTilesetOutOfCore.
/// Same exit codes.
int writeMeshTilesetOutOfCore(const Options& options, const std::string& input,
                              const qnv::SurfaceEncodeOptions& encode,
                              const qnv::WriteOptions& write);

/// `encode SCENE --tileset OUT/ --memory MB` of a Gaussian splatting scene (binary INRIA
/// .ply or .splat, read piecewise): encode::writeGaussianTilesetOutOfCore into `target`,
/// with --sh-bits, --sh-full, --memory and --merged-cells (not given: the scene's
/// default). Returns 0; 1 when the scene cannot be read or a file not written; 2 for a
/// scene of another format (which the in-memory encode reads).
int writeGaussianTilesetOutOfCore(const Options& options, const encode::TilesetTarget& target,
                                  const std::string& input);

/// Prints a merged tileset's sizes on stdout.
void printMerged(const std::filesystem::path& dir, const encode::Merged& merged);

/// The last line of a tileset encode on stdout: the merged tileset's sizes and `seconds`
/// (the whole command's time) when the run was the whole encode, else which leaves the
/// share wrote and the merge command to run after every share.
void printEncodeResult(const encode::TilesetTarget& target, const std::string& input,
                       const encode::TilesetResult& result, double seconds);

}  // namespace gs::app
