// X3D Layout (X3D 4.0 clause 36): where a Layout puts its LayoutGroup's children in the
// rectangle of its parent (the layer's view, or the enclosing LayoutGroup's rectangle),
// computed as X_ITE computes it (castle-model-viewer has no Layout). Sizes are metres of
// the view plane: the layer's orthographic region for a LayoutLayer, the viewport at the
// near clipping distance for a layer seen in perspective.
#pragma once

#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>

namespace gs::scene {

/// A Layout's units (clause 36.4.1: offsetUnits, sizeUnits).
enum class LayoutUnit : std::uint8_t { world, fraction, pixel };

/// The rectangle a Layout lays out in.
struct LayoutRectangle {
  glm::vec2 size{0.0f};            // metres of the view plane, > 0
  glm::vec2 metresPerPixel{0.0f};  // of the view plane, > 0
  /// What WORLD means inside it (a child's WORLD is its parent's unit, FRACTION at the top,
  /// as X_ITE resolves it), for x and y.
  std::array<LayoutUnit, 2> offsetUnits{LayoutUnit::fraction, LayoutUnit::fraction};
  std::array<LayoutUnit, 2> sizeUnits{LayoutUnit::fraction, LayoutUnit::fraction};
  bool top = true;  // the view's own rectangle (no Layout encloses it)
};

/// Where a Layout puts its children.
struct LayoutPlacement {
  /// From the parent rectangle's centre to the child rectangle's centre (align, then
  /// offset), metres of the view plane.
  glm::vec2 translation{0.0f};
  /// The children's scale, metres of the view plane per unit of their coordinates; where
  /// `keepScale` is set (scaleMode NONE inside another Layout) the scale in force stays.
  glm::vec2 scale{1.0f};
  std::array<bool, 2> keepScale{false, false};
  /// The child rectangle (for Layouts inside it).
  LayoutRectangle rectangle;
};

/// The placement by `layout` (a Layout node: align, offsetUnits, offset, sizeUnits, size,
/// scaleMode, each with one value for x and y or two; unknown words read as the default)
/// inside `parent`. At the top, scaleMode NONE is FRACTION (X_ITE). STRETCH in one axis
/// takes the other's scale; in both, the larger rectangle side's.
LayoutPlacement placeLayout(const vrml::Node& layout, const LayoutRectangle& parent);

/// The rectangle of a whole view of `pixels` (width, height) whose smaller side spans
/// `smallerSide` metres (an orthographic region's, or 2 tan(fieldOfView / 2) times the
/// near distance): the larger side sees more, as VRML's fieldOfView has it.
LayoutRectangle viewRectangle(glm::vec2 pixels, float smallerSide);

}  // namespace gs::scene
