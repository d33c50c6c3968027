// The ghostspace command line (see README.md, "Command line"): what the options fill.
// Each option is declared once, in app/src/option_table.cpp.
#pragma once

#include "session/world_runtime.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "app/layout.hpp"
#include "render/browser_options.hpp"
#include "render/splat_renderer.hpp"
#include "scene/traversal.hpp"

namespace gs::app {

enum class Command { window, snapshot, info, encode, tilesetIndex, convert };

/// `ghostspace encode` (README.md, "Encoding QNV streams").
struct EncodeOptions {
  std::string output;                // -o OUT.qnv
  double fraction = 1.0;             // --fraction F: keep the largest F of all elements
  std::uint64_t count = 0;           // --count N: keep the N largest (wins over F)
  std::uint32_t packetBytes = 1376;  // --packet-bytes B: record bytes per packet
  bool compact = false;              // --compact: zstd-compressed packets
  std::string coding;       // --coding plain|compact|entropy|entropy-fast (wins over --compact)
  std::string valueWindow;  // --window LO:HI: volume values kept
  std::string magnitude = "log";     // --magnitude log|linear
  int magnitudeBits = 15;            // --magnitude-bits N: A codes rounded to N bits (lossy)
  int shBits = 5;                    // --sh-bits N: Gaussian scenes' SH codes to N bits (lossy)
  double shFull = 0.0;               // --sh-full F: the most important F keep every SH bit
  std::string rawDims;               // --raw-dims X,Y,Z: INPUT is raw voxels
  std::string rawType = "uint8";     // --raw-type int16 ...
  std::string rawSpacing = "1,1,1";  // --raw-spacing SX,SY,SZ
  bool rawBigEndian = false;         // --raw-big-endian
  std::uint64_t rawHeaderBytes = 0;  // --raw-skip BYTES
  bool progress = true;              // --no-progress turns the terminal bar off
  bool outline = false;              // --outline: OUT is a .wrl of outline groups
  double maxAngle = 30.0;            // --max-angle DEG: outline groups' normal spread

  // Tilesets (docs/qnv-format.md, "Tilesets"; app/src/encode_tileset.cpp).
  std::string tileset;             // --tileset OUT/: a tileset folder, not a stream
  std::uint32_t brickVoxels = 64;  // --brick-voxels B: volume leaf block side
  /// --brick-vectors K: vectors a node aims at; 0 = not given (16384; a Gaussian scene's
  /// own default, splats::defaultGaussianBrickVectors).
  std::uint64_t brickVectors = 0;
  unsigned mergedCells = 1;  // --merged-cells R; 1, not given: 16 (a splat scene: 16 or 32)
  std::string bricks;        // --bricks I/N: write share I of N only
  double memoryMB = 0;       // --memory MB: volumes out of core (0: in memory)
  unsigned threads = 0;      // --threads N: out-of-core workers (0: all cores)
};

struct Options {
  Command command = Command::window;
  std::vector<std::string> inputs;  // paths, file: or http(s) URLs, in order
  std::string snapshotPath;         // --snapshot OUT.png
  int width = 800;                  // --size WxH, pixels
  int height = 600;
  int frames = 0;  // --frames N: window closes after N frames (0 = never)
  int samples =
      -1;  // --samples N: anti-aliasing samples per pixel (-1: 4 in the window, 1 off-screen)
  double lod = 1.0;                // --lod F: fraction of each QNV stream drawn, (0, 1]
  std::vector<double> lods;        // --lod F1,F2,...: per viewport (the last one repeats)
  Layout layout = Layout::single;  // --layout 1x1|2x1|2x2: viewports in the window or image
  std::string script;              // --script FILE: UI actions for the window (window_script.hpp)
  bool newInstance = false;        // --new-instance: do not hand INPUTs to a running window
  std::string frameLog;            // --frame-log FILE: a line per window frame (frame_log.hpp)
  scene::RenderMode mode = scene::RenderMode::polygons;        // --mode polygons|splats|outlines
  render::SplatPath splatPath = render::SplatPath::automatic;  // --splat-path (docs/rendering.md)
  render::TextureQuality textureQuality = render::TextureQuality::high;  // --texture-quality
  render::ShadingOption shading = render::ShadingOption::phong;          // --shading
  bool fit = false;           // --fit: frame the whole scene, not the Viewpoint
  bool castleCamera = false;  // --castle-camera: castle's camera for a world without Viewpoint
  double maxRate = 0.0;       // --max-rate BYTES_PER_S: emulate a slow link (0: off)
  /// --snapshot-at BYTES | SECONDSs: render after only part of the input arrived.
  std::uint64_t snapshotAtBytes = 0;  // 0: not set
  double snapshotAtSeconds = 0.0;     // 0: not set
  bool progress = true;               // --no-progress: no progress bar on the terminal
  double stallTimeout = 20.0;         // --stall-timeout S: a transfer silent this long fails
  double tilesetMemoryMb = 512.0;     // --tileset-memory MB: decoded tileset vectors held
  session::RuntimeOptions time;       // --time, --time-step, --trace-events
  bool infoExitZero = false;          // info --exit-zero: worlds with errors exit 0
  EncodeOptions encode;
  std::string convertOutput;  // convert -o OUT: .wrl, .x3dv, .x3d or .x3dj
  std::string tilesetDir;     // tileset index OUT/: the folder whose shares are merged
};

/// The level of detail of viewport `index`: lods[index], the last of lods past its end,
/// or lod when lods is empty.
double viewportLod(const Options& options, std::size_t index);

/// Parses --snapshot-at: "123456" (bytes; suffixes k, M for 1024, 1048576) or "2.5s"
/// (seconds). Returns false when malformed, negative or zero.
bool parseSnapshotAt(const std::string& text, std::uint64_t& bytes, double& seconds);

/// Parses "WxH" (e.g. "800x600") into pixels; each side 1..16384. Returns false when the
/// text is malformed or out of range.
bool parseSize(const std::string& text, int& width, int& height);

}  // namespace gs::app
