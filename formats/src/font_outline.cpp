// Glyph outlines: FreeType decomposition, curves flattened, contours grouped into filled
// regions (outer loop and holes).
#include "font_internal.hpp"

#include FT_OUTLINE_H

#include <algorithm>
#include <cmath>

namespace gs::formats::detail {

namespace {

struct Flattener {
  std::vector<std::vector<glm::dvec2>> contours;
  double tolerance = 8.0;  // font units
  std::size_t points = 0;
  bool tooMany = false;

  void add(glm::dvec2 p) {
    if (contours.empty()) contours.emplace_back();
    std::vector<glm::dvec2>& c = contours.back();
    if (!c.empty() && c.back() == p) return;
    if (++points > kMaxOutlinePoints) {
      tooMany = true;
      return;
    }
    c.push_back(p);
  }
  int segments(double deviation) const {
    const double n = std::ceil(std::sqrt(std::max(deviation, 0.0) / tolerance));
    return std::clamp(static_cast<int>(std::isfinite(n) ? n : 1.0), 1, 32);
  }
  glm::dvec2 last() const {
    return contours.empty() || contours.back().empty() ? glm::dvec2(0.0) : contours.back().back();
  }
};

glm::dvec2 vec(const FT_Vector* v) {
  return {static_cast<double>(v->x), static_cast<double>(v->y)};
}

int moveTo(const FT_Vector* to, void* user) {
  auto* f = static_cast<Flattener*>(user);
  f->contours.emplace_back();
  f->add(vec(to));
  return 0;
}

int lineTo(const FT_Vector* to, void* user) {
  static_cast<Flattener*>(user)->add(vec(to));
  return 0;
}

int conicTo(const FT_Vector* control, const FT_Vector* to, void* user) {
  auto* f = static_cast<Flattener*>(user);
  const glm::dvec2 p0 = f->last(), p1 = vec(control), p2 = vec(to);
  const int n = f->segments(glm::length(p0 - 2.0 * p1 + p2) * 0.25);
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n, u = 1.0 - t;
    f->add(u * u * p0 + 2.0 * u * t * p1 + t * t * p2);
  }
  return 0;
}

int cubicTo(const FT_Vector* c1, const FT_Vector* c2, const FT_Vector* to, void* user) {
  auto* f = static_cast<Flattener*>(user);
  const glm::dvec2 p0 = f->last(), p1 = vec(c1), p2 = vec(c2), p3 = vec(to);
  const double dev = std::max(glm::length(p0 - 2.0 * p1 + p2), glm::length(p1 - 2.0 * p2 + p3));
  const int n = f->segments(dev * 0.75);
  for (int i = 1; i <= n; ++i) {
    const double t = static_cast<double>(i) / n, u = 1.0 - t;
    f->add(u * u * u * p0 + 3.0 * u * u * t * p1 + 3.0 * u * t * t * p2 + t * t * t * p3);
  }
  return 0;
}

double signedArea(const std::vector<glm::dvec2>& c) {
  double a = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const glm::dvec2 &p = c[i], &q = c[(i + 1) % c.size()];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

bool inside(const std::vector<glm::dvec2>& poly, glm::dvec2 p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const glm::dvec2 &a = poly[i], &b = poly[j];
    if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
  }
  return in;
}

// A point well inside contour `c` near its first vertex (the centroid of the first
// triangle fan corner is enough for glyph contours, whose holes do not touch).
glm::dvec2 probe(const std::vector<glm::dvec2>& c) {
  return c[0] * 0.998 + c[c.size() / 2] * 0.002;
}

}  // namespace

GlyphOutline decomposeGlyph(const Face& face, std::uint32_t glyph) {
  GlyphOutline result;
  if (face.ft == nullptr ||
      FT_Load_Glyph(face.ft, glyph, FT_LOAD_NO_SCALE | FT_LOAD_NO_BITMAP | FT_LOAD_NO_HINTING) != 0)
    return result;
  FT_GlyphSlot slot = face.ft->glyph;
  if (slot->format != FT_GLYPH_FORMAT_OUTLINE || slot->outline.n_contours <= 0) return result;
  FT_Outline& outline = slot->outline;
  const double upem = face.info.unitsPerEm;
  if (face.info.syntheticBold) {
    const auto strength = static_cast<FT_Pos>(upem / 28.0);
    FT_Outline_EmboldenXY(&outline, strength, strength);
  }
  if (face.info.syntheticOblique) {
    FT_Matrix shear{0x10000, 0x0366A, 0, 0x10000};  // x += 0.2126 y, as FT_GlyphSlot_Oblique
    FT_Outline_Transform(&outline, &shear);
  }
  const FT_Orientation fill = FT_Outline_Get_Orientation(&outline);

  Flattener f;
  f.tolerance = std::max(upem / 256.0, 1e-3);
  const FT_Outline_Funcs funcs{moveTo, lineTo, conicTo, cubicTo, 0, 0};
  if (FT_Outline_Decompose(&outline, &funcs, &f) != 0 || f.tooMany) return result;

  struct Contour {
    std::vector<glm::dvec2> points;
    double area = 0.0;
  };
  std::vector<Contour> outers, holes;
  for (std::vector<glm::dvec2>& c : f.contours) {
    if (c.size() > 1 && c.front() == c.back()) c.pop_back();
    if (c.size() < 3) continue;
    const double a = signedArea(c);
    if (a == 0.0 || !std::isfinite(a)) continue;
    // FT_ORIENTATION_TRUETYPE: filled contours turn clockwise (negative area).
    const bool filled = (fill == FT_ORIENTATION_TRUETYPE) ? a < 0.0 : a > 0.0;
    if (a < 0.0) std::reverse(c.begin(), c.end());  // every contour counter-clockwise now
    (filled ? outers : holes).push_back({std::move(c), std::abs(a)});
  }
  std::vector<std::vector<const Contour*>> holesOf(outers.size());
  for (const Contour& h : holes) {
    std::size_t best = outers.size();
    for (std::size_t o = 0; o < outers.size(); ++o)
      if (outers[o].area > h.area && inside(outers[o].points, probe(h.points)) &&
          (best == outers.size() || outers[o].area < outers[best].area))
        best = o;
    if (best < outers.size()) holesOf[best].push_back(&h);
  }
  for (std::size_t o = 0; o < outers.size(); ++o) {
    GlyphRegion region;
    auto append = [&](const std::vector<glm::dvec2>& pts, bool reverse) {
      region.loopLengths.push_back(static_cast<std::int32_t>(pts.size()));
      const std::size_t first = region.points.size();
      for (const glm::dvec2& p : pts) {
        region.points.emplace_back(p);
        result.bounds.extend(glm::vec2(p));
      }
      if (reverse)
        std::reverse(region.points.begin() + static_cast<std::ptrdiff_t>(first),
                     region.points.end());
    };
    append(outers[o].points, false);
    for (const Contour* h : holesOf[o]) append(h->points, true);  // holes clockwise
    result.regions.push_back(std::move(region));
  }
  return result;
}

std::vector<std::uint32_t> decodeUtf8(const std::string& text, bool& bad) {
  std::vector<std::uint32_t> out;
  out.reserve(text.size());
  const auto* s = reinterpret_cast<const unsigned char*>(text.data());
  const std::size_t n = text.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned char b = s[i];
    int extra = 0;
    std::uint32_t c = 0, min = 0;
    if (b < 0x80) {
      out.push_back(b);
      ++i;
      continue;
    } else if ((b & 0xE0) == 0xC0) {
      extra = 1, c = b & 0x1F, min = 0x80;
    } else if ((b & 0xF0) == 0xE0) {
      extra = 2, c = b & 0x0F, min = 0x800;
    } else if ((b & 0xF8) == 0xF0) {
      extra = 3, c = b & 0x07, min = 0x10000;
    } else {
      out.push_back(0xFFFD);
      bad = true;
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    for (; j < n && j <= i + static_cast<std::size_t>(extra) && (s[j] & 0xC0) == 0x80; ++j)
      c = (c << 6) | (s[j] & 0x3F);
    if (j != i + 1 + static_cast<std::size_t>(extra) || c < min || c > 0x10FFFF ||
        (c >= 0xD800 && c <= 0xDFFF)) {
      out.push_back(0xFFFD);
      bad = true;
      i = j;  // skip the bytes of the broken sequence
      continue;
    }
    out.push_back(c);
    i = j;
  }
  return out;
}

}  // namespace gs::formats::detail
