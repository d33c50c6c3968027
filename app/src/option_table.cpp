#include "option_table.hpp"

#include <cstdio>
#include <string_view>
#include <type_traits>
#include <vector>

#include "app/layout.hpp"
#include "render/splat_renderer.hpp"
#include "scene/traversal.hpp"

namespace gs::app {

Arguments::Arguments() {
  size = std::to_string(options.width) + "x" + std::to_string(options.height);
  char text[32];
  std::snprintf(text, sizeof text, "%g", options.lod);
  lod = text;
  layout = std::string(layoutName(options.layout));
  mode = scene::renderModeName(options.mode);
  splatPath = render::splatPathName(render::SplatPath::automatic);
  scriptMegabytes = static_cast<double>(options.time.scriptLimits.heapBytes) / 1048576.0;
}

namespace {

// A Field: the member of Arguments `expression` names, of type `type`.
#define GS_FIELD(type, expression) Field(+[](Arguments& a) -> type& { return a.expression; })

std::vector<std::string> layoutNames() {
  std::vector<std::string> names;
  for (const LayoutInfo& l : kLayouts) names.emplace_back(l.name);
  return names;
}

std::vector<std::string> modeNames() {
  std::vector<std::string> names;
  for (const scene::RenderModeInfo& m : scene::kRenderModes) names.emplace_back(m.name);
  return names;
}

const std::vector<OptionSpec>& table() {
  using enum OptionScope;
  static const std::vector<OptionSpec> rows = {
      {.scope = main,
       .names = "--snapshot",
       .valueName = "OUT.png",
       .field = GS_FIELD(std::string, options.snapshotPath),
       .help = "Render INPUT off-screen (no display needed) from its bound Viewpoint and "
               "write a PNG to this path",
       .more = "It draws once everything it asks for arrived, from the VRML97 default "
               "viewpoint (0 0 10, field of view 0.785398 rad) when the world has none. Exit code "
               "0 when the "
               "PNG was written; 3 when it was written from an incomplete input (a transfer "
               "failed: the message names the URL and why); 1 with an error on stderr when "
               "nothing could be shown; 2 on bad options. Diagnostics about the world are "
               "printed to stderr, one per line, and the rest of the world still renders."},
      {.scope = main,
       .names = "--size",
       .valueName = "WxH",
       .field = GS_FIELD(std::string, size),
       .help = "Image or window size in pixels"},
      {.scope = main,
       .names = "--layout",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, layout),
       .help = "Viewports: 1x1, 2x1 (two side by side) or 2x2; the INPUTs fill them in order "
               "(one INPUT fills them all)",
       .more = "Works in the window and with `--snapshot`.",
       .check = CLI::IsMember(layoutNames())},
      {.scope = main,
       .names = "--lod",
       .valueName = "F[,F...]",
       .field = GS_FIELD(std::string, lod),
       .help = "Level of detail: the fraction of every QNV stream drawn, largest vectors "
               "first (0 < F <= 1); a list F1,F2,... gives one per viewport",
       .more = "The last one repeats. Paper section 2: every prefix is the best picture of "
               "its size."},
      {.scope = main,
       .names = "--mode",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, mode),
       .help = "polygons, splats (polygons drawn as QNV splats) or outlines (OutlineGroup "
               "outlines only)",
       .more = "Splats: the triangles go through the surface encoder; outlines: "
               "docs/vrml-extensions.md.",
       .check = CLI::IsMember(modeNames())},
      {.scope = main,
       .names = "--splat-path",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, splatPath),
       .help = "How splats (3D Gaussians and QNV vectors, one model: docs/splats.md) are "
               "drawn: auto (cpu where GL is llvmpipe or softpipe, else gpu), gpu (instanced "
               "quads, depth order by a radix sort in compute shaders, OpenGL 4.3), geometry "
               "(instanced quads, depth order sorted on the CPU; points is the same) or cpu (a "
               "multi-threaded CPU rasterizer; docs/rendering.md)",
       .more = "The cpu path draws its image as one quad, about 3x faster on llvmpipe; every "
               "path gives the same picture, measured in docs/splats.md.",
       .check =
           CLI::IsMember(std::vector<std::string>{"auto", "gpu", "geometry", "points", "cpu"})},
      {.scope = main,
       .names = "--samples",
       .valueName = "N",
       .field = GS_FIELD(int, options.samples),
       .help = "Anti-aliasing: N samples per pixel (multisampling; 0 or 1: none). Default 4 "
               "in the window, 1 with --snapshot",
       .more = "On llvmpipe a frame of 4 samples takes 1.3-1.9x as long, so snapshots (tests, "
               "batch work) are not anti-aliased unless asked; `--samples 4` gives the window's "
               "picture "
               "(docs/rendering.md, \"Anti-aliasing\").",
       .shownDefault = "",
       .check = CLI::Range(0, 16)},
      {.scope = main,
       .names = "--texture-quality",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, textureQuality),
       .help = "The X3D browser option TextureQuality: how textures without TextureProperties "
               "are filtered when minified. high: trilinear mipmaps (castle-model-viewer's); "
               "medium: the nearest texels of the two nearest mipmaps (X_ITE's default); low: "
               "bilinear, no mipmaps",
       .more = "docs/rendering.md, \"Browser options\".",
       .check = CLI::IsMember(std::vector<std::string>{"low", "medium", "high"}, CLI::ignore_case)},
      {.scope = main,
       .names = "--shading",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, shading),
       .help = "The X3D browser option Shading that worlds start with: phong; gouraud (in "
               "VRML97 and X3D 3 worlds a Material shape's texture multiplies the lit colour, "
               "X_ITE's default; X3D 4 worlds stay phong, clause 17.2.2.4); flat (each "
               "triangle's own normal); wireframe or point (polygons as edges or vertices)",
       .more = "Every mode lights every pixel, as X_ITE's GOURAUD does; a world's Scripts "
               "may change it with Browser.setBrowserOption(\"Shading\", ...) "
               "(docs/rendering.md, \"Browser options\").",
       .check = CLI::IsMember(
           std::vector<std::string>{"phong", "gouraud", "flat", "wireframe", "point", "pointset"},
           CLI::ignore_case)},
      {.scope = main,
       .names = "--fit",
       .valueName = "",
       .field = GS_FIELD(bool, options.fit),
       .help = "Frame the whole scene instead of using the bound Viewpoint",
       .more = "Streams, meshes and volumes have no Viewpoint and are always framed."},
      {.scope = main,
       .names = "--castle-camera",
       .valueName = "",
       .field = GS_FIELD(bool, options.castleCamera),
       .help = "With --snapshot: start a world without a Viewpoint where castle-model-viewer "
               "starts it instead of at VRML97's default viewpoint",
       .more = "Looking along -Z from the box centre's X and Y, at the box's largest Z plus "
               "twice its average side (scene::wholeSceneCamera). glTF assets without a camera "
               "always start there; tests/bench/x3d_vs_castle.sh compares with it."},
      {.scope = main,
       .names = "--frames",
       .valueName = "N",
       .field = GS_FIELD(int, options.frames),
       .help = "Close the window after this many frames (0: never; testing)",
       .check = CLI::NonNegativeNumber},
      {.scope = main,
       .names = "--script",
       .valueName = "FILE",
       .field = GS_FIELD(std::string, options.script),
       .help = "Window: run the UI actions of FILE between frames (layout, open, viewport, "
               "lod, mode, wait-loaded, frames, screenshot, quit; see app/window_script.hpp)",
       .more = "One per line; also `viewpoint N`, `auto-lod on|off`, `frame-target MS`, "
               "`budget N`, `wait-viewports N`, `screenshot-viewport OUT.png`, `status "
               "OUT.txt`, `frame-stats OUT.txt` (frame times, movie frames shown); "
               "interaction: `time T`, `advance S` (the clock becomes virtual), `pointer X "
               "Y`, `press`, `release`, `click X Y`, `drag X1 Y1 X2 Y2 [STEPS]`, `key K`, "
               "`key-down K`, `key-up K`, `type TEXT` (X3D KeySensor, StringSensor); "
               "navigation: `navigation EXAMINE|WALK|FLY`, `walk F R U [STEPS]`, `back`, "
               "`forward`, `camera OUT.txt`. A bad line is an error naming it (exit code 2)."},
      {.scope = main,
       .names = "--frame-log",
       .valueName = "FILE",
       .field = GS_FIELD(std::string, options.frameLog),
       .help = "Write one CSV line per frame (seconds, frame and work ms, resident KiB, "
               "splats drawn and level of detail per viewport) to FILE: every frame of the "
               "window, and with --snapshot every frame written (one per --time frame)",
       .more = "The frame time includes the wait for events, the work time does not "
               "(app/include/app/frame_log.hpp; the soak test uses it, docs/soak.md)."},
      {.scope = main,
       .names = "--new-instance",
       .valueName = "",
       .field = GS_FIELD(bool, options.newInstance),
       .help = "Open a window of its own even when one is running (by default the INPUTs go "
               "to the running window, each in a new viewport)",
       .more = "The running window is found through a socket in `$XDG_RUNTIME_DIR`; the "
               "launch that handed its INPUTs over exits."},
      {.scope = main,
       .names = "--max-rate",
       .valueName = "BYTES_PER_S",
       .field = GS_FIELD(double, options.maxRate),
       .help = "Deliver at most this many bytes per second per transfer (0: no limit; "
               "emulates a slow link; files and URLs alike)",
       .more = "docs/progressive-loading.md.",
       .check = CLI::NonNegativeNumber},
      {.scope = main,
       .names = "--snapshot-at",
       .valueName = "BYTES|Ts",
       .field = GS_FIELD(std::string, snapshotAt),
       .help = "With --snapshot: render what arrived after this many bytes (e.g. 200000, "
               "512k, 2M) or seconds (e.g. 2.5s) instead of waiting for the whole input"},
      {.scope = main,
       .names = "--stall-timeout",
       .valueName = "S",
       .field = GS_FIELD(double, options.stallTimeout),
       .help = "Seconds without a byte after which a transfer fails",
       .check = CLI::Range(0.05, 3600.0)},
      {.scope = main,
       .names = "--tileset-memory",
       .valueName = "MB",
       .field = GS_FIELD(double, options.tilesetMemoryMb),
       .help = "Megabytes of decoded vectors a QNV tileset keeps at most; bricks far from "
               "every view are dropped beyond it (docs/tilesets.md)",
       .more = "A Gaussian tileset's splat counts its decoded size and its share of the "
               "level-of-detail tree drawn from them (about 0.4 of it again).",
       .check = CLI::PositiveNumber},
      {.scope = main,
       .names = "--no-progress",
       .valueName = "",
       .field = GS_FIELD(bool, noProgress),
       .help = "No progress bar on the terminal"},
      {.scope = main,
       .names = "--time",
       .valueName = "T|T0:DT:N",
       .field = GS_FIELD(std::string, time),
       .help = "SFTime (seconds since 1970) the world is loaded and shown at; T0:DT:N with "
               "--snapshot writes N frames DT seconds apart (OUT-0000.png ...). Default: the "
               "wall clock in a window, 0 for --snapshot",
       .more = "In the window the clock starts at T, then follows the wall clock. The same "
               "command gives the same pixels on any machine (docs/runtime.md)."},
      {.scope = main,
       .names = "--load-time",
       .valueName = "S",
       .field = GS_FIELD(double, options.time.load),
       .help = "With --snapshot: SFTime the world is loaded at, then run to --time's T at "
               "--time-step (S <= T). Default: loaded at T",
       .more = "What has moved since the load shows at T: particles, followers (X_ITE's "
               "pictures at T are of a world loaded T seconds before: docs/x3d.md).",
       .shownDefault = "T",
       .check = CLI::NonNegativeNumber},
      {.scope = main,
       .names = "--time-step",
       .valueName = "S",
       .field = GS_FIELD(double, options.time.step),
       .help = "Fixed step of the event cascade between times, seconds",
       .shownDefault = "1/60",  // the field holds 0.016666...
       .check = CLI::PositiveNumber},
      {.scope = main,
       .names = "--trace-events",
       .valueName = "FILE",
       .field = GS_FIELD(std::string, options.time.traceFile),
       .help = "Write every event as a JSON line (time, node, field, value) to FILE",
       .more = "ROUTEs, sensors and Scripts alike: "
               "`{\"time\":1.320,\"node\":\"TS\",\"field\":\"fraction_changed\",\"value\":"
               "\"0.33\"}`."},
      {.scope = main,
       .names = "--no-scripts",
       .valueName = "",
       .field = GS_FIELD(bool, noScripts),
       .help = "Script nodes do not run",
       .more = "A warning names each."},
      {.scope = main,
       .names = "--script-time-limit",
       .valueName = "S",
       .field = GS_FIELD(double, options.time.scriptLimits.callSeconds),
       .help = "Seconds one Script call may run before the Script is stopped",
       .more = "A call (initialize, an eventIn ...) running longer stops that Script with a "
               "diagnostic naming its file:line; the world goes on (docs/runtime-scripts.md, "
               "docs/limits.md).",
       .check = CLI::PositiveNumber},
      {.scope = main,
       .names = "--script-memory-limit",
       .valueName = "MB",
       .field = GS_FIELD(double, scriptMegabytes),
       .help = "Megabytes one Script's heap may use before it is stopped",
       .more = "It is stopped as with `--script-time-limit` (docs/limits.md).",
       .check = CLI::Range(1.0, 65536.0)},
      {.scope = main,
       .names = "--help-markdown",
       .valueName = "",
       .field = GS_FIELD(bool, helpMarkdown),
       .help = "Print this table of options as Markdown (README.md's) and exit"},
      {.scope = info,
       .names = "--exit-zero",
       .valueName = "",
       .field = GS_FIELD(bool, options.infoExitZero),
       .help = "Exit 0 when every INPUT was read, even when a world has errors (by default "
               "a world with errors makes the exit status 1)"},
      {.scope = encode,
       .names = "-o,--output",
       .valueName = "OUT.qnv",
       .field = GS_FIELD(std::string, options.encode.output),
       .help = "The .qnv file to write",
       .more = "With `--outline`: the VRML97 world of outline groups."},
      {.scope = encode,
       .names = "--fraction",
       .valueName = "F",
       .field = GS_FIELD(double, options.encode.fraction),
       .help = "Keep the largest F of all triangles or voxels (0 < F <= 1)",
       .more = "The paper's figure 2 uses 1.2%, 3.5% and 9.1% of CThead."},
      {.scope = encode,
       .names = "--count",
       .valueName = "N",
       .field = GS_FIELD(std::uint64_t, options.encode.count),
       .help = "Keep the N largest vectors (0: as --fraction says)",
       .excludes = "--fraction"},
      {.scope = encode,
       .names = "--packet-bytes",
       .valueName = "B",
       .field = GS_FIELD(unsigned, options.encode.packetBytes),
       .help = "Record bytes per packet, a multiple of 8 (48 = the paper's ATM cell; 1376 "
               "fits a 1400-byte datagram)"},
      {.scope = encode,
       .names = "--compact",
       .valueName = "",
       .field = GS_FIELD(bool, options.encode.compact),
       .help = "zstd-compress each packet (spatially sorted, delta-coded)",
       .more = "Each packet on its own."},
      {.scope = encode,
       .names = "--coding",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, options.encode.coding),
       .help = "Packet coding: plain (64-bit records), compact (zstd), entropy (rANS, "
               "smallest) or entropy-fast (rANS, fast layout; docs/qnv-format.md)",
       .more = "Wins over `--compact`. `entropy` codes each packet with small rANS models and "
               "puts a stream model (occupied blocks, their directions, shared tables) in the "
               "header when that saves bytes (CThead's top 9.1%: 31.5 bits per vector in 16 "
               "KiB packets against 48 for `--compact` and 64 plain; docs/qnv-format.md, "
               "\"Compact coding\" and \"Stream model\").",
       .check = CLI::IsMember({"plain", "compact", "entropy", "entropy-fast"})},
      {.scope = encode,
       .names = "--window",
       .valueName = "LO:HI",
       .field = GS_FIELD(std::string, options.encode.valueWindow),
       .help = "Volumes: keep voxels with values in LO..HI",
       .more = "The window (e.g. bone) becomes the transfer function's domain."},
      {.scope = encode,
       .names = "--magnitude",
       .valueName = "NAME",
       .field = GS_FIELD(std::string, options.encode.magnitude),
       .help = "Magnitude quantization: log or linear"},
      {.scope = encode,
       .names = "--magnitude-bits",
       .valueName = "N",
       .field = GS_FIELD(int, options.encode.magnitudeBits),
       .help = "Keep the top N of A's 15 bits (1..15; 15: exact). Lossy; smaller entropy streams",
       .more = "Each magnitude code is rounded to the middle of its cell of 2^(15-N) codes, "
               "records of one code are ordered by position, and entropy packets send the low "
               "bits they share once. 7 bits: magnitudes within 1% on CThead's top 9.1% (31.5 "
               "-> 23.3 bits per vector in 16 KiB packets), 2.5% on the bunny (29.2 -> 21.1); "
               "the whole picture unchanged (docs/qnv-format.md, \"Shared low bits\"). "
               "Streams only, not --tileset.",
       .check = CLI::Range(1, 15)},
      {.scope = encode,
       .names = "--sh-bits",
       .valueName = "N",
       .field = GS_FIELD(int, options.encode.shBits),
       .help = "Gaussian splatting scenes: keep the top N of the 5 bits of each degree-1 SH "
               "code (1..5; 5: all). Lossy; smaller streams",
       .more = "Each bit dropped doubles the SH step (5 bits: 1/16); degree 2 and 3 codes "
               "(4 bits, step 1/8) drop as many, keeping one; a value halfway goes towards 0. "
               "Every reader reads the stream. Streams and tilesets of Gaussian scenes only.",
       .check = CLI::Range(1, 5)},
      {.scope = encode,
       .names = "--sh-full",
       .valueName = "F",
       .field = GS_FIELD(double, options.encode.shFull),
       .help = "With --sh-bits: the most important F of the splats (0..1, the stream's or "
               "each brick's first) keep every SH bit",
       .more = "CThead's capture at --sh-bits 4: 12.2 bytes per splat, 41.0 dB from the "
               "source's picture; with --sh-full 0.4, 15.3 and 47.0 dB; all bits, 19.9 and "
               "54.2 dB; its SOG, 19.0 and 40.8 dB (docs/splats.md, \"Bytes and pictures\").",
       .check = CLI::Range(0.0, 1.0)},
      {.scope = encode,
       .names = "--raw-dims",
       .valueName = "X,Y,Z",
       .field = GS_FIELD(std::string, options.encode.rawDims),
       .help = "INPUT is raw voxels of this size",
       .more = "E.g. `--raw-dims 256,256,113 --raw-type int16 --raw-big-endian "
               "--raw-spacing 1,1,2`."},
      {.scope = encode,
       .names = "--raw-type",
       .valueName = "TYPE",
       .field = GS_FIELD(std::string, options.encode.rawType),
       .help = "Raw sample type: uint8 int16 float32 ..."},
      {.scope = encode,
       .names = "--raw-spacing",
       .valueName = "SX,SY,SZ",
       .field = GS_FIELD(std::string, options.encode.rawSpacing),
       .help = "Raw voxel spacing"},
      {.scope = encode,
       .names = "--raw-big-endian",
       .valueName = "",
       .field = GS_FIELD(bool, options.encode.rawBigEndian),
       .help = "Raw samples are big-endian"},
      {.scope = encode,
       .names = "--raw-skip",
       .valueName = "BYTES",
       .field = GS_FIELD(std::uint64_t, options.encode.rawHeaderBytes),
       .help = "Bytes to skip before the raw samples"},
      {.scope = encode,
       .names = "--no-progress",
       .valueName = "",
       .field = GS_FIELD(bool, encodeNoProgress),
       .help = "No progress bar on the terminal",
       .more = "Without it, one is drawn on stderr when it is a terminal."},
      {.scope = encode,
       .names = "--outline",
       .valueName = "",
       .field = GS_FIELD(bool, options.encode.outline),
       .help = "Write OUT as a VRML97 world of outline groups, outlines first "
               "(docs/vrml-extensions.md) instead of a .qnv stream"},
      {.scope = encode,
       .names = "--max-angle",
       .valueName = "DEG",
       .field = GS_FIELD(double, options.encode.maxAngle),
       .help = "With --outline: largest angle in degrees between a triangle's normal and "
               "its group's",
       .check = CLI::Range(0.0, 180.0)},
      {.scope = encode,
       .names = "--tileset",
       .valueName = "OUT/",
       .field = GS_FIELD(std::string, options.encode.tileset),
       .help = "Write a tileset folder (index.qnvt and bricks/, docs/qnv-format.md "
               "\"Tilesets\") instead of one stream",
       .more = "One brick per octree node, `OUT/bricks/L/X_Y_Z.qnv`, each an ordinary stream "
               "sorted largest first. `--fraction`, `--count`, `--window`, `--coding` and "
               "`--packet-bytes` mean what they mean for a stream. A Gaussian splatting "
               "scene's bricks are Gaussian streams, importance first (the scene is read whole) "
               "(docs/tilesets.md, \"Gaussian tilesets\")."},
      {.scope = encode,
       .names = "--brick-voxels",
       .valueName = "B",
       .field = GS_FIELD(unsigned, options.encode.brickVoxels),
       .help = "Tilesets of volumes: leaf bricks of B voxels per side",
       .check = CLI::Range(1u, 1u << 20)},
      {.scope = encode,
       .names = "--brick-vectors",
       .valueName = "K",
       .field = GS_FIELD(std::uint64_t, options.encode.brickVectors),
       .help = "Tilesets: vectors (or splats) an octree node aims at",
       .more = "For surfaces and splat scenes also the leaf size that sets the depth. Not "
               "given, 16384; a Gaussian splatting scene of 16,385 to 131,072 splats gets the "
               "K that makes its octree 2 deep, so that its level-1 nodes have merged bricks "
               "(docs/tilesets.md, \"Gaussian tilesets\").",
       .shownDefault = "16384",
       .check = CLI::Range(std::uint64_t{1}, std::uint64_t{1} << 32)},
      {.scope = encode,
       .names = "--merged-cells",
       .valueName = "R",
       .field = GS_FIELD(unsigned, options.encode.mergedCells),
       .help = "Tilesets: merged levels of R^3 cells per interior node (0: none)",
       .more = "Each interior node of the top levels (8^L R^3 <= 2^18 cells; of a Gaussian "
               "splatting scene every interior node) gets `OUT/merged/L/X_Y_Z.qnv`, a Gaussian "
               "stream of its region merged cell by cell (coverage kept), which a far view "
               "draws instead of the region's vectors (docs/tilesets.md, \"Merged levels\"). "
               "Not given, a "
               "Gaussian splatting scene gets 32 where the root's 32^3 cells are at most one "
               "per 8 splats (docs/tilesets.md, \"Gaussian tilesets\").",
       .shownDefault = "16",
       .check = CLI::IsMember(std::vector<unsigned>{0, 2, 4, 8, 16, 32, 64, 128})},
      {.scope = encode,
       .names = "--memory",
       .valueName = "MB",
       .field = GS_FIELD(double, options.encode.memoryMB),
       .help = "Tilesets of volumes, PLY meshes and Gaussian splatting scenes: encode out "
               "of core in about MB mebibytes (fractions allowed; 0: in memory; "
               "docs/out-of-core.md)",
       .more = "Volumes slab by slab, meshes triangle by triangle (bricked by centroid), "
               "Gaussian scenes (binary and compressed PLY, .splat, SPZ, SOG, glTF) a "
               "batch of splats at a time, "
               "spilling to `OUT/parts/I-of-N/` past it; the files are the in-memory "
               "encode's byte for byte (docs/out-of-core.md, \"Tileset encoding\", "
               "\"Meshes\" and \"Gaussian splatting scenes\"). Volumes, meshes and "
               "scenes may then be larger than memory, and `INPUT` "
               "may also be a folder or `%04d` pattern of PNG/TIFF slices or a multi-file "
               "NRRD.",
       .check = CLI::Range(0.001, 1048576.0 * 1024.0)},
      {.scope = encode,
       .names = "--threads",
       .valueName = "N",
       .field = GS_FIELD(unsigned, options.encode.threads),
       .help = "Out-of-core and Gaussian tileset encodes: worker threads (0: every core)",
       .check = CLI::Range(1u, 256u)},
      {.scope = encode,
       .names = "--bricks",
       .valueName = "I/N",
       .field = GS_FIELD(std::string, options.encode.bricks),
       .help = "Tilesets: write only share I of N (0 <= I < N) of a split encode; "
               "`ghostspace tileset index OUT/` merges the shares",
       .more = "A share is the leaf bricks of the I-th contiguous range of leaves and "
               "`OUT/parts/I-of-N/`; run the shares anywhere (a SLURM array, Kubernetes "
               "Jobs, GNU parallel); the merge writes the interior bricks and `index.qnvt`, "
               "byte-identical to an unsplit run. Each share of a Gaussian splatting scene "
               "reads the whole scene, and share 0 writes the interior and merged bricks."},
      {.scope = convert,
       .names = "-o,--output",
       .valueName = "OUT",
       .field = GS_FIELD(std::string, options.convertOutput),
       .help = "The world to write: .wrl (VRML97), .x3dv (X3D Classic VRML), .x3d (X3D XML) "
               "or .x3dj (X3D JSON), by its extension",
       .more = "DEF names, PROTOs, ROUTEs, IMPORT / EXPORT and the X3D header are kept where "
               "the encoding has them; what it cannot hold (an X3D node in a .wrl, a UNIT "
               "statement) is a warning on stderr (docs/x3d.md, \"Conversion\")."},
      {.scope = builtIn,
       .names = "--help",
       .valueName = "",
       .field = GS_FIELD(bool, helpMarkdown),
       .help = "Print the options and exit (also after `info`, `encode` and `convert`)"},
      {.scope = builtIn,
       .names = "--version",
       .valueName = "",
       .field = GS_FIELD(bool, helpMarkdown),
       .help = "Print the version and exit",
       .more = "An unknown option is an error that names it (exit code 2)."},
  };
  return rows;
}

#undef GS_FIELD

CLI::Option* add(CLI::App& app, const OptionSpec& spec, Arguments& arguments) {
  CLI::Option* option = std::visit(
      [&](auto get) -> CLI::Option* {
        auto& value = get(arguments);
        using T = std::remove_reference_t<decltype(value)>;
        if constexpr (std::is_same_v<T, bool>)
          return app.add_flag(spec.names, value, spec.help);
        else
          return app.add_option(spec.names, value, spec.help)->capture_default_str();
      },
      spec.field);
  if (*spec.valueName) option->type_name(spec.valueName);
  if (spec.shownDefault) option->default_str(spec.shownDefault);
  if (spec.check) option->check(*spec.check);
  if (spec.excludes) option->excludes(app.get_option(spec.excludes));
  return option;
}

/// `text` with `|` escaped for a Markdown table cell.
std::string cell(std::string_view text) {
  std::string out;
  for (char c : text) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

}  // namespace

std::span<const OptionSpec> optionTable() {
  return table();
}

void registerOptions(OptionScope scope, CLI::App& app, Arguments& arguments) {
  for (const OptionSpec& spec : table())
    if (spec.scope == scope) add(app, spec, arguments);
}

std::string optionsMarkdown() {
  using enum OptionScope;
  Arguments arguments;
  std::string out = "| option | default | meaning |\n|---|---|---|\n";
  for (OptionScope scope : {main, info, encode, convert, builtIn}) {
    CLI::App app;  // what --help shows as each default
    if (scope != builtIn) registerOptions(scope, app, arguments);
    for (const OptionSpec& spec : table()) {
      if (spec.scope != scope) continue;
      std::string name = scope == info      ? "info "
                         : scope == encode  ? "encode "
                         : scope == convert ? "convert "
                                            : "";
      name += spec.names;
      if (const auto comma = name.find(','); comma != std::string::npos)
        name.insert(comma + 1, " ");
      if (*spec.valueName) name += std::string(" ") + spec.valueName;
      std::string shown;
      if (scope != builtIn) {
        const std::string names(spec.names);
        shown = app.get_option(names.substr(names.rfind(',') + 1))->get_default_str();
      }
      std::string meaning = spec.help;
      meaning += *spec.more ? std::string(". ") + spec.more : std::string(".");
      out += "| `" + cell(name) + "` | " + (shown.empty() ? "" : "`" + cell(shown) + "`") + " | " +
             cell(meaning) + " |\n";
    }
  }
  return out;
}

}  // namespace gs::app
