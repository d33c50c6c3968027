// Text layout (6.47, 6.20): shaping each line with HarfBuzz, then length, maxExtent and
// justification.
#include "font_internal.hpp"

#include "base/text.hpp"

#include <algorithm>
#include <cmath>

namespace gs::formats {

namespace {

Justify justifyOf(const std::string& s, Justify fallback, std::string* unknown) {
  if (s.empty()) return fallback;
  if (base::equalsNoCase(s, "FIRST")) return Justify::first;
  if (base::equalsNoCase(s, "BEGIN")) return Justify::begin;
  if (base::equalsNoCase(s, "MIDDLE")) return Justify::middle;
  if (base::equalsNoCase(s, "END")) return Justify::end;
  if (unknown != nullptr) *unknown = s;
  return fallback;
}

// One glyph of a shaped line in visual order, local units (size applied, not length).
struct Shaped {
  GlyphKey key;
  glm::vec2 advance{0.0f};
  glm::vec2 offset{0.0f};
  float scale = 1.0f;  // size / unitsPerEm of its face
};

bool isRightToLeft(const std::vector<std::uint32_t>& text) {
  hb_unicode_funcs_t* uf = hb_unicode_funcs_get_default();
  for (std::uint32_t c : text) {
    const hb_script_t s = hb_unicode_script(uf, c);
    if (s == HB_SCRIPT_COMMON || s == HB_SCRIPT_INHERITED || s == HB_SCRIPT_UNKNOWN) continue;
    return hb_script_get_horizontal_direction(s) == HB_DIRECTION_RTL;
  }
  return false;
}

}  // namespace

void parseJustify(const std::vector<std::string>& justify, Justify& major, Justify& minor,
                  std::string* unknown) {
  major = justifyOf(justify.empty() ? std::string() : justify[0], Justify::begin, unknown);
  minor = justifyOf(justify.size() < 2 ? std::string() : justify[1], Justify::first, unknown);
}

TextLayout FontLibrary::layout(const std::vector<std::string>& strings, const TextStyle& style) {
  const std::lock_guard lock(impl_->mutex);
  TextLayout out;
  auto warnOnce = [&out](std::string w) {
    if (std::find(out.warnings.begin(), out.warnings.end(), w) == out.warnings.end())
      out.warnings.push_back(std::move(w));
  };
  float size = style.size;
  if (!(size > 0.0f) || !std::isfinite(size)) {
    warnOnce("FontStyle: size must be > 0; 1 used");
    size = 1.0f;
  }
  const float spacing =
      std::isfinite(style.spacing) && style.spacing >= 0.0f ? style.spacing : 1.0f;
  const std::vector<std::string> family =
      style.family.empty() ? std::vector<std::string>{"SERIF"} : style.family;
  std::vector<std::string> warnings;
  const std::uint32_t primary = impl_->resolveLocked(family, style.style, style.language, warnings);
  for (std::string& w : warnings) warnOnce(std::move(w));
  out.textureUnit = size;
  out.lines.resize(strings.size());
  if (primary == kNoFace) return out;
  const FaceInfo pinfo = impl_->faces[primary].info;  // a copy: faces grows below
  out.faceDescription = pinfo.family + " " + pinfo.style + " (" + pinfo.path + ")";
  const float pscale = size / pinfo.unitsPerEm;
  const float ascent = pinfo.ascender * pscale, descent = pinfo.descender * pscale;
  const hb_language_t language = style.language.empty()
                                     ? HB_LANGUAGE_INVALID
                                     : hb_language_from_string(style.language.c_str(), -1);

  // Shape every line into visual order.
  std::vector<std::vector<Shaped>> shaped(strings.size());
  hb_buffer_t* buffer = hb_buffer_create();
  for (std::size_t l = 0; l < strings.size(); ++l) {
    bool bad = false;
    std::vector<std::uint32_t> text = detail::decodeUtf8(strings[l], bad);
    if (bad) warnOnce("Text: invalid UTF-8 replaced by U+FFFD");
    if (text.size() > kMaxLineCharacters) {
      text.resize(kMaxLineCharacters);
      warnOnce("Text: line longer than " + std::to_string(kMaxLineCharacters) +
               " characters cut short");
    }
    for (std::uint32_t& c : text)
      if (c < 0x20 || c == 0x7F) c = 0x20;  // tabs, newlines and controls: blanks
    // The line's direction: its first strong character's, or right-to-left when asked.
    hb_direction_t dir = HB_DIRECTION_TTB;
    if (style.horizontal)
      dir = (!style.leftToRight || isRightToLeft(text)) ? HB_DIRECTION_RTL : HB_DIRECTION_LTR;
    // Runs of one face (the primary one, or a fallback per character) and one script
    // (blanks and punctuation join the run they are in).
    struct Run {
      std::size_t start;
      std::uint32_t face;
      hb_script_t script;
    };
    std::vector<Run> runs;
    hb_unicode_funcs_t* uf = hb_unicode_funcs_get_default();
    for (std::size_t i = 0; i < text.size(); ++i) {
      std::uint32_t f = impl_->faceForChar(primary, text[i]);
      if (f == kNoFace) f = primary;  // drawn as the primary face's .notdef box
      hb_script_t script = hb_unicode_script(uf, text[i]);
      const bool weak = script == HB_SCRIPT_COMMON || script == HB_SCRIPT_INHERITED ||
                        script == HB_SCRIPT_UNKNOWN;
      if (!runs.empty() && runs.back().face == f &&
          (weak || runs.back().script == script || runs.back().script == HB_SCRIPT_COMMON)) {
        if (!weak) runs.back().script = script;
        continue;
      }
      runs.push_back({i, f, weak ? HB_SCRIPT_COMMON : script});
    }
    std::vector<std::vector<Shaped>> runGlyphs;
    for (std::size_t r = 0; r < runs.size(); ++r) {
      const std::size_t begin = runs[r].start;
      const std::size_t end = r + 1 < runs.size() ? runs[r + 1].start : text.size();
      const detail::Face& face = impl_->faces[runs[r].face];
      // A run reads in its script's direction inside a line of the other direction
      // (a simplified bidi: no nesting); leftToRight FALSE makes every run right to left.
      hb_direction_t runDir = dir;
      if (style.horizontal && style.leftToRight && runs[r].script != HB_SCRIPT_COMMON)
        runDir = hb_script_get_horizontal_direction(runs[r].script);
      if (runDir == HB_DIRECTION_INVALID) runDir = dir;
      hb_buffer_clear_contents(buffer);
      hb_buffer_add_utf32(buffer, text.data(), static_cast<int>(text.size()),
                          static_cast<unsigned>(begin), static_cast<int>(end - begin));
      hb_buffer_set_direction(buffer, runDir);
      if (runs[r].script != HB_SCRIPT_COMMON) hb_buffer_set_script(buffer, runs[r].script);
      if (language != HB_LANGUAGE_INVALID) hb_buffer_set_language(buffer, language);
      hb_buffer_guess_segment_properties(buffer);
      hb_shape(face.hb, buffer, nullptr, 0);
      unsigned count = 0;
      const hb_glyph_info_t* info = hb_buffer_get_glyph_infos(buffer, &count);
      const hb_glyph_position_t* pos = hb_buffer_get_glyph_positions(buffer, &count);
      const float s = size / face.info.unitsPerEm;
      std::vector<Shaped>& run = runGlyphs.emplace_back();
      for (unsigned g = 0; g < count; ++g)
        run.push_back({{runs[r].face, info[g].codepoint},
                       {pos[g].x_advance * s, pos[g].y_advance * s},
                       {pos[g].x_offset * s, pos[g].y_offset * s},
                       s});
    }
    // Runs of a right-to-left line run right to left; bottom-to-top columns read upwards.
    const bool reverseRuns = dir == HB_DIRECTION_RTL || (!style.horizontal && !style.topToBottom);
    if (reverseRuns) std::reverse(runGlyphs.begin(), runGlyphs.end());
    for (std::vector<Shaped>& run : runGlyphs) {
      if (!style.horizontal && !style.topToBottom) std::reverse(run.begin(), run.end());
      shaped[l].insert(shaped[l].end(), run.begin(), run.end());
    }
  }
  hb_buffer_destroy(buffer);

  // Natural lengths, then length (per line) and maxExtent (all lines) along the major axis.
  std::vector<float> k(strings.size(), 1.0f);
  float longest = 0.0f;
  for (std::size_t l = 0; l < strings.size(); ++l) {
    float natural = 0.0f;
    for (const Shaped& g : shaped[l]) natural += style.horizontal ? g.advance.x : -g.advance.y;
    natural = std::abs(natural);
    out.lines[l].naturalLength = natural;
    const float want = l < style.length.size() ? style.length[l] : 0.0f;
    if (want > 0.0f && std::isfinite(want) && natural > 0.0f) k[l] = want / natural;
    longest = std::max(longest, natural * k[l]);
  }
  if (style.maxExtent > 0.0f && std::isfinite(style.maxExtent) && longest > style.maxExtent)
    for (float& f : k) f *= style.maxExtent / longest;

  // Place each line: along the major axis from its begin edge, across it by spacing.
  const float step = spacing * size;
  for (std::size_t l = 0; l < strings.size(); ++l) {
    TextLine& line = out.lines[l];
    line.firstGlyph = out.glyphs.size();
    line.glyphCount = shaped[l].size();
    line.length = line.naturalLength * k[l];
    const float L = line.length;
    glm::vec2 pen(0.0f);
    const float across = static_cast<float>(l) * step;
    if (style.horizontal) {
      // Visual order runs left to right over [0, L]; the begin edge is the left one for
      // left-to-right text and the right one otherwise.
      float shift = 0.0f;
      const bool ltr = style.leftToRight;
      switch (style.major) {
        case Justify::first:
        case Justify::begin:
          shift = ltr ? 0.0f : -L;
          break;
        case Justify::middle:
          shift = -0.5f * L;
          break;
        case Justify::end:
          shift = ltr ? -L : 0.0f;
          break;
      }
      const float baseline = style.topToBottom ? -across : across;
      for (const Shaped& g : shaped[l]) {
        out.glyphs.push_back({g.key,
                              {shift + k[l] * (pen.x + g.offset.x), baseline + pen.y + g.offset.y},
                              {g.scale * k[l], g.scale}});
        pen += g.advance;
      }
      line.box.extend(glm::vec2(shift, baseline + descent));
      line.box.extend(glm::vec2(shift + L, baseline + ascent));
    } else {
      // Columns: visual order runs top to bottom over [-L, 0].
      float shift = 0.0f;
      const bool ttb = style.topToBottom;
      switch (style.major) {
        case Justify::first:
        case Justify::begin:
          shift = ttb ? 0.0f : L;
          break;
        case Justify::middle:
          shift = 0.5f * L;
          break;
        case Justify::end:
          shift = ttb ? L : 0.0f;
          break;
      }
      const float axis = style.leftToRight ? across : -across;
      for (const Shaped& g : shaped[l]) {
        out.glyphs.push_back({g.key,
                              {axis + pen.x + g.offset.x, shift + k[l] * (pen.y + g.offset.y)},
                              {g.scale, g.scale * k[l]}});
        pen += g.advance;
      }
      line.box.extend(glm::vec2(axis - 0.5f * size, shift - L));
      line.box.extend(glm::vec2(axis + 0.5f * size, shift));
    }
  }

  // Minor alignment: move the whole block across the major axis.
  Box2 block;
  for (const TextLine& line : out.lines) block.extend(line.box);
  glm::vec2 move(0.0f);
  if (!out.lines.empty()) {
    const Box2& first = out.lines.front().box;
    const Box2& last = out.lines.back().box;
    if (style.horizontal) {
      const bool ttb = style.topToBottom;
      switch (style.minor) {
        case Justify::first:
          break;  // baseline of the first line at y = 0
        case Justify::begin:
          move.y = ttb ? -first.max.y : -first.min.y;
          break;
        case Justify::middle:
          move.y = -0.5f * (block.min.y + block.max.y);
          break;
        case Justify::end:
          move.y = ttb ? -last.min.y : -last.max.y;
          break;
      }
    } else {
      const bool ltr = style.leftToRight;
      switch (style.minor) {
        case Justify::first:  // FIRST is BEGIN for vertical text (6.20.3)
        case Justify::begin:
          move.x = ltr ? -first.min.x : -first.max.x;
          break;
        case Justify::middle:
          move.x = -0.5f * (block.min.x + block.max.x);
          break;
        case Justify::end:
          move.x = ltr ? -last.max.x : -last.min.x;
          break;
      }
    }
  }
  for (PlacedGlyph& g : out.glyphs) g.origin += move;
  for (TextLine& line : out.lines) {
    line.box.min += move;
    line.box.max += move;
    out.bounds.extend(line.box);
  }
  if (!out.lines.empty()) {
    const Box2& first = out.lines.front().box;
    out.textureOrigin = style.horizontal ? glm::vec2(first.min.x, first.min.y - descent)
                                         : glm::vec2(first.min.x, first.max.y);
  }
  return out;
}

}  // namespace gs::formats
