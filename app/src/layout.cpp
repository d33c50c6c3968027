#include "app/layout.hpp"

#include <algorithm>

namespace gs::app {

const LayoutInfo& layoutInfo(Layout layout) {
  for (const LayoutInfo& info : kLayouts)
    if (info.layout == layout) return info;
  return kLayouts.front();
}

std::string_view layoutName(Layout layout) {
  return layoutInfo(layout).name;
}

std::optional<Layout> layoutFromName(std::string_view name) {
  for (const LayoutInfo& info : kLayouts)
    if (info.name == name) return info.layout;
  return std::nullopt;
}

int layoutCells(Layout layout) {
  const LayoutInfo& info = layoutInfo(layout);
  return info.columns * info.rows;
}

ViewportRect layoutRect(Layout layout, int index, int width, int height) {
  const int columns = layoutInfo(layout).columns;
  const int rows = layoutInfo(layout).rows;
  const int column = index % columns, row = index / columns;  // row 0 is the top
  const int cellWidth = width / columns, cellHeight = height / rows;
  ViewportRect r;
  r.x = column * cellWidth;
  r.width = column == columns - 1 ? width - r.x : cellWidth;
  // Lower-left origin: the top row is the highest.
  const int top = row * cellHeight;
  const int bottom = row == rows - 1 ? height : top + cellHeight;
  r.y = height - bottom;
  r.height = bottom - top;
  r.width = std::max(1, r.width);
  r.height = std::max(1, r.height);
  return r;
}

}  // namespace gs::app
