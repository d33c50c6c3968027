#include "app/application.hpp"

#include "app/commands.hpp"
#include "app/layout.hpp"
#include "app/options.hpp"
#include "encode_tileset.hpp"

#include <CLI/CLI.hpp>

#include "render/splat_renderer.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <exception>
#include <string>

#ifndef GS_VERSION
#define GS_VERSION "0.0.0"
#endif

namespace gs::app {

bool parseSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  if (x == std::string::npos) return false;
  auto parseSide = [](const char* b, const char* e, int& out) {
    auto [p, ec] = std::from_chars(b, e, out);
    return ec == std::errc() && p == e && out >= 1 && out <= 16384;
  };
  const char* s = text.data();
  return parseSide(s, s + x, width) && parseSide(s + x + 1, s + text.size(), height);
}

double viewportLod(const Options& options, std::size_t index) {
  if (options.lods.empty()) return options.lod;
  return options.lods[std::min(index, options.lods.size() - 1)];
}

bool parseSnapshotAt(const std::string& text, std::uint64_t& bytes, double& seconds) {
  bytes = 0;
  seconds = 0.0;
  if (text.empty()) return false;
  if (text.back() == 's') {
    const char* b = text.data();
    const char* e = b + text.size() - 1;
    auto [p, ec] = std::from_chars(b, e, seconds);
    return ec == std::errc() && p == e && seconds > 0.0 && seconds < 1e6;
  }
  std::uint64_t scale = 1;
  std::size_t n = text.size();
  if (text.back() == 'k' || text.back() == 'K') {
    scale = 1024;
    --n;
  } else if (text.back() == 'M') {
    scale = 1024 * 1024;
    --n;
  }
  std::uint64_t value = 0;
  auto [p, ec] = std::from_chars(text.data(), text.data() + n, value);
  if (ec != std::errc() || p != text.data() + n || value == 0 || value > (UINT64_MAX / scale))
    return false;
  bytes = value * scale;
  return true;
}

namespace {

constexpr const char* kDescription =
    "GhostSpace " GS_VERSION
    ": an extended VRML97 browser for remote visualization of large 3D data.\n"
    "Opens VRML97 worlds (.wrl, .wrl.gz, .wrz), X3D worlds (.x3dv, .x3d, .x3dz, .x3dvz) and\n"
    "QNV streams from files or http(s) URLs in a\n"
    "window, showing them while they arrive, or renders them headless.";

struct Parsed {
  Options options;
  int exitCode = -1;  // >= 0: stop with this code (help, version, usage error)
};

Parsed parseArguments(int argc, char** argv) {
  Parsed r;
  Options& o = r.options;
  CLI::App cli{kDescription, "ghostspace"};
  cli.set_version_flag("--version", std::string("ghostspace ") + GS_VERSION);
  cli.footer(
      "Examples:\n"
      "  ghostspace world.wrl                          open a window\n"
      "  ghostspace --snapshot out.png --size 640x480 world.wrl\n"
      "  ghostspace info world.wrl                     print what was read\n"
      "  ghostspace http://host/world.wrl               stream a world into a window\n"
      "  ghostspace --snapshot part.png --max-rate 1250000 --snapshot-at 2s http://host/head.qnv\n"
      "  ghostspace encode CThead.nhdr --fraction 0.091 -o head.qnv\n"
      "  ghostspace info head.qnv                      header, packets, magnitude histogram");
  std::string size;
  cli.add_option("--snapshot", o.snapshotPath,
                 "Render INPUT off-screen (no display needed) from its bound Viewpoint and "
                 "write a PNG to this path")
      ->type_name("OUT.png");
  cli.add_option("--size", size, "Image or window size in pixels, e.g. 800x600")->type_name("WxH");
  cli.add_option("--frames", o.frames, "Close the window after this many frames (testing)")
      ->check(CLI::NonNegativeNumber);
  std::string lodText;
  cli.add_option("--lod", lodText,
                 "Level of detail: the fraction of every QNV stream drawn, largest vectors "
                 "first (0 < F <= 1); a list F1,F2,... gives one per viewport")
      ->type_name("F[,F...]");
  std::vector<std::string> layoutNames, modeNames;
  for (const LayoutInfo& l : kLayouts) layoutNames.emplace_back(l.name);
  for (const render::RenderModeInfo& m : render::kRenderModes) modeNames.emplace_back(m.name);
  std::string layoutText(layoutName(o.layout)), modeText(render::renderModeName(o.mode));
  cli.add_option("--layout", layoutText,
                 "Viewports: 1x1 (default), 2x1 (two side by side) or 2x2; the INPUTs fill "
                 "them in order (one INPUT fills them all)")
      ->check(CLI::IsMember(layoutNames));
  cli.add_option("--mode", modeText,
                 "polygons (default), splats (polygons drawn as QNV splats) or outlines "
                 "(OutlineGroup outlines only)")
      ->check(CLI::IsMember(modeNames));
  std::string splatPathText = render::splatPathName(render::defaultSplatPath());
  cli.add_option("--splat-path", splatPathText,
                 "How splats are drawn: auto (default: cpu where GL is llvmpipe or softpipe, "
                 "else geometry), geometry (a geometry shader makes each patch), points (point "
                 "sprites) or cpu (a multi-threaded CPU rasterizer; render/README.md)")
      ->check(CLI::IsMember(std::vector<std::string>{"auto", "geometry", "points", "cpu"}));
  cli.add_option("--script", o.script,
                 "Window: run the UI actions of FILE between frames (layout, open, viewport, "
                 "lod, mode, wait-loaded, frames, screenshot, quit; see app/window_script.hpp)")
      ->type_name("FILE");
  cli.add_option("--frame-log", o.frameLog,
                 "Window: write one CSV line per frame (seconds, frame and work ms, resident "
                 "KiB, vectors and level of detail per viewport) to FILE")
      ->type_name("FILE");
  cli.add_flag("--new-instance", o.newInstance,
               "Open a window of its own even when one is running (by default the INPUTs go "
               "to the running window, each in a new viewport)");
  cli.add_flag("--fit", o.fit, "Frame the whole scene instead of using the bound Viewpoint");
  cli.add_option("--max-rate", o.maxRate,
                 "Deliver at most this many bytes per second per transfer (emulates a slow "
                 "link; files and URLs alike)")
      ->type_name("BYTES_PER_S")
      ->check(CLI::NonNegativeNumber);
  cli.add_option("--tileset-memory", o.tilesetMemoryMb,
                 "Megabytes of decoded vectors a QNV tileset keeps at most (default 512); "
                 "bricks far from every view are dropped beyond it (docs/tilesets.md)")
      ->type_name("MB")
      ->check(CLI::PositiveNumber);
  std::string snapshotAt;
  cli.add_option("--snapshot-at", snapshotAt,
                 "With --snapshot: render what arrived after this many bytes (e.g. 200000, "
                 "512k, 2M) or seconds (e.g. 2.5s) instead of waiting for the whole input")
      ->type_name("BYTES|Ts");
  cli.add_option("--stall-timeout", o.stallTimeout,
                 "Seconds without a byte after which a transfer fails (default 20)")
      ->type_name("S")
      ->check(CLI::Range(0.05, 3600.0));
  std::string timeText;
  cli.add_option("--time", timeText,
                 "SFTime (seconds since 1970) the world is loaded and shown at; T0:DT:N with "
                 "--snapshot writes N frames DT seconds apart (OUT-0000.png ...). Default: the "
                 "wall clock in a window, 0 for --snapshot")
      ->type_name("T|T0:DT:N");
  cli.add_option("--time-step", o.time.step,
                 "Fixed step of the event cascade between times, seconds (default 1/60)")
      ->type_name("S")
      ->check(CLI::PositiveNumber);
  cli.add_option("--trace-events", o.time.traceFile,
                 "Write every event as a JSON line (time, node, field, value) to FILE")
      ->type_name("FILE");
  bool noScripts = false;
  cli.add_flag("--no-scripts", noScripts, "Script nodes do not run");
  cli.add_option("--script-time-limit", o.time.scriptLimits.callSeconds,
                 "Seconds one Script call may run before the Script is stopped (default 0.5)")
      ->type_name("S")
      ->check(CLI::PositiveNumber);
  double scriptMegabytes = static_cast<double>(o.time.scriptLimits.heapBytes) / 1048576.0;
  cli.add_option("--script-memory-limit", scriptMegabytes,
                 "Megabytes one Script's heap may use before it is stopped (default 64)")
      ->type_name("MB")
      ->check(CLI::Range(1.0, 65536.0));
  bool noProgressBar = false;
  cli.add_flag("--no-progress", noProgressBar, "No progress bar on the terminal");
  cli.add_option("INPUT", o.inputs,
                 "Worlds to open, files or http(s):// URLs: VRML97 (.wrl, .wrl.gz, .wrz), X3D "
                 "(.x3dv, .x3d, .x3dz, .x3dvz), QNV "
                 "streams (.qnv), and local meshes (.ply, .obj, .gltf, .glb) or volumes "
                 "(.nrrd, .nhdr, .nii, .nii.gz)");

  CLI::App* info = cli.add_subcommand("info",
                                      "Print what was read from INPUT: node counts, "
                                      "triangles, bounding box, diagnostics, parse time");
  std::vector<std::string> infoInputs;
  info->add_option("INPUT", infoInputs, "VRML97 world or .qnv stream")->required();
  info->add_flag("--exit-zero", o.infoExitZero,
                 "Exit 0 when every INPUT was read, even when a world has errors (by default "
                 "a world with errors makes the exit status 1)");

  EncodeOptions& enc = o.encode;
  CLI::App* encode = cli.add_subcommand(
      "encode",
      "Encode INPUT as a QNV stream (docs/qnv-format.md): a VRML97 world, a mesh (.ply, .obj, "
      ".gltf, .glb) or a volume (.nrrd, .nhdr, .nii, .nii.gz, or raw with --raw-dims)");
  std::string encodeInput;
  encode->add_option("INPUT", encodeInput, "World, mesh or volume")->required();
  encode->add_option("-o,--output", enc.output, "The .qnv file to write")->type_name("OUT.qnv");
  addTilesetOptions(*encode, enc);  // encode_tileset.cpp
  auto* fraction = encode
                       ->add_option("--fraction", enc.fraction,
                                    "Keep the largest F of all triangles or voxels (0 < F <= 1)")
                       ->type_name("F");
  encode->add_option("--count", enc.count, "Keep the N largest vectors")
      ->type_name("N")
      ->excludes(fraction);
  encode
      ->add_option(
          "--packet-bytes", enc.packetBytes,
          "Record bytes per packet, a multiple of 8 (48 = the paper's ATM cell; default 1376 "
          "fits a 1400-byte datagram)")
      ->type_name("B");
  encode->add_flag("--compact", enc.compact,
                   "zstd-compress each packet (spatially sorted, delta-coded)");
  encode
      ->add_option("--coding", enc.coding,
                   "Packet coding: plain (64-bit records), compact (zstd), entropy (rANS, "
                   "smallest) or entropy-fast (rANS, fast layout; docs/qnv-format.md)")
      ->check(CLI::IsMember({"plain", "compact", "entropy", "entropy-fast"}))
      ->type_name("NAME");
  encode->add_option("--window", enc.valueWindow, "Volumes: keep voxels with values in LO..HI")
      ->type_name("LO:HI");
  encode->add_option("--magnitude", enc.magnitude,
                     "Magnitude quantization: log (default) or linear");
  encode->add_option("--raw-dims", enc.rawDims, "INPUT is raw voxels of this size")
      ->type_name("X,Y,Z");
  encode->add_option("--raw-type", enc.rawType, "Raw sample type: uint8 int16 float32 ...");
  encode->add_option("--raw-spacing", enc.rawSpacing, "Raw voxel spacing")->type_name("SX,SY,SZ");
  encode->add_flag("--raw-big-endian", enc.rawBigEndian, "Raw samples are big-endian");
  encode->add_option("--raw-skip", enc.rawHeaderBytes, "Bytes to skip before the raw samples");
  encode->add_flag("--outline", enc.outline,
                   "Write OUT as a VRML97 world of outline groups, outlines first "
                   "(docs/vrml-extensions.md) instead of a .qnv stream");
  encode
      ->add_option("--max-angle", enc.maxAngle,
                   "With --outline: largest angle in degrees between a triangle's normal and "
                   "its group's (default 30)")
      ->type_name("DEG")
      ->check(CLI::Range(0.0, 180.0));
  bool noProgress = false;
  encode->add_flag("--no-progress", noProgress, "No progress bar on the terminal");

  CLI::App* tileset = addTilesetCommand(cli, o.tilesetDir);  // encode_tileset.cpp

  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(cli.help().c_str(), stdout);
    r.exitCode = 0;
    return r;
  } catch (const CLI::CallForVersion&) {
    std::printf("ghostspace %s\n", GS_VERSION);
    r.exitCode = 0;
    return r;
  } catch (const CLI::ExtrasError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    r.exitCode = 2;
    return r;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "ghostspace: %s (see --help)\n", e.what());
    r.exitCode = 2;
    return r;
  }
  o.layout = layoutFromName(layoutText).value_or(Layout::single);  // checked by IsMember
  o.mode = render::renderModeFromName(modeText).value_or(render::RenderMode::polygons);
  if (render::SplatPath path; render::parseSplatPath(splatPathText.c_str(), path))
    render::setDefaultSplatPath(path);  // checked by IsMember
  if (!size.empty() && !parseSize(size, o.width, o.height)) {
    std::fprintf(stderr, "ghostspace: --size: expected WxH such as 800x600, got '%s'\n",
                 size.c_str());
    r.exitCode = 2;
    return r;
  }
  enc.progress = !noProgress;
  if (!lodText.empty()) {
    // "F" or "F1,F2,...": each 0 < F <= 1.
    std::size_t at = 0;
    for (;;) {
      const std::size_t comma = lodText.find(',', at);
      const std::string item = lodText.substr(at, comma == std::string::npos ? comma : comma - at);
      double f = 0.0;
      auto [p, ec] = std::from_chars(item.data(), item.data() + item.size(), f);
      if (item.empty() || ec != std::errc() || p != item.data() + item.size() || !(f > 0.0) ||
          f > 1.0) {
        std::fprintf(stderr,
                     "ghostspace: --lod: expected fractions 0 < F <= 1 such as 0.1 or "
                     "0.1,1, got '%s'\n",
                     lodText.c_str());
        r.exitCode = 2;
        return r;
      }
      o.lods.push_back(f);
      if (comma == std::string::npos) break;
      at = comma + 1;
    }
    o.lod = o.lods.front();
  }
  o.progress = !noProgressBar;
  o.time.scripts = !noScripts;
  o.time.scriptLimits.heapBytes = static_cast<std::size_t>(scriptMegabytes * 1048576.0);
  if (!timeText.empty() && !session::parseTimeOption(timeText, o.time)) {
    std::fprintf(stderr,
                 "ghostspace: --time: expected seconds T >= 0 or T0:DT:N (DT > 0, N >= 1), "
                 "got '%s'\n",
                 timeText.c_str());
    r.exitCode = 2;
    return r;
  }
  if (!snapshotAt.empty() && !parseSnapshotAt(snapshotAt, o.snapshotAtBytes, o.snapshotAtSeconds)) {
    std::fprintf(stderr,
                 "ghostspace: --snapshot-at: expected a byte count (200000, 512k, 2M) or "
                 "seconds (2.5s), got '%s'\n",
                 snapshotAt.c_str());
    r.exitCode = 2;
    return r;
  }
  if (encode->parsed()) {
    o.command = Command::encode;
    o.inputs = {encodeInput};
  } else if (tileset->parsed()) {
    o.command = Command::tilesetIndex;
  } else if (info->parsed()) {
    o.command = Command::info;
    o.inputs = infoInputs;
  } else if (!o.snapshotPath.empty()) {
    o.command = Command::snapshot;
    const std::size_t cells = static_cast<std::size_t>(layoutCells(o.layout));
    if (o.inputs.empty() || o.inputs.size() > cells) {
      std::fprintf(stderr,
                   "ghostspace: --snapshot needs 1 to %zu INPUTs for --layout %s, got %zu\n", cells,
                   std::string(layoutName(o.layout)).c_str(), o.inputs.size());
      r.exitCode = 2;
    }
  }
  return r;
}

}  // namespace

int run(int argc, char** argv) {
  Parsed p = parseArguments(argc, argv);
  if (p.exitCode >= 0) return p.exitCode;
  try {
    switch (p.options.command) {
      case Command::info:
        return runInfo(p.options);
      case Command::snapshot:
        return runSnapshot(p.options);
      case Command::window:
        return runWindow(p.options);
      case Command::encode:
        return runEncode(p.options);
      case Command::tilesetIndex:
        return runTilesetIndex(p.options);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  return 1;
}

}  // namespace gs::app
