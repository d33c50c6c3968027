// FontLibrary: faces through fontconfig and FreeType, the glyph outline cache.
#include "font_internal.hpp"

#include "base/text.hpp"

#include <fontconfig/fontconfig.h>

#include <array>
#include <string_view>

namespace gs::formats {

namespace {

struct Generic {
  std::string_view vrmlName;
  const char* preferred;  // X_ITE's face, or its Debian successor (nullptr: none)
  const char* dejavu;
  const char* fontconfig;
  const char* path;
};

// The generic families of 6.20.2 and the faces each prefers: first the face X_ITE (the
// reference browser of X3D 4) draws it with, where Debian has it (Droid Serif's successor
// Noto Serif, fonts-noto-core; PT Sans, fonts-paratype; X_ITE's TYPEWRITER, Ubuntu Mono,
// is not packaged), so that a Text is as wide as its author saw it there; then DejaVu
// (fonts-dejavu-core is always installed, so a layout does not depend on what else a
// machine has); then fontconfig's generic family; then the DejaVu file by path.
constexpr std::array<Generic, 3> kGenerics = {{
    {"SERIF", "Noto Serif", "DejaVu Serif", "serif",
     "/usr/share/fonts/truetype/dejavu/DejaVuSerif.ttf"},
    {"SANS", "PT Sans", "DejaVu Sans", "sans-serif",
     "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"},
    {"TYPEWRITER", nullptr, "DejaVu Sans Mono", "monospace",
     "/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf"},
}};

const Generic* genericFamily(const std::string& name) {
  for (const Generic& g : kGenerics)
    if (base::equalsNoCase(name, g.vrmlName)) return &g;
  return nullptr;
}

const char* str(FcPattern* p, const char* object, int n = 0) {
  FcChar8* s = nullptr;
  return FcPatternGetString(p, object, n, &s) == FcResultMatch ? reinterpret_cast<char*>(s)
                                                               : nullptr;
}

int integer(FcPattern* p, const char* object, int fallback) {
  int v = fallback;
  return FcPatternGetInteger(p, object, 0, &v) == FcResultMatch ? v : fallback;
}

FcPattern* stylePattern(bool bold, bool italic, const std::string& language) {
  FcPattern* pat = FcPatternCreate();
  FcPatternAddInteger(pat, FC_WEIGHT, bold ? FC_WEIGHT_BOLD : FC_WEIGHT_REGULAR);
  FcPatternAddInteger(pat, FC_SLANT, italic ? FC_SLANT_ITALIC : FC_SLANT_ROMAN);
  FcPatternAddInteger(pat, FC_WIDTH, FC_WIDTH_NORMAL);
  FcPatternAddBool(pat, FC_SCALABLE, FcTrue);
  if (!language.empty())
    FcPatternAddString(pat, FC_LANG, reinterpret_cast<const FcChar8*>(language.c_str()));
  return pat;
}

}  // namespace

std::uint32_t FontLibrary::Impl::openFace(const std::string& path, int index, bool bold,
                                          bool oblique) {
  const std::string key =
      path + "|" + std::to_string(index) + "|" + (bold ? "b" : "") + (oblique ? "o" : "");
  if (auto it = faceByKey.find(key); it != faceByKey.end()) return it->second;
  if (ft == nullptr) return kNoFace;
  detail::Face face;
  if (FT_New_Face(ft, path.c_str(), index, &face.ft) != 0) {
    faceByKey[key] = kNoFace;
    return kNoFace;
  }
  if (!FT_IS_SCALABLE(face.ft) || face.ft->units_per_EM == 0) {
    FT_Done_Face(face.ft);
    faceByKey[key] = kNoFace;
    return kNoFace;
  }
  hb_blob_t* blob = hb_blob_create_from_file_or_fail(path.c_str());
  if (blob == nullptr) {
    FT_Done_Face(face.ft);
    faceByKey[key] = kNoFace;
    return kNoFace;
  }
  hb_face_t* hbFace = hb_face_create(blob, static_cast<unsigned>(index));
  hb_blob_destroy(blob);
  face.hb = hb_font_create(hbFace);
  hb_face_destroy(hbFace);
  const auto upem = static_cast<int>(face.ft->units_per_EM);
  hb_font_set_scale(face.hb, upem, upem);
  face.index = index;
  face.info.path = path;
  face.info.family = face.ft->family_name ? face.ft->family_name : "";
  face.info.style = face.ft->style_name ? face.ft->style_name : "";
  face.info.unitsPerEm = static_cast<float>(upem);
  face.info.ascender = static_cast<float>(face.ft->ascender);
  face.info.descender = static_cast<float>(face.ft->descender);
  if (face.info.ascender <= 0.0f) face.info.ascender = 0.8f * face.info.unitsPerEm;
  if (face.info.descender >= 0.0f) face.info.descender = -0.2f * face.info.unitsPerEm;
  face.info.syntheticBold = bold;
  face.info.syntheticOblique = oblique;
  const auto number = static_cast<std::uint32_t>(faces.size());
  faces.push_back(face);
  faceByKey[key] = number;
  return number;
}

std::uint32_t FontLibrary::Impl::matchFamily(const std::string& family, bool bold, bool italic,
                                             const std::string& language, bool& exact) {
  exact = false;
  if (!fontconfigReady) return kNoFace;
  FcPattern* pat = stylePattern(bold, italic, language);
  FcPatternAddString(pat, FC_FAMILY, reinterpret_cast<const FcChar8*>(family.c_str()));
  FcConfigSubstitute(nullptr, pat, FcMatchPattern);
  FcDefaultSubstitute(pat);
  FcResult result = FcResultNoMatch;
  FcPattern* match = FcFontMatch(nullptr, pat, &result);
  FcPatternDestroy(pat);
  if (match == nullptr) return kNoFace;
  std::uint32_t face = kNoFace;
  if (const char* file = str(match, FC_FILE)) {
    for (int n = 0; const char* fam = str(match, FC_FAMILY, n); ++n)
      exact = exact || base::equalsNoCase(fam, family);
    const bool synthBold =
        bold && integer(match, FC_WEIGHT, FC_WEIGHT_REGULAR) < FC_WEIGHT_DEMIBOLD;
    const bool synthOblique = italic && integer(match, FC_SLANT, FC_SLANT_ROMAN) == FC_SLANT_ROMAN;
    face = openFace(file, integer(match, FC_INDEX, 0), synthBold, synthOblique);
  }
  FcPatternDestroy(match);
  if (face == kNoFace) exact = false;
  return face;
}

std::uint32_t FontLibrary::Impl::faceForChar(std::uint32_t primary, std::uint32_t c) {
  if (primary >= faces.size()) return kNoFace;
  if (FT_Get_Char_Index(faces[primary].ft, c) != 0) return primary;
  const auto key = std::make_pair(primary, c);
  if (auto it = fallbackByChar.find(key); it != fallbackByChar.end()) return it->second;
  std::uint32_t found = kNoFace;
  if (fontconfigReady) {
    const FaceInfo& info = faces[primary].info;
    FcPattern* pat = stylePattern(false, false, "");
    FcPatternAddString(pat, FC_FAMILY, reinterpret_cast<const FcChar8*>(info.family.c_str()));
    FcCharSet* cs = FcCharSetCreate();
    FcCharSetAddChar(cs, static_cast<FcChar32>(c));
    FcPatternAddCharSet(pat, FC_CHARSET, cs);
    FcCharSetDestroy(cs);
    FcConfigSubstitute(nullptr, pat, FcMatchPattern);
    FcDefaultSubstitute(pat);
    FcResult result = FcResultNoMatch;
    FcFontSet* set = FcFontSort(nullptr, pat, FcFalse, nullptr, &result);
    FcPatternDestroy(pat);
    for (int i = 0; set != nullptr && i < set->nfont && found == kNoFace; ++i) {
      FcCharSet* has = nullptr;
      if (FcPatternGetCharSet(set->fonts[i], FC_CHARSET, 0, &has) != FcResultMatch ||
          !FcCharSetHasChar(has, static_cast<FcChar32>(c)))
        continue;
      const char* file = str(set->fonts[i], FC_FILE);
      if (file == nullptr) continue;
      const std::uint32_t f = openFace(file, integer(set->fonts[i], FC_INDEX, 0),
                                       info.syntheticBold, info.syntheticOblique);
      if (f != kNoFace && FT_Get_Char_Index(faces[f].ft, c) != 0) found = f;
    }
    if (set != nullptr) FcFontSetDestroy(set);
  }
  fallbackByChar[key] = found;
  return found;
}

std::uint32_t FontLibrary::Impl::resolveLocked(const std::vector<std::string>& family,
                                               const std::string& style,
                                               const std::string& language,
                                               std::vector<std::string>& warnings) {
  bool bold = false, italic = false;
  if (base::equalsNoCase(style, "BOLD")) {
    bold = true;
  } else if (base::equalsNoCase(style, "ITALIC")) {
    italic = true;
  } else if (base::equalsNoCase(style, "BOLDITALIC")) {
    bold = italic = true;
  } else if (!style.empty() && !base::equalsNoCase(style, "PLAIN")) {
    warnings.push_back("FontStyle: unknown style \"" + style + "\"; PLAIN used");
  }
  std::string key = style + "|" + language;
  for (const std::string& f : family) key += "|" + f;
  if (auto it = resolved.find(key); it != resolved.end()) return it->second;

  std::uint32_t face = kNoFace;
  bool exact = false;
  for (const std::string& name : family) {
    if (name.empty()) continue;
    if (const Generic* g = genericFamily(name)) {
      exact = false;
      if (g->preferred != nullptr) face = matchFamily(g->preferred, bold, italic, language, exact);
      if (!exact) face = matchFamily(g->dejavu, bold, italic, language, exact);
      if (!exact) face = matchFamily(g->fontconfig, bold, italic, language, exact);
      if (face == kNoFace) face = openFace(g->path, 0, bold, italic);
    } else {
      face = matchFamily(name, bold, italic, language, exact);
      if (!exact) {
        warnings.push_back("FontStyle: font family \"" + name + "\" is not installed");
        face = kNoFace;
      }
    }
    if (face != kNoFace) break;
  }
  if (face == kNoFace) {  // 6.20.2: the default family SERIF
    const Generic& serif = kGenerics[0];
    face = matchFamily(serif.preferred, bold, italic, language, exact);
    if (!exact) face = matchFamily(serif.dejavu, bold, italic, language, exact);
    if (face == kNoFace) face = matchFamily("serif", bold, italic, language, exact);
    for (const Generic& g : kGenerics)
      if (face == kNoFace) face = openFace(g.path, 0, bold, italic);
    if (face == kNoFace) warnings.push_back("Text: no font could be opened; text not drawn");
  }
  resolved[key] = face;
  return face;
}

const GlyphOutline& FontLibrary::Impl::outlineLocked(GlyphKey key) {
  static const GlyphOutline kEmpty;
  if (key.face >= faces.size()) return kEmpty;
  const std::uint64_t k = (std::uint64_t{key.face} << 32) | key.glyph;
  auto it = outlines.find(k);
  if (it == outlines.end())
    it = outlines.emplace(k, detail::decomposeGlyph(faces[key.face], key.glyph)).first;
  return it->second;
}

FontLibrary::FontLibrary() : impl_(std::make_unique<Impl>()) {
  if (FT_Init_FreeType(&impl_->ft) != 0) impl_->ft = nullptr;
  impl_->fontconfigReady = FcInit() == FcTrue;
}

FontLibrary::~FontLibrary() {
  for (detail::Face& f : impl_->faces) {
    if (f.hb != nullptr) hb_font_destroy(f.hb);
    if (f.ft != nullptr) FT_Done_Face(f.ft);
  }
  if (impl_->ft != nullptr) FT_Done_FreeType(impl_->ft);
}

const GlyphOutline& FontLibrary::outline(GlyphKey key) {
  const std::lock_guard lock(impl_->mutex);
  return impl_->outlineLocked(key);
}

FaceInfo FontLibrary::faceInfo(std::uint32_t face) {
  const std::lock_guard lock(impl_->mutex);
  return face < impl_->faces.size() ? impl_->faces[face].info : FaceInfo{};
}

std::uint32_t FontLibrary::resolveFace(const std::vector<std::string>& family,
                                       const std::string& style, const std::string& language,
                                       std::vector<std::string>& warnings) {
  const std::lock_guard lock(impl_->mutex);
  return impl_->resolveLocked(family, style, language, warnings);
}

std::size_t FontLibrary::cachedOutlineCount() const {
  const std::lock_guard lock(impl_->mutex);
  return impl_->outlines.size();
}

FontLibrary& sharedFontLibrary() {
  static FontLibrary library;
  return library;
}

}  // namespace gs::formats
