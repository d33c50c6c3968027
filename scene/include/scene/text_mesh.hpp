// The Text node (ISO/IEC 14772-1, 6.47) as triangles: the layout of formats::FontLibrary
// (FontStyle 6.20: font, size, spacing, justify, direction; length, maxExtent), each
// glyph's outline triangulated once (holes kept) and cached per face and glyph.
#pragma once

#include "formats/font.hpp"
#include "geometry/geometry.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/node.hpp"

namespace gs::scene {

/// The FontStyle (6.20) and Text (6.47) fields of `text` as a formats::TextStyle (a
/// missing fontStyle gives the defaults). An unknown justify value is a warning in
/// `diag` (when not null) at the FontStyle's location.
formats::TextStyle textStyleOf(const vrml::Node& text, vrml::Diagnostics* diag = nullptr);

/// Triangles of a Text node in its local coordinates (z = 0, metres): every glyph filled,
/// holes open, normal +Z, not solid (VRML97 Text is seen from both sides), texture
/// coordinates as 6.47 says ((x, y) minus the origin of the first string, divided by
/// size: the font's em is one texture unit, S right, T up). A text with no glyphs (empty
/// strings, blanks) gives an empty mesh. Font problems (a family not installed, invalid
/// UTF-8, no font at all) are warnings in `diag` at the node's location; never throws.
vrml::Mesh tessellateText(const vrml::Node& text, vrml::Diagnostics* diag = nullptr,
                          formats::FontLibrary& fonts = formats::sharedFontLibrary());

/// vrml::tessellate, with Text nodes tessellated by tessellateText: what the renderer,
/// picking and worldTriangles use when TraversalOptions::tessellator is empty.
vrml::Mesh tessellateGeometry(const vrml::Node& geometry, vrml::Diagnostics* diag = nullptr,
                              float nurbsTessellationScale = 1.0f);

/// Glyph triangulations made so far (each face and glyph once), for tests of the cache.
std::size_t cachedGlyphMeshCount();

}  // namespace gs::scene
