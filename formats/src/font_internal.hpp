// Private to formats/: the state behind FontLibrary (FreeType, HarfBuzz, fontconfig).
#pragma once

#include "formats/font.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H
#include <hb.h>

#include <map>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace gs::formats::detail {

/// One opened face (a font file, a face index in it, and the synthesis asked of it).
struct Face {
  FaceInfo info;
  int index = 0;
  FT_Face ft = nullptr;
  hb_font_t* hb = nullptr;  // scale = unitsPerEm: positions in font units
};

/// The flattened outline of glyph `glyph` of `face` (FT_LOAD_NO_SCALE), contours grouped
/// into regions (outer loop + holes) by the nonzero fill rule; empty for glyphs without
/// an outline or with more than kMaxOutlinePoints points.
GlyphOutline decomposeGlyph(const Face& face, std::uint32_t glyph);

/// Decodes UTF-8; invalid sequences (bad bytes, overlong forms, surrogates, values past
/// U+10FFFF, truncated sequences) become U+FFFD and set `bad`.
std::vector<std::uint32_t> decodeUtf8(const std::string& text, bool& bad);

}  // namespace gs::formats::detail

namespace gs::formats {

struct FontLibrary::Impl {
  mutable std::mutex mutex;
  FT_Library ft = nullptr;
  bool fontconfigReady = false;
  std::vector<detail::Face> faces;
  std::map<std::string, std::uint32_t> faceByKey;  // "path|index|bold|oblique"
  std::unordered_map<std::uint64_t, GlyphOutline> outlines;
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> fallbackByChar;
  std::map<std::string, std::uint32_t> resolved;  // family|style|language -> face

  /// Opens (or finds) a face; kNoFace when FreeType cannot read it.
  std::uint32_t openFace(const std::string& path, int index, bool bold, bool oblique);
  /// The face fontconfig picks for one family name; kNoFace when fontconfig offers
  /// nothing readable. `exact` is set when the face's family is the one asked for.
  std::uint32_t matchFamily(const std::string& family, bool bold, bool italic,
                            const std::string& language, bool& exact);
  /// The face that has character `c` when `primary` lacks it (kNoFace: none has it).
  std::uint32_t faceForChar(std::uint32_t primary, std::uint32_t c);
  std::uint32_t resolveLocked(const std::vector<std::string>& family, const std::string& style,
                              const std::string& language, std::vector<std::string>& warnings);
  const GlyphOutline& outlineLocked(GlyphKey key);
};

inline constexpr std::uint32_t kNoFace = 0xffffffffu;

}  // namespace gs::formats
