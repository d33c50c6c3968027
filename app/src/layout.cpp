#include "app/layout.hpp"

#include <algorithm>

namespace gs::app {

int layoutCells(const std::string& layout) {
  if (layout == "1x1") return 1;
  if (layout == "2x1") return 2;
  if (layout == "2x2") return 4;
  return 0;
}

ViewportRect layoutRect(const std::string& layout, int index, int width, int height) {
  const int columns = layout == "1x1" ? 1 : 2;
  const int rows = layout == "2x2" ? 2 : 1;
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
