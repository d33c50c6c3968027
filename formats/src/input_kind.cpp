#include "formats/input_kind.hpp"

#include <array>
#include <filesystem>
#include <fstream>

#include "base/gzip.hpp"
#include "base/text.hpp"
#include "base/url.hpp"
#include "formats/dicom_reader.hpp"
#include "formats/tiff_reader.hpp"
#include "formats/vdb_reader.hpp"
#include "qnv/stream.hpp"
#include "qnv/tileset.hpp"

namespace gs::formats {

namespace {

struct Suffix {
  std::string_view text;
  InputKind kind;
};

// Longest first where one suffix ends another (".nii.gz" before ".gz" handling).
constexpr std::array kSuffixes = {
    Suffix{".wrl", InputKind::world},
    Suffix{".wrl.gz", InputKind::world},
    Suffix{".wrz", InputKind::world},
    Suffix{".qnv", InputKind::qnv},
    Suffix{".qnvt", InputKind::qnvTileset},
    Suffix{".compressed.ply", InputKind::gaussianSplats},
    Suffix{".splat", InputKind::gaussianSplats},
    Suffix{".spz", InputKind::gaussianSplats},
    Suffix{".sog", InputKind::gaussianSplats},
    Suffix{".las", InputKind::gaussianSplats},
    Suffix{".laz", InputKind::gaussianSplats},
    Suffix{".ply", InputKind::ply},
    Suffix{".ply.gz", InputKind::ply},
    Suffix{".obj", InputKind::obj},
    Suffix{".obj.gz", InputKind::obj},
    Suffix{".gltf", InputKind::gltf},
    Suffix{".gltf.gz", InputKind::gltf},
    Suffix{".glb", InputKind::gltf},
    Suffix{".glb.gz", InputKind::gltf},
    Suffix{".nrrd", InputKind::nrrd},
    Suffix{".nhdr", InputKind::nrrd},
    Suffix{".nii", InputKind::nifti},
    Suffix{".nii.gz", InputKind::nifti},
    Suffix{".dcm", InputKind::dicom},
    Suffix{".dicom", InputKind::dicom},
    Suffix{".tif", InputKind::tiff},
    Suffix{".tiff", InputKind::tiff},
    Suffix{".vdb", InputKind::vdb},
    // X3D (ISO/IEC 19776-1, -2, -5): XML, Classic VRML, JSON, and their gzip forms.
    Suffix{".x3d", InputKind::world},
    Suffix{".x3dv", InputKind::world},
    Suffix{".x3dj", InputKind::world},
    Suffix{".x3dz", InputKind::world},
    Suffix{".x3dvz", InputKind::world},
    Suffix{".x3d.gz", InputKind::world},
    Suffix{".x3dv.gz", InputKind::world},
    Suffix{".x3dj.gz", InputKind::world},
};

bool lineEndAt(std::string_view s, std::size_t i) {
  return i < s.size() && (s[i] == '\n' || s[i] == '\r');
}

InputKind sniffPlain(std::string_view head) {
  if (head.starts_with("#VRML V2.0") || head.starts_with("#X3D V")) return InputKind::world;
  // The X3D XML encoding: an XML declaration or DOCTYPE, then <X3D (ISO/IEC 19776-1 4.2).
  if (const std::size_t x3d = head.find("<X3D"); x3d != std::string_view::npos) {
    std::string_view before = head.substr(0, x3d);
    if (before.starts_with("\xEF\xBB\xBF")) before.remove_prefix(3);
    const std::size_t first = before.find_first_not_of(" \t\r\n");
    if (first == std::string_view::npos || before[first] == '<') return InputKind::world;
  }
  // The X3D JSON encoding (ISO/IEC 19776-5): '{', then the key "X3D" first, within the
  // first 64 bytes (a glTF's JSON starts with other keys).
  {
    std::string_view json = head.substr(0, 64);
    if (json.starts_with("\xEF\xBB\xBF")) json.remove_prefix(3);
    const std::size_t brace = json.find_first_not_of(" \t\r\n");
    if (brace != std::string_view::npos && json[brace] == '{') {
      const std::size_t key = json.find_first_not_of(" \t\r\n", brace + 1);
      if (key != std::string_view::npos && json.substr(key).starts_with("\"X3D\""))
        return InputKind::world;
      // PlayCanvas SOG's meta.json (its textures beside it): "count" and "means" come
      // first, before the codebooks (splats/readers.hpp, detectSplatFormat).
      if (head.find("\"means\"") != std::string_view::npos &&
          head.find("\"count\"") != std::string_view::npos)
        return InputKind::gaussianSplats;
    }
  }
  const auto& magic = qnv::kMagic;
  if (head.size() >= magic.size() &&
      std::equal(magic.begin(), magic.end(), head.begin(),
                 [](std::uint8_t m, char c) { return m == static_cast<std::uint8_t>(c); }))
    return InputKind::qnv;
  const auto& index = qnv::kTilesetMagic;
  if (head.size() >= index.size() &&
      std::equal(index.begin(), index.end(), head.begin(),
                 [](std::uint8_t m, char c) { return m == static_cast<std::uint8_t>(c); }))
    return InputKind::qnvTileset;
  if (head.starts_with("ply") && lineEndAt(head, 3)) {
    // A Gaussian splatting PLY: its vertex element has Gaussian properties, or it has
    // PlayCanvas's chunk element (compressed PLY).
    const std::size_t end = head.find("end_header");
    const std::string_view header = head.substr(0, end);
    for (std::string_view p : {" f_dc_0", " scale_0", " rot_0", "element chunk "})
      if (header.find(p) != std::string_view::npos) return InputKind::gaussianSplats;
    return InputKind::ply;
  }
  if (head.starts_with("NGSP")) return InputKind::gaussianSplats;  // SPZ (v4 raw; v2-v3 gzip)
  if (head.starts_with("LASF")) return InputKind::gaussianSplats;  // LAS / LAZ point clouds
  if (head.starts_with("glTF")) return InputKind::gltf;
  if (head.size() >= 8 && head.starts_with("NRRD000") && head[7] >= '1' && head[7] <= '5')
    return InputKind::nrrd;
  if (hasDicomMagic(head)) return InputKind::dicom;  // DICOM PS3.10 7.1
  if (hasTiffMagic(head)) return InputKind::tiff;    // TIFF 6.0 section 2, BigTIFF
  if (hasVdbMagic(head)) return InputKind::vdb;      // OpenVDB io::Archive's magic number
  if (head.size() >= 348) {
    const std::string_view m = head.substr(344, 4);
    if (m == std::string_view("n+1\0", 4) || m == std::string_view("ni1\0", 4))
      return InputKind::nifti;
  }
  return InputKind::unknown;
}

}  // namespace

bool isOpenableName(std::string_view name) {
  return kindFromName(name) != InputKind::unknown;
}

InputKind kindFromName(std::string_view name) {
  name = base::withoutQueryOrFragment(name);
  // A DICOMDIR (DICOM PS3.10 8.6) has no extension; the name is fixed.
  if (const std::size_t slash = name.find_last_of("/\\");
      base::endsWithNoCase(name, "DICOMDIR") &&
      (name.size() == 8 || (slash != std::string_view::npos && name.size() - slash == 9)))
    return InputKind::dicom;
  // PlayCanvas SOG's meta.json (its WebP images beside it): the name is fixed too.
  if (const std::size_t slash = name.find_last_of("/\\");
      base::endsWithNoCase(name, "meta.json") &&
      (name.size() == 9 || (slash != std::string_view::npos && name.size() - slash == 10)))
    return InputKind::gaussianSplats;
  for (const Suffix& s : kSuffixes)
    if (name.size() > s.text.size() && base::endsWithNoCase(name, s.text)) return s.kind;
  return InputKind::unknown;
}

InputKind kindFromContent(std::string_view head) {
  if (base::isGzip(head)) return sniffPlain(base::gunzipPrefix(head, kSniffBytes));
  return sniffPlain(head);
}

InputKind classifyInput(std::string_view name, std::string_view head) {
  const InputKind k = kindFromContent(head);
  return k != InputKind::unknown ? k : kindFromName(name);
}

InputKind classifyFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (isDicomPath(path)) return InputKind::dicom;
    std::size_t looked = 0;
    for (std::filesystem::directory_iterator it(path, ec), end; !ec && it != end && looked < 4096;
         it.increment(ec), ++looked) {
      const std::string name = it->path().filename().string();
      if (!name.starts_with(".") && kindFromName(name) == InputKind::tiff) return InputKind::tiff;
    }
    return kindFromName(path);
  }
  std::string head(kSniffBytes, '\0');
  std::ifstream in(path, std::ios::binary);
  if (in) {
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<std::size_t>(in.gcount()));
  } else {
    head.clear();
  }
  return classifyInput(path, head);
}

}  // namespace gs::formats
