// The three things ghostspace does; each returns a process exit code.
#pragma once

#include "app/options.hpp"
#include "net/loader.hpp"
#include "render/scene_renderer.hpp"
#include "session/tileset_stream.hpp"

#include <string>

namespace gs::app {

/// `ghostspace info INPUT...`: prints node counts by type, triangles, bounding box,
/// diagnostics and parse time to stdout, for scripts that validate worlds (as xmllint or
/// gltf-validator do). Returns 1 when an INPUT could not be read at all or a world has
/// errors (parser or renderer diagnostics of severity error; warnings do not count), 0
/// otherwise; with options.infoExitZero (--exit-zero) errors in a world that was read
/// give 0. A .qnv INPUT (formats::classifyFile) goes to runQnvInfo, a Gaussian splatting
/// scene to runGaussianInfo.
int runInfo(const Options& options);

/// `ghostspace info FILE.qnv`: the stream header, vector and packet counts, bytes per
/// vector, a magnitude histogram, and damaged or missing packets. 0 when the header was
/// readable (even with packets lost), 1 otherwise.
int runQnvInfo(const std::string& path);

/// `ghostspace info SCENE`: a 3D Gaussian splatting scene file (.ply, .compressed.ply,
/// .splat, .spz, SOG, a glTF capture, LAS; session::isGaussianSplatFile): its format,
/// splats, SH degree, colour space, bounds (the reader's axes: docs/splats.md, "Axes"), the range
/// of the splats' largest scale (metres), the mean opacity, bytes a splat and the read time; read a
/// batch at a time where the format allows (splats::openGaussianBatches). 0, or 1 with the reader's
/// error ("PATH: ...") on stderr when it cannot be read.
int runGaussianInfo(const std::string& path);

/// `ghostspace encode INPUT -o OUT.wrl --outline`: loads the world INPUT, writes
/// outline::writeOutlineWorld's text to OUT and prints groups, triangles, outline
/// vertices, input and output bytes and the outline prefix bytes on stdout. Diagnostics
/// of INPUT go to stderr. Returns the exit code: 0, 1 when INPUT cannot be read or OUT
/// written.
int runEncodeOutline(const Options& options);

/// `ghostspace encode INPUT -o OUT.qnv`: a VRML97 world, mesh (PLY, OBJ, glTF/GLB) or
/// volume (NRRD, NIfTI-1, raw) to a .qnv stream (docs/qnv-format.md). Prints what was
/// kept and the sizes; 0 on success, 1 with one line on stderr when the input cannot be
/// read or the output written, 2 on bad options.
int runEncode(const Options& options);

/// `ghostspace convert IN -o OUT`: reads the world IN (any encoding session::loadWorld
/// reads) and writes it to OUT in the encoding OUT's extension names (.wrl VRML97, .x3dv
/// X3D Classic VRML, .x3d X3D XML, .x3dj X3D JSON; vrml::writeScene, docs/x3d.md
/// "Conversion"). IN's diagnostics and what OUT's encoding cannot hold go to stderr, one
/// line each ("file:line:column: warning: ..."); one summary line goes to stdout. Returns
/// 0 when OUT was written and IN had no errors, 1 when IN cannot be read, has errors (OUT
/// is still written with what was read) or OUT cannot be written, 2 when OUT's extension
/// names no encoding.
int runConvert(const Options& options);

/// `ghostspace tileset index OUT/`: merges the shares an `encode --tileset OUT/ --bricks
/// I/N` run left under OUT/parts/ into the interior bricks and OUT/index.qnvt, then removes
/// OUT/parts (app/src/encode_tileset.cpp, docs/qnv-format.md "Tilesets"). 0 on success, 1
/// with one line on stderr when a share is missing, damaged or from another encode.
int runTilesetIndex(const Options& options);

/// `ghostspace --snapshot OUT.png [--size WxH] INPUT`: streams INPUT (a file or an
/// http(s) URL, docs/progressive-loading.md), renders off-screen through OSMesa from the
/// bound Viewpoint once everything asked for arrived (or at --snapshot-at) and writes a
/// PNG. 0 on success; 3 when the PNG shows an incomplete input (a transfer failed);
/// 1 with the reason on stderr when nothing can be shown or the image cannot be written.
int runSnapshot(const Options& options);

/// `ghostspace [INPUT...]`: the GLFW window with its Dear ImGui menu. Returns when the
/// window is closed; 1 when no window can be created (e.g. no display).
int runWindow(const Options& options);

/// The renderer options the command line asks for: --lod, --mode, and the application's
/// splat loader (session/splat_inputs.hpp).
render::SceneRendererOptions rendererOptions(const Options& options);

/// The tileset options the command line asks for: --tileset-memory.
session::TilesetOptions tilesetOptions(const Options& options);

/// The loader options the command line asks for: --max-rate, --snapshot-at BYTES.
net::LoaderOptions loaderOptions(const Options& options);

}  // namespace gs::app
