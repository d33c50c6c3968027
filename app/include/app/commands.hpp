// The three things ghostspace does; each returns a process exit code.
#pragma once

#include "app/options.hpp"

namespace gs::app {

/// `ghostspace info INPUT`: prints node counts by type, triangles, bounding box,
/// diagnostics and parse time to stdout. 0 when the input was read (even with
/// diagnostics), 1 when it could not be read at all.
int runInfo(const Options& options);

/// `ghostspace --snapshot OUT.png [--size WxH] INPUT`: renders off-screen through OSMesa
/// from the bound Viewpoint and writes a PNG. 0 on success; 1 with one line on stderr
/// when the input cannot be read or the image cannot be written.
int runSnapshot(const Options& options);

/// `ghostspace [INPUT...]`: the GLFW window with its Dear ImGui menu. Returns when the
/// window is closed; 1 when no window can be created (e.g. no display).
int runWindow(const Options& options);

}  // namespace gs::app
