// Several viewports in one window or image (Nagasawa, "Beyond VRML", section 4: several
// streams on one display, each at its own resolution): the layouts 1x1, 2x1 (side by
// side) and 2x2, declared once in kLayouts (the command line, the window script, the
// menu and the snapshot read their names from it).
#pragma once

#include <array>
#include <optional>
#include <string_view>

namespace gs::app {

enum class Layout {
  single,      // "1x1": one viewport
  sideBySide,  // "2x1": two, left and right
  quad,        // "2x2": four, left to right, then top to bottom
};

/// One row of the layout table: its name on the command line, in scripts and menus, and
/// its grid of cells.
struct LayoutInfo {
  Layout layout;
  std::string_view name;
  int columns, rows;
};

inline constexpr std::array<LayoutInfo, 3> kLayouts = {{
    {Layout::single, "1x1", 1, 1},
    {Layout::sideBySide, "2x1", 2, 1},
    {Layout::quad, "2x2", 2, 2},
}};

/// The table row of `layout`.
const LayoutInfo& layoutInfo(Layout layout);

/// The name of `layout` ("1x1", "2x1", "2x2").
std::string_view layoutName(Layout layout);

/// The layout named `name` (exactly as in kLayouts), or nullopt.
std::optional<Layout> layoutFromName(std::string_view name);

/// Viewports of `layout`: 1, 2 or 4.
int layoutCells(Layout layout);

/// A viewport rectangle in pixels, lower-left origin (as glViewport takes it).
struct ViewportRect {
  int x = 0, y = 0, width = 1, height = 1;
};

/// The rectangle of viewport `index` (0-based; left to right, then top to bottom) of
/// `layout` in a framebuffer of width x height pixels. Cells split the size evenly; the
/// last column and the bottom row take the odd pixel. Each side is at least 1.
ViewportRect layoutRect(Layout layout, int index, int width, int height);

}  // namespace gs::app
