#include "app/application.hpp"

#include "app/commands.hpp"
#include "app/layout.hpp"
#include "app/options.hpp"
#include "encode_tileset.hpp"
#include "option_table.hpp"

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
    "Opens VRML97 worlds (.wrl, .wrl.gz, .wrz), X3D worlds (.x3dv, .x3d, .x3dj, .x3dz,\n"
    ".x3dvz), QNV streams and tilesets, meshes, volumes and Gaussian splatting scenes from\n"
    "files or http(s) URLs in a window, showing them while they arrive, or renders them\n"
    "headless.";

struct Parsed {
  Options options;
  int exitCode = -1;  // >= 0: stop with this code (help, version, usage error)
};

Parsed parseArguments(int argc, char** argv) {
  Parsed r;
  Arguments a;  // every option's value (option_table.cpp)
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
      "  ghostspace info head.qnv                      header, packets, magnitude histogram\n"
      "  ghostspace convert world.x3dv -o world.x3d    X3D Classic VRML to XML");
  registerOptions(OptionScope::main, cli, a);
  cli.add_option(
      "INPUT", a.options.inputs,
      "Worlds to open, files or http(s):// URLs: VRML97 (.wrl, .wrl.gz, .wrz), X3D "
      "(.x3dv, .x3d, .x3dj, .x3dz, .x3dvz), QNV streams (.qnv) and tilesets "
      "(index.qnvt or its folder), Gaussian splatting scenes (.ply, "
      ".compressed.ply, .splat, .spz, .sog, .glb), and local meshes (.ply, .obj, "
      ".gltf, .glb) or volumes (.nrrd, .nhdr, .nii, .nii.gz; DICOM: .dcm, a series folder "
      "or a DICOMDIR; TIFF and OME-TIFF: .tif, .tiff, or a folder of slices; OpenVDB: .vdb)");

  CLI::App* info = cli.add_subcommand("info",
                                      "Print what was read from INPUT: node counts, "
                                      "triangles, bounding box, diagnostics, parse time");
  std::vector<std::string> infoInputs;
  info->add_option("INPUT", infoInputs, "VRML97 world or .qnv stream")->required();
  registerOptions(OptionScope::info, *info, a);

  CLI::App* encode = cli.add_subcommand(
      "encode",
      "Encode INPUT as a QNV stream (docs/qnv-format.md): a VRML97 world, a mesh (.ply, .obj, "
      ".gltf, .glb) or a volume (.nrrd, .nhdr, .nii, .nii.gz, DICOM .dcm, series folder or "
      "DICOMDIR, TIFF .tif/.tiff or a folder of slices, OpenVDB .vdb, or raw with --raw-dims)");
  std::string encodeInput;
  encode->add_option("INPUT", encodeInput, "World, mesh or volume")->required();
  registerOptions(OptionScope::encode, *encode, a);

  CLI::App* convert = cli.add_subcommand(
      "convert",
      "Write the world INPUT in another encoding: VRML97 (.wrl), X3D Classic VRML (.x3dv), "
      "XML (.x3d) or JSON (.x3dj), chosen by OUT's extension");
  std::string convertInput;
  convert->add_option("INPUT", convertInput, "World to read")->required();
  registerOptions(OptionScope::convert, *convert, a);
  convert->get_option("--output")->required();

  Options& o = a.options;
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
  if (a.helpMarkdown) {
    std::fputs(optionsMarkdown().c_str(), stdout);
    r.exitCode = 0;
    return r;
  }
  o.layout = layoutFromName(a.layout).value_or(Layout::single);  // checked by IsMember
  o.mode = scene::renderModeFromName(a.mode).value_or(scene::RenderMode::polygons);
  // The names below were checked by IsMember.
  render::parseTextureQuality(a.textureQuality, o.textureQuality);
  render::parseShadingOption(a.shading, o.shading);
  if (render::SplatPath path; render::parseSplatPath(a.splatPath.c_str(), path))
    o.splatPath = path;  // checked by IsMember
  if (!a.size.empty() && !parseSize(a.size, o.width, o.height)) {
    std::fprintf(stderr, "ghostspace: --size: expected WxH such as 800x600, got '%s'\n",
                 a.size.c_str());
    r.exitCode = 2;
    return r;
  }
  o.encode.progress = !a.encodeNoProgress;
  if (cli.count("--lod") > 0 && !a.lod.empty()) {
    const std::string& lodText = a.lod;
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
  o.progress = !a.noProgress;
  o.time.scripts = !a.noScripts;
  o.time.shading = o.shading;  // the Shading option a world's Scripts start from
  o.time.scriptLimits.heapBytes = static_cast<std::size_t>(a.scriptMegabytes * 1048576.0);
  if (!a.time.empty() && !session::parseTimeOption(a.time, o.time)) {
    std::fprintf(stderr,
                 "ghostspace: --time: expected seconds T >= 0 or T0:DT:N (DT > 0, N >= 1), "
                 "got '%s'\n",
                 a.time.c_str());
    r.exitCode = 2;
    return r;
  }
  if (o.time.load >= 0.0 && o.time.load > o.time.start) {
    std::fprintf(stderr,
                 "ghostspace: --load-time %g is after --time's %g: a world is shown "
                 "after it loads\n",
                 o.time.load, o.time.start);
    r.exitCode = 2;
    return r;
  }
  if (!a.snapshotAt.empty() &&
      !parseSnapshotAt(a.snapshotAt, o.snapshotAtBytes, o.snapshotAtSeconds)) {
    std::fprintf(stderr,
                 "ghostspace: --snapshot-at: expected a byte count (200000, 512k, 2M) or "
                 "seconds (2.5s), got '%s'\n",
                 a.snapshotAt.c_str());
    r.exitCode = 2;
    return r;
  }
  if (encode->parsed()) {
    o.command = Command::encode;
    o.inputs = {encodeInput};
  } else if (convert->parsed()) {
    o.command = Command::convert;
    o.inputs = {convertInput};
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
  r.options = std::move(o);
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
      case Command::convert:
        return runConvert(p.options);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  return 1;
}

}  // namespace gs::app
