// Text layout (6.47, 6.20) against boxes computed by hand from DejaVu's metrics, glyph
// outlines with holes, shaping of Cyrillic and Arabic, font fallback.
#include "formats/font.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

using gs::formats::FontLibrary;
using gs::formats::Justify;
using gs::formats::TextLayout;
using gs::formats::TextStyle;

namespace {

// DejaVu Sans 2.37 (fonts-dejavu-core), read with FreeType (FT_LOAD_NO_SCALE).
constexpr float kUpem = 2048.0f;
constexpr float kAscender = 1901.0f;
constexpr float kDescender = -483.0f;
constexpr float kAdvanceH = 1540.0f;  // 'H'

// The layout's arithmetic is checked on DejaVu Sans, named (SANS is PT Sans where
// fonts-paratype is installed, docs/text.md).
TextStyle sans(float size = 1.0f) {
  TextStyle s;
  s.family = {"DejaVu Sans"};
  s.size = size;
  return s;
}

FontLibrary& fonts() {
  static FontLibrary library;
  return library;
}

double signedArea(const std::vector<glm::vec2>& p, std::size_t first, std::size_t n) {
  double a = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec2 &s = p[first + i], &t = p[first + (i + 1) % n];
    a += double(s.x) * t.y - double(t.x) * s.y;
  }
  return 0.5 * a;
}

}  // namespace

TEST_CASE("FontStyle families map to X_ITE's faces where Debian has them, else DejaVu",
          "[formats][font]") {
  std::vector<std::string> warnings;
  auto face = [&](std::vector<std::string> family, const char* style) {
    return fonts().faceInfo(fonts().resolveFace(family, style, "", warnings));
  };
  CHECK(face({"SANS"}, "PLAIN").family == "PT Sans");
  CHECK(face({"SERIF"}, "PLAIN").family == "Noto Serif");
  CHECK(face({"TYPEWRITER"}, "PLAIN").family == "DejaVu Sans Mono");
  CHECK(face({"SANS"}, "BOLD").style == "Bold");
  const auto italic = face({"TYPEWRITER"}, "ITALIC");
  CHECK(italic.family == "DejaVu Sans Mono");
  CHECK((italic.style == "Oblique" || italic.syntheticOblique));
  const auto boldItalic = face({"SERIF"}, "BOLDITALIC");
  CHECK(((boldItalic.style == "Bold Italic") || (boldItalic.syntheticBold)));
  CHECK(warnings.empty());
  CHECK(face({}, "PLAIN").family == "Noto Serif");  // no family: SERIF
}

TEST_CASE("A family that is not installed falls back with a warning", "[formats][font]") {
  TextStyle s = sans();
  s.family = {"NoSuchFamilyAnywhere"};
  const TextLayout l = fonts().layout({"HH"}, s);
  REQUIRE(l.warnings.size() == 1);
  CHECK(l.warnings[0].find("NoSuchFamilyAnywhere") != std::string::npos);
  CHECK(l.faceDescription.find("Noto Serif") != std::string::npos);  // 6.20.2: SERIF
  CHECK(l.glyphs.size() == 2);

  s.family = {"NoSuchFamilyAnywhere", "TYPEWRITER"};  // the next preference wins
  const TextLayout next = fonts().layout({"HH"}, s);
  CHECK(next.faceDescription.find("DejaVu Sans Mono") != std::string::npos);

  s.style = "WOBBLY";
  CHECK(fonts().layout({"H"}, s).warnings.size() == 2);  // family and style
}

TEST_CASE("Major justification places each line by its advance", "[formats][font]") {
  const float size = 2.0f, scale = size / kUpem;
  const float L = 3.0f * kAdvanceH * scale;  // "HHH"
  TextStyle s = sans(size);
  struct Case {
    Justify major;
    bool leftToRight;
    float min, max;
  };
  for (const Case& c :
       {Case{Justify::begin, true, 0.0f, L}, Case{Justify::first, true, 0.0f, L},
        Case{Justify::middle, true, -L / 2, L / 2}, Case{Justify::end, true, -L, 0.0f},
        Case{Justify::begin, false, -L, 0.0f}, Case{Justify::end, false, 0.0f, L}}) {
    s.major = c.major;
    s.leftToRight = c.leftToRight;
    const TextLayout l = fonts().layout({"HHH"}, s);
    REQUIRE(l.lines.size() == 1);
    CHECK(l.lines[0].naturalLength == Approx(L));
    CHECK(l.lines[0].box.min.x == Approx(c.min).margin(1e-5));
    CHECK(l.lines[0].box.max.x == Approx(c.max).margin(1e-5));
    // Baseline at y = 0 (minor FIRST): the box spans the font's descender..ascender.
    CHECK(l.lines[0].box.min.y == Approx(kDescender * scale));
    CHECK(l.lines[0].box.max.y == Approx(kAscender * scale));
  }
}

TEST_CASE("leftToRight FALSE runs the characters right to left", "[formats][font]") {
  TextStyle s = sans();
  const auto glyphOf = [&](const char* ch) {
    return fonts().layout({ch}, s).glyphs.at(0).key.glyph;
  };
  const std::uint32_t a = glyphOf("A"), b = glyphOf("B");
  s.leftToRight = false;
  const TextLayout l = fonts().layout({"AB"}, s);
  REQUIRE(l.glyphs.size() == 2);
  const auto& left = l.glyphs[0].origin.x < l.glyphs[1].origin.x ? l.glyphs[0] : l.glyphs[1];
  const auto& right = &left == &l.glyphs[0] ? l.glyphs[1] : l.glyphs[0];
  CHECK(left.key.glyph == b);
  CHECK(right.key.glyph == a);
  CHECK(l.lines[0].box.max.x == Approx(0.0f).margin(1e-6));  // BEGIN: right edge at 0
}

TEST_CASE("Minor justification and spacing place the lines", "[formats][font]") {
  const float size = 2.0f, scale = size / kUpem, spacing = 1.5f, step = spacing * size;
  TextStyle s = sans(size);
  s.spacing = spacing;
  const std::vector<std::string> lines = {"H", "HH", "HHH"};
  auto baseline = [&](const TextLayout& l, std::size_t i) {
    return l.lines[i].box.min.y - kDescender * scale;
  };
  SECTION("FIRST: first baseline at 0, lines step down by spacing x size") {
    const TextLayout l = fonts().layout(lines, s);
    CHECK(baseline(l, 0) == Approx(0.0f).margin(1e-5));
    CHECK(baseline(l, 1) == Approx(-step));
    CHECK(baseline(l, 2) == Approx(-2 * step));
  }
  SECTION("topToBottom FALSE: lines step up") {
    s.topToBottom = false;
    const TextLayout l = fonts().layout(lines, s);
    CHECK(baseline(l, 1) == Approx(step));
    CHECK(baseline(l, 2) == Approx(2 * step));
  }
  SECTION("BEGIN: top of the first line at 0") {
    s.minor = Justify::begin;
    const TextLayout l = fonts().layout(lines, s);
    CHECK(l.lines[0].box.max.y == Approx(0.0f).margin(1e-5));
    CHECK(baseline(l, 0) == Approx(-kAscender * scale));
  }
  SECTION("END: bottom of the last line at 0") {
    s.minor = Justify::end;
    const TextLayout l = fonts().layout(lines, s);
    CHECK(l.lines[2].box.min.y == Approx(0.0f).margin(1e-5));
  }
  SECTION("MIDDLE: the block centred on 0") {
    s.minor = Justify::middle;
    const TextLayout l = fonts().layout(lines, s);
    CHECK(l.bounds.min.y + l.bounds.max.y == Approx(0.0f).margin(1e-5));
    CHECK(l.bounds.max.y - l.bounds.min.y == Approx(2 * step + (kAscender - kDescender) * scale));
  }
  SECTION("parseJustify reads the MFString") {
    Justify major{}, minor{};
    std::string unknown;
    gs::formats::parseJustify({"MIDDLE", "END"}, major, minor, &unknown);
    CHECK((major == Justify::middle && minor == Justify::end));
    gs::formats::parseJustify({""}, major, minor, &unknown);
    CHECK((major == Justify::begin && minor == Justify::first));
    CHECK(unknown.empty());
    gs::formats::parseJustify({"LEFT"}, major, minor, &unknown);
    CHECK(unknown == "LEFT");
  }
}

TEST_CASE("length and maxExtent scale lines along the major axis", "[formats][font]") {
  const float scale = 1.0f / kUpem;
  TextStyle s = sans();
  s.length = {5.0f, 0.0f};
  TextLayout l = fonts().layout({"HH", "HHH"}, s);
  CHECK(l.lines[0].length == Approx(5.0f));
  CHECK(l.lines[0].box.max.x - l.lines[0].box.min.x == Approx(5.0f));
  CHECK(l.glyphs[0].scale.x == Approx(scale * 5.0f / (2 * kAdvanceH * scale)));
  CHECK(l.glyphs[0].scale.y == Approx(scale));                // glyph height kept
  CHECK(l.lines[1].length == Approx(3 * kAdvanceH * scale));  // 0: natural

  s.length = {};
  s.maxExtent = 2.0f;  // the longest line ("HHH", 2.26) is squeezed to 2, the other alike
  l = fonts().layout({"HH", "HHH"}, s);
  const float k = 2.0f / (3 * kAdvanceH * scale);
  CHECK(l.lines[1].length == Approx(2.0f));
  CHECK(l.lines[0].length == Approx(2 * kAdvanceH * scale * k));

  s.maxExtent = 10.0f;  // longer than every line: nothing changes
  l = fonts().layout({"HH", "HHH"}, s);
  CHECK(l.lines[1].length == Approx(3 * kAdvanceH * scale));
}

TEST_CASE("Vertical text runs down in columns left to right", "[formats][font]") {
  const float size = 1.0f;
  TextStyle s = sans(size);
  s.horizontal = false;
  s.spacing = 2.0f;
  const TextLayout l = fonts().layout({"HHH", "H"}, s);
  REQUIRE(l.glyphs.size() == 4);
  // Major BEGIN with topToBottom: the top of each column at y = 0, glyphs going down.
  CHECK(l.lines[0].box.max.y == Approx(0.0f).margin(1e-6));
  CHECK(l.lines[0].box.min.y < -2.0f * size);
  CHECK(l.glyphs[0].origin.y > l.glyphs[1].origin.y);
  CHECK(l.glyphs[1].origin.y > l.glyphs[2].origin.y);
  // Minor FIRST (= BEGIN for vertical text): left edge of the first column at x = 0; the
  // next column spacing x size to the right.
  CHECK(l.lines[0].box.min.x == Approx(0.0f).margin(1e-6));
  CHECK(l.lines[1].box.min.x == Approx(2.0f * size));
  s.topToBottom = false;  // bottom to top: bottom of the column at 0, first character lowest
  const std::uint32_t a = fonts().layout({"A"}, sans()).glyphs.at(0).key.glyph;
  const TextLayout up = fonts().layout({"AB"}, s);
  REQUIRE(up.glyphs.size() == 2);
  CHECK(up.lines[0].box.min.y == Approx(0.0f).margin(1e-6));
  const auto& lowest = up.glyphs[0].origin.y < up.glyphs[1].origin.y ? up.glyphs[0] : up.glyphs[1];
  CHECK(lowest.key.glyph == a);
}

TEST_CASE("Glyph outlines keep their holes", "[formats][font]") {
  const TextLayout l = fonts().layout({"OAiB"}, sans());
  REQUIRE(l.glyphs.size() == 4);
  const auto& o = fonts().outline(l.glyphs[0].key);
  REQUIRE(o.regions.size() == 1);
  REQUIRE(o.regions[0].loopLengths.size() == 2);  // outer ring and the hole
  const auto& r = o.regions[0];
  const auto outer = static_cast<std::size_t>(r.loopLengths[0]);
  const auto hole = static_cast<std::size_t>(r.loopLengths[1]);
  CHECK(signedArea(r.points, 0, outer) > 0.0);             // counter-clockwise
  CHECK(signedArea(r.points, outer, hole) < 0.0);          // clockwise
  CHECK(o.bounds.max.y == Approx(1520.0f).margin(40.0f));  // cap height of DejaVu Sans 'O'
  CHECK(fonts().outline(l.glyphs[1].key).regions.at(0).loopLengths.size() == 2);  // A
  CHECK(fonts().outline(l.glyphs[2].key).regions.size() == 2);                    // i: dot, stem
  CHECK(fonts().outline(l.glyphs[3].key).regions.at(0).loopLengths.size() == 3);  // B
  const std::size_t cached = fonts().cachedOutlineCount();
  fonts().outline(l.glyphs[0].key);
  CHECK(fonts().cachedOutlineCount() == cached);
  CHECK(fonts().outline({999999u, 1u}).regions.empty());  // unknown face
}

TEST_CASE("Cyrillic and Arabic shape to real glyphs", "[formats][font]") {
  TextStyle s;  // DejaVu Serif has Cyrillic but no Arabic
  s.family = {"DejaVu Serif"};
  const TextLayout cyr = fonts().layout({"Привет"}, s);
  REQUIRE(cyr.glyphs.size() == 6);
  for (const auto& g : cyr.glyphs) CHECK(g.key.glyph != 0);  // no .notdef
  CHECK(cyr.lines[0].naturalLength > 3.0f);
  CHECK(cyr.lines[0].naturalLength < 6.0f);

  const std::uint32_t isolatedMeem = fonts().layout({"م"}, s).glyphs.at(0).key.glyph;
  const TextLayout ar = fonts().layout({"مرحبا"}, s);
  REQUIRE(ar.glyphs.size() == 5);
  for (const auto& g : ar.glyphs) {
    CHECK(g.key.glyph != 0);
    CHECK(fonts().faceInfo(g.key.face).family == "DejaVu Sans");  // fallback per character
    CHECK(g.key.glyph != isolatedMeem);  // joined: the initial form, not the isolated one
  }
  // Right to left: the first character (meem) is the rightmost glyph.
  const auto rightmost = std::max_element(ar.glyphs.begin(), ar.glyphs.end(),
                                          [](auto& a, auto& b) { return a.origin.x < b.origin.x; });
  CHECK(rightmost == ar.glyphs.end() - 1);
  CHECK(ar.lines[0].box.min.x == Approx(0.0f).margin(1e-6));  // BEGIN, leftToRight TRUE
}

TEST_CASE("A Latin word and an Arabic word on one line each keep their direction",
          "[formats][font]") {
  TextStyle s = sans();
  const TextLayout word = fonts().layout({"مرحبا"}, s);
  const TextLayout mixed = fonts().layout({"ab مرحبا"}, s);
  REQUIRE(mixed.glyphs.size() == 3 + word.glyphs.size());
  // The line starts with Latin (left to right); the Arabic run is shaped as Arabic
  // (joined forms, right to left) exactly as alone.
  const std::uint32_t a = fonts().layout({"a"}, s).glyphs.at(0).key.glyph;
  CHECK(mixed.glyphs[0].key.glyph == a);
  for (std::size_t i = 0; i < word.glyphs.size(); ++i)
    CHECK(mixed.glyphs[3 + i].key.glyph == word.glyphs[i].key.glyph);
}

TEST_CASE("Invalid UTF-8 becomes U+FFFD with a warning", "[formats][font]") {
  const TextLayout l = fonts().layout({"A\xFF"
                                       "B\xC3",
                                       "\xE0\x80\x80\xED\xA0\x80"},
                                      sans());
  REQUIRE(l.warnings.size() == 1);
  CHECK(l.warnings[0].find("UTF-8") != std::string::npos);
  CHECK(l.lines[0].glyphCount == 4);  // A, U+FFFD, B, U+FFFD
  CHECK(l.lines[1].glyphCount >= 2);  // an overlong form and a surrogate
  const TextLayout empty = fonts().layout({"", " "}, sans());
  CHECK(empty.lines.size() == 2);
  CHECK(empty.warnings.empty());
  TextStyle bad = sans();
  bad.size = -1.0f;
  CHECK(fonts().layout({"H"}, bad).warnings.size() == 1);
}
