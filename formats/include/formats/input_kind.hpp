// The one input classifier: what a file or URL holds, decided the same way by the
// command line, the window's open dialog, the session and the mesh and volume loaders.
// Content wins over the name: recognised leading bytes ("magic") decide when present,
// so a file without an extension, or with one that lies, opens as what it is; the name
// (extension, any case, URL query and fragment ignored) decides otherwise.
#pragma once

#include <string>
#include <string_view>

namespace gs::formats {

enum class InputKind {
  unknown,     // nothing recognised (the caller decides; the session parses it as VRML97)
  world,       // VRML97 (.wrl, .wrl.gz, .wrz; content "#VRML V2.0") and X3D (.x3d, .x3dv,
               // .x3dj, .x3dz, .x3dvz, .x3d.gz, .x3dv.gz; content "#X3D V" or "<X3D")
  qnv,         // QNV stream: .qnv; content the QNV signature (docs/qnv-format.md)
  qnvTileset,  // QNV tileset index: .qnvt; content its signature "\x89QNT\r\n\x1a\n"
  ply,         // .ply[.gz]; content "ply" + line end
  obj,         // Wavefront OBJ: .obj[.gz] (no magic)
  gltf,        // .gltf[.gz], .glb[.gz]; content "glTF" (GLB)
  nrrd,        // .nrrd, .nhdr; content "NRRD0001".."NRRD0005"
  nifti,       // .nii, .nii.gz; content "n+1\0" or "ni1\0" at byte 344
  /// DICOM (formats/dicom_reader.hpp): .dcm, .dicom, a file named DICOMDIR; content "DICM"
  /// at byte 128; classifyFile also takes a folder holding DICOM files or a DICOMDIR.
  dicom,
  /// TIFF and OME-TIFF volumes (formats/tiff_reader.hpp): .tif, .tiff (.ome.tif, .ome.tiff);
  /// content "II*\0", "MM\0*" or BigTIFF's "II+\0", "MM\0+"; classifyFile also takes a
  /// folder holding .tif or .tiff files (a stack of single-page slices).
  tiff,
  /// OpenVDB sparse grids (formats/vdb_reader.hpp): .vdb; content OpenVDB's magic number
  /// (bytes 20 42 44 56 00 00 00 00).
  vdb,
  /// A 3D Gaussian splatting scene (docs/splats.md): a PLY whose header (in the sniffed
  /// bytes) has Gaussian properties (f_dc_0, scale_0, rot_0) or PlayCanvas's chunk element,
  /// SPZ (content "NGSP", raw or gzip), .splat, .spz, .sog, .compressed.ply by name; an
  /// ASPRS LAS point cloud (content "LASF"; .las, .laz), drawn as splats too.
  /// A glTF using KHR_gaussian_splatting is `gltf` here (session/ looks inside).
  gaussianSplats,
};

/// The kind the name says: `name` is a path or URL; its extension (case-insensitive,
/// after removing "?query" and "#fragment") decides. unknown when none matches.
InputKind kindFromName(std::string_view name);

/// Whether a file of this name is one the program opens, by name alone (kindFromName is
/// not unknown): what the window's File > Open dialog lists (worlds, QNV streams and
/// tilesets, meshes, volumes, Gaussian splatting scenes; issue 42, friction 6).
bool isOpenableName(std::string_view name);

/// The kind the leading bytes `head` say (at least 352 bytes are needed to see NIfTI-1;
/// fewer are fine for the others). gzip data are inflated (their first bytes only) and
/// the result sniffed. unknown when nothing is recognised.
InputKind kindFromContent(std::string_view head);

/// kindFromContent(head), else kindFromName(name).
InputKind classifyInput(std::string_view name, std::string_view head);

/// classifyInput for the local file `path` (its first bytes are read; a file that cannot
/// be read is classified by name alone); a folder is dicom when it holds a DICOMDIR or a
/// DICOM file (formats::isDicomPath), else tiff when it holds a .tif or .tiff file, else
/// classified by name. Never throws.
InputKind classifyFile(const std::string& path);

/// How many leading bytes kindFromContent wants.
inline constexpr std::size_t kSniffBytes = 512;

/// PLY, OBJ and glTF.
constexpr bool isMesh(InputKind k) {
  return k == InputKind::ply || k == InputKind::obj || k == InputKind::gltf;
}
/// NRRD, NIfTI-1, DICOM, TIFF and OpenVDB.
constexpr bool isVolume(InputKind k) {
  return k == InputKind::nrrd || k == InputKind::nifti || k == InputKind::dicom ||
         k == InputKind::tiff || k == InputKind::vdb;
}
/// Inputs shown as QNV splats or as a world made for them (no Viewpoint of their own):
/// QNV streams and tilesets, PLY and OBJ meshes, volumes and Gaussian splatting scenes. glTF opens
/// as a world of its own (its nodes, materials, cameras, lights and animations; docs/gltf.md),
/// though `encode` still reads it as a mesh.
constexpr bool isSplatKind(InputKind k) {
  return k == InputKind::qnv || k == InputKind::qnvTileset || k == InputKind::ply ||
         k == InputKind::obj || isVolume(k) || k == InputKind::gaussianSplats;
}

}  // namespace gs::formats
