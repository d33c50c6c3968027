// The ghostspace command line (see README.md, "Command line").
#pragma once

#include <string>
#include <vector>

namespace gs::app {

enum class Command { window, snapshot, info };

struct Options {
  Command command = Command::window;
  std::vector<std::string> inputs;  // files (later: URLs), in order
  std::string snapshotPath;         // --snapshot OUT.png
  int width = 800;                  // --size WxH, pixels
  int height = 600;
  int frames = 0;  // --frames N: window closes after N frames (0 = never)
};

/// Parses "WxH" (e.g. "800x600") into pixels; each side 1..16384. Returns false when the
/// text is malformed or out of range.
bool parseSize(const std::string& text, int& width, int& height);

}  // namespace gs::app
