// Several viewports in one window or image (Nagasawa, "Beyond VRML", section 4: several
// streams on one display, each at its own resolution): the layouts 1x1, 2x1 (side by
// side) and 2x2.
#pragma once

#include <string>

namespace gs::app {

/// Viewports of `layout`: "1x1" 1, "2x1" 2, "2x2" 4; 0 for anything else.
int layoutCells(const std::string& layout);

/// A viewport rectangle in pixels, lower-left origin (as glViewport takes it).
struct ViewportRect {
  int x = 0, y = 0, width = 1, height = 1;
};

/// The rectangle of viewport `index` (0-based; left to right, then top to bottom) of
/// `layout` in a framebuffer of width x height pixels. Cells split the size evenly; the
/// last column and the bottom row take the odd pixel. Each side is at least 1.
ViewportRect layoutRect(const std::string& layout, int index, int width, int height);

}  // namespace gs::app
