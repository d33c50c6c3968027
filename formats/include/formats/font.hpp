// Fonts for the VRML97 Text node (ISO/IEC 14772-1, 6.47) and its FontStyle (6.20): font
// choice through fontconfig, UTF-8 shaping through HarfBuzz, glyph outlines through
// FreeType, and the layout of lines (size, spacing, justify, horizontal, leftToRight,
// topToBottom, length, maxExtent). Produces plain data: flattened outlines and glyph
// placements; turning outlines into triangles is render/'s (scene/text_mesh.hpp).
// docs/text.md explains the choices.
#pragma once

#include <glm/glm.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace gs::formats {

/// A 2-D axis-aligned box; empty when min > max.
struct Box2 {
  glm::vec2 min{1e30f};
  glm::vec2 max{-1e30f};
  bool empty() const { return min.x > max.x || min.y > max.y; }
  void extend(glm::vec2 p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  void extend(const Box2& b) {
    if (!b.empty()) {
      extend(b.min);
      extend(b.max);
    }
  }
};

/// One filled region of a glyph: an outer loop then its holes, points concatenated, in
/// font units (unitsPerEm to the em, y up). The outer loop turns counter-clockwise, holes
/// clockwise (whatever the font's own convention), so the region is what the nonzero
/// fill rule of the outline fills, for outlines whose contours do not cross.
struct GlyphRegion {
  std::vector<glm::vec2> points;
  std::vector<std::int32_t> loopLengths;  // first: the outer loop; then one per hole
};

/// A glyph's outline, curves flattened to line segments (at most 1/256 em from the
/// curve). Empty regions for blanks (space) and glyphs without outlines.
struct GlyphOutline {
  std::vector<GlyphRegion> regions;
  Box2 bounds;  // of all points, font units
};

/// Which face and glyph, as FontLibrary numbers them: the key of the glyph cache.
struct GlyphKey {
  std::uint32_t face = 0;   // FontLibrary's face number (a file, index and synthesis)
  std::uint32_t glyph = 0;  // glyph index in that face
  bool operator==(const GlyphKey&) const = default;
};

/// Alignment along one axis (FontStyle justify, 6.20.3).
enum class Justify : std::uint8_t { first, begin, middle, end };

/// The fields of FontStyle (6.20) and Text (6.47) that shape the layout. Defaults are
/// the VRML97 defaults.
struct TextStyle {
  /// Preference order; "SERIF", "SANS", "TYPEWRITER" or a fontconfig family name
  /// ("DejaVu Sans", "Liberation Mono"). Empty: SERIF.
  std::vector<std::string> family{"SERIF"};
  std::string style = "PLAIN";  // PLAIN, BOLD, ITALIC, BOLDITALIC; others: PLAIN + warning
  std::string language;         // RFC 1766 tag ("en", "ja", "ar"); "" = none
  float size = 1.0f;            // em height, local units, > 0 (else 1 with a warning)
  float spacing = 1.0f;         // baseline distance = spacing x size, >= 0
  Justify major = Justify::begin;
  Justify minor = Justify::first;
  bool horizontal = true;
  bool leftToRight = true;
  bool topToBottom = true;
  std::vector<float> length;  // per line, along the major axis; 0 or absent: natural
  float maxExtent = 0.0f;     // 0: no limit
};

/// Reads FontStyle's justify MFString (6.20.3): first value major, second minor; "" is
/// the default of its place (major BEGIN, minor FIRST); unknown names likewise, with
/// `unknown` set to the offending value.
void parseJustify(const std::vector<std::string>& justify, Justify& major, Justify& minor,
                  std::string* unknown = nullptr);

/// One glyph placed in the Text node's local coordinates: a point p of the outline (font
/// units) lands at origin + scale * p (z = 0).
struct PlacedGlyph {
  GlyphKey key;
  glm::vec2 origin{0.0f};
  glm::vec2 scale{1.0f};
};

/// One line (string) of a Text node after layout.
struct TextLine {
  std::size_t firstGlyph = 0;  // into TextLayout::glyphs
  std::size_t glyphCount = 0;
  /// Advance length along the major axis before length / maxExtent, local units.
  float naturalLength = 0.0f;
  /// Advance length after length / maxExtent (what the line occupies on the major axis).
  float length = 0.0f;
  /// The line's layout box: along the major axis its advance extent, across it the font's
  /// ascender..descender around the baseline (horizontal) or size wide around the
  /// column's axis (vertical).
  Box2 box;
};

/// A laid-out Text node.
struct TextLayout {
  std::vector<PlacedGlyph> glyphs;
  std::vector<TextLine> lines;  // one per string, also for empty strings
  Box2 bounds;                  // union of the line boxes (empty when no line has glyphs)
  /// Texture coordinates (6.47): (s, t) = (p - textureOrigin) / size, the origin of the
  /// first string as the justification placed it (its box's left end on the baseline
  /// for horizontal text; its box's left edge and top for vertical text).
  glm::vec2 textureOrigin{0.0f};
  float textureUnit = 1.0f;  // = size
  /// Problems met (a family not found, a bad style, invalid UTF-8), each once.
  std::vector<std::string> warnings;
  /// Description of the face used for the first line (family and style, file path).
  std::string faceDescription;
};

/// What FontLibrary knows of one face.
struct FaceInfo {
  std::string path;
  std::string family;
  std::string style;
  float unitsPerEm = 2048.0f;
  float ascender = 0.0f;   // font units, > 0 above the baseline
  float descender = 0.0f;  // font units, < 0 below the baseline
  bool syntheticBold = false;
  bool syntheticOblique = false;
};

/// Fonts, faces and the glyph cache. Thread-safe (one mutex). Untrusted font files (a file
/// that is not a font, a missing file) give a warning and the DejaVu fallback; the
/// outlines of a hostile font are bounded (at most kMaxOutlinePoints points per glyph).
class FontLibrary {
 public:
  FontLibrary();
  ~FontLibrary();
  FontLibrary(const FontLibrary&) = delete;
  FontLibrary& operator=(const FontLibrary&) = delete;

  /// Lays out `strings` (UTF-8; invalid bytes become U+FFFD with a warning) as 6.47 and
  /// 6.20 say. Characters the chosen face lacks come from another installed face that
  /// has them (fontconfig's choice, per character). Each line is shaped by HarfBuzz:
  /// its direction is right-to-left when leftToRight is FALSE or its first strong
  /// character is (Arabic, Hebrew), top-to-bottom for vertical text.
  TextLayout layout(const std::vector<std::string>& strings, const TextStyle& style);

  /// The outline of a glyph (cached; the reference stays valid while the library lives).
  /// An unknown key gives an empty outline.
  const GlyphOutline& outline(GlyphKey key);

  /// Face `face` (numbers from GlyphKey); a default FaceInfo for an unknown number.
  FaceInfo faceInfo(std::uint32_t face);

  /// The face for one family name and style (the face number), adding a warning to
  /// `warnings` when the family is not installed (then the DejaVu face of the generic
  /// family, else whatever fontconfig offers). Generic names: SERIF -> DejaVu Serif
  /// (fontconfig "serif"), SANS -> DejaVu Sans ("sans-serif"), TYPEWRITER -> DejaVu
  /// Sans Mono ("monospace").
  std::uint32_t resolveFace(const std::vector<std::string>& family, const std::string& style,
                            const std::string& language, std::vector<std::string>& warnings);

  /// Cached outlines so far (for tests of the cache).
  std::size_t cachedOutlineCount() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The process' font library (created on first use).
FontLibrary& sharedFontLibrary();

/// Most points a glyph outline keeps after flattening; a glyph beyond it is drawn empty.
inline constexpr std::size_t kMaxOutlinePoints = 65536;
/// Most characters of one Text line that are laid out; the rest is dropped (warning).
inline constexpr std::size_t kMaxLineCharacters = 100000;

}  // namespace gs::formats
