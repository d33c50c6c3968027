// `ghostspace info INPUT`: what was read, how big it is, how long parsing took.
#include "app/commands.hpp"
#include "base/file.hpp"
#include "formats/dicom_reader.hpp"
#include "formats/input_kind.hpp"
#include "formats/tiff_reader.hpp"
#include "formats/vdb_reader.hpp"
#include "qnv/tileset.hpp"
#include "scene/traversal.hpp"
#include "session/splat_inputs.hpp"
#include "session/volume_input.hpp"
#include "session/world.hpp"
#include "vrml/node_support.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace gs::app {

namespace {

// `info index.qnvt` (or its folder): the tileset's bounds, vectors, bricks and levels
// (docs/tilesets.md; issue 42, friction 7).
int runTilesetInfo(const std::string& path) {
  std::string bytes, error;
  if (!base::readFile(path, bytes, error)) {
    std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
    return 1;
  }
  const std::optional<qnv::TilesetIndex> index = qnv::parseTilesetIndex(bytes, path, error);
  if (!index) {
    std::fprintf(stderr, "ghostspace: %s\n", error.c_str());
    return 1;
  }
  const qnv::StreamHeader& h = index->header;
  const bool gaussian = h.kind == qnv::StreamKind::gaussian;
  const std::uint64_t words = h.recordsPerElement();  // records a splat (1: a vector)
  const char* unit = gaussian ? "splats" : "vectors";
  std::printf("%s: QNV tileset, %s\n", path.c_str(),
              h.kind == qnv::StreamKind::volume ? "volume"
              : gaussian ? ("Gaussian splats, SH degree " + std::to_string(h.shDegree)).c_str()
                         : "surface");
  std::printf("  bounds      %g %g %g .. %g %g %g\n", h.boundsMin.x, h.boundsMin.y, h.boundsMin.z,
              h.boundsMax.x, h.boundsMax.y, h.boundsMax.z);
  if (h.kind == qnv::StreamKind::volume)
    std::printf("  volume      %u x %u x %u voxels, spacing %g %g %g\n", h.volumeDims.x,
                h.volumeDims.y, h.volumeDims.z, h.voxelSpacing.x, h.voxelSpacing.y,
                h.voxelSpacing.z);
  std::uint64_t brickBytes = 0;
  for (const qnv::TilesetBrick& b : index->bricks) brickBytes += b.fileBytes;
  std::printf("  %-10s  %llu in %zu bricks, depth %u (levels 0..%u)\n", unit,
              static_cast<unsigned long long>(h.vectorCount / words), index->bricks.size(),
              static_cast<unsigned>(index->depth), static_cast<unsigned>(index->depth));
  std::printf("  bytes       %llu in bricks, %zu in the index\n",
              static_cast<unsigned long long>(brickBytes), bytes.size());
  for (unsigned level = 0; level <= index->depth; ++level) {
    std::size_t bricks = 0;
    std::uint64_t vectors = 0;
    for (const qnv::TilesetBrick& b : index->bricks)
      if (b.level == level) {
        ++bricks;
        vectors += b.vectorCount;
      }
    std::printf("  level %-4u  %zu bricks, %llu %s\n", level, bricks,
                static_cast<unsigned long long>(vectors / words), unit);
  }
  return 0;
}

// `info` on a DICOM file, series folder or DICOMDIR: the volume's grid, values and what
// the files say (modality, rescale, window presets, orientation; formats/dicom_reader.hpp).
int runDicomInfo(const std::string& path) {
  formats::DicomVolume d;
  try {
    d = formats::loadDicom(path);
  } catch (const qnv::InputError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  const qnv::Volume& v = d.volume;
  float lo = 0.0f, hi = 0.0f;
  if (!v.samples.empty()) {
    const auto [a, b] = std::minmax_element(v.samples.begin(), v.samples.end());
    lo = *a, hi = *b;
  }
  std::printf("%s\n", path.c_str());
  std::printf("  DICOM volume: %u x %u x %u voxels from %zu file%s, spacing %g %g %g mm\n",
              v.dims.x, v.dims.y, v.dims.z, d.files, d.files == 1 ? "" : "s", v.spacing.x,
              v.spacing.y, v.spacing.z);
  std::printf("  modality: %s, stored %s, transfer syntax %s\n",
              d.modality.empty() ? "(none)" : d.modality.c_str(),
              formats::scalarTypeName(v.sourceType), d.transferSyntax.c_str());
  std::printf("  values: %g .. %g%s%s (rescale slope %g, intercept %g)\n", lo, hi,
              d.rescaleType.empty() ? "" : " ", d.rescaleType.c_str(), d.slope, d.intercept);
  if (d.windows.empty()) std::printf("  windows: none\n");
  for (const formats::DicomWindow& w : d.windows)
    std::printf("  window: centre %g, width %g (%g .. %g)%s%s\n", w.center, w.width,
                w.center - w.width / 2, w.center + w.width / 2, w.explanation.empty() ? "" : " ",
                w.explanation.c_str());
  std::printf("  orientation (patient, LPS): x (%g %g %g), y (%g %g %g), z (%g %g %g)\n",
              d.rowDirection.x, d.rowDirection.y, d.rowDirection.z, d.columnDirection.x,
              d.columnDirection.y, d.columnDirection.z, d.sliceDirection.x, d.sliceDirection.y,
              d.sliceDirection.z);
  std::printf("  origin: (%g %g %g) mm\n", v.origin.x, v.origin.y, v.origin.z);
  for (const std::string& note : d.notes) std::printf("  note: %s\n", note.c_str());
  return 0;
}

// `info` on a TIFF or OME-TIFF file or a folder of TIFF slices: the volume's grid, sample
// type, values and what the OME-XML says (formats/tiff_reader.hpp).
int runTiffInfo(const std::string& path) {
  qnv::Volume v;
  formats::OmePixels ome;
  std::uint32_t pages = 0;
  try {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) {
      v = session::loadVolumeFile(path);
    } else {
      std::string bytes, error;
      if (!base::readFile(path, bytes, error)) throw qnv::InputError(error);
      formats::TiffVolume t = formats::readTiff(bytes, path);
      v = std::move(t.volume);
      ome = t.ome;
      pages = t.pages;
    }
  } catch (const qnv::InputError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  float lo = 0.0f, hi = 0.0f;
  if (!v.samples.empty()) {
    const auto [a, b] = std::minmax_element(v.samples.begin(), v.samples.end());
    lo = *a, hi = *b;
  }
  std::printf("%s\n", path.c_str());
  std::printf("  TIFF volume: %u x %u x %u voxels", v.dims.x, v.dims.y, v.dims.z);
  if (pages > 0) std::printf(" from %u page%s", pages, pages == 1 ? "" : "s");
  std::printf(", %s, spacing %g %g %g%s\n", formats::scalarTypeName(v.sourceType), v.spacing.x,
              v.spacing.y, v.spacing.z, ome.found ? " um" : "");
  std::printf("  values: %g .. %g\n", lo, hi);
  if (ome.found)
    std::printf(
        "  OME-XML: SizeZ %llu, SizeC %llu, SizeT %llu, DimensionOrder %s (channel 0, "
        "time 0 read)\n",
        static_cast<unsigned long long>(ome.sizeZ), static_cast<unsigned long long>(ome.sizeC),
        static_cast<unsigned long long>(ome.sizeT), ome.dimensionOrder.c_str());
  return 0;
}

// `info` on an OpenVDB file: the grid read and its active box (formats/vdb_reader.hpp).
int runVdbInfo(const std::string& path) {
  try {
    const auto reader = formats::openVdb(path);
    const formats::VdbGridSummary& s = reader->summary();
    const qnv::VolumeGridInfo& g = reader->info();
    std::printf("%s\n", path.c_str());
    std::printf("  OpenVDB grid '%s' (%s%s), 1 of %u grid%s, %llu active voxels\n", s.name.c_str(),
                s.valueType.c_str(), s.levelSet ? ", level set read as fog" : "", s.grids,
                s.grids == 1 ? "" : "s", static_cast<unsigned long long>(s.activeVoxels));
    std::printf("  active box: %u x %u x %u voxels, spacing %g %g %g, origin %g %g %g\n", g.dims.x,
                g.dims.y, g.dims.z, g.spacing.x, g.spacing.y, g.spacing.z, g.origin.x, g.origin.y,
                g.origin.z);
    if (g.valueRange)
      std::printf("  values: %g .. %g\n", g.valueRange->first, g.valueRange->second);
  } catch (const qnv::InputError& e) {
    std::fprintf(stderr, "ghostspace: %s\n", e.what());
    return 1;
  }
  return 0;
}

}  // namespace

int runInfo(const Options& options) {
  int status = 0;
  for (const std::string& input : options.inputs) {
    if (formats::classifyFile(input) == formats::InputKind::dicom) {
      status = std::max(status, runDicomInfo(input));
      continue;
    }
    if (formats::classifyFile(input) == formats::InputKind::tiff) {
      status = std::max(status, runTiffInfo(input));
      continue;
    }
    if (formats::classifyFile(input) == formats::InputKind::vdb) {
      status = std::max(status, runVdbInfo(input));
      continue;
    }
    if (formats::classifyFile(input) == formats::InputKind::qnv) {
      status = std::max(status, runQnvInfo(input));
      continue;
    }
    if (const std::string index = session::tilesetIndexOf(input); !index.empty()) {
      status = std::max(status, runTilesetInfo(index));
      continue;
    }
    // A capture (not a glTF world that also holds splats: described as a world).
    if (session::isGaussianSplatFile(input) && session::isSplatInput(input)) {
      status = std::max(status, runGaussianInfo(input));
      continue;
    }
    const session::LoadedWorld w = session::loadWorld(input);
    if (!w.readable) {
      for (const auto& d : w.scene->diagnostics.items)
        std::fprintf(stderr, "ghostspace: %s\n", d.format().c_str());
      status = 1;
      continue;
    }
    std::printf("%s\n", input.c_str());
    std::printf("  bytes: %zu\n", w.bytes);
    std::printf("  parse time: %.3f ms (%.1f MB/s)\n", w.parseSeconds * 1e3,
                w.parseSeconds > 0 ? static_cast<double>(w.bytes) / 1e6 / w.parseSeconds : 0.0);
    if (const vrml::X3dInfo& x = w.scene->x3d; !x.version.empty()) {
      // X3D: the encoding, profile and components the world declares, and which
      // components are not fully supported (docs/x3d.md).
      std::printf("  X3D %s, %s encoding, profile %s\n", x.version.c_str(), x.encoding.c_str(),
                  x.profile.empty() ? "(none)" : x.profile.c_str());
      for (const auto& [name, level] : x.components) {
        const auto missing = vrml::unimplementedNodes(name, level);
        std::printf("  component %s:%d: %s\n", name.c_str(), level,
                    !vrml::knownComponent(name) ? "unknown"
                    : missing.empty()           ? "supported"
                                                : "not fully supported (see diagnostics)");
      }
    }
    std::printf("  root nodes: %zu, routes: %zu, PROTO/EXTERNPROTO: %zu\n",
                w.scene->rootNodes.size(), w.scene->routes.size(), w.scene->protos.size());
    std::printf("  nodes by type:\n");
    for (const auto& [type, count] : session::countNodesByType(*w.scene))
      std::printf("    %-24s %zu\n", type.c_str(), count);

    scene::SceneTraversal traversal(w.scene);
    scene::TraversalFrame frame;
    traversal.collect(traversal.boundViewpointCamera(), frame);
    std::size_t triangles = 0;
    for (const auto& s : frame.shapes) triangles += traversal.mesh(*s.geometry).triangleCount();
    std::printf("  shapes drawn: %zu, triangles: %zu\n", frame.shapes.size(), triangles);
    const vrml::Bounds& b = traversal.worldBounds();
    if (b.empty()) {
      std::printf("  bounding box: empty\n");
    } else {
      std::printf("  bounding box: min (%g %g %g) max (%g %g %g) size (%g %g %g)\n", b.min.x,
                  b.min.y, b.min.z, b.max.x, b.max.y, b.max.z, b.size().x, b.size().y, b.size().z);
    }
    std::printf("  viewpoints: %zu\n", traversal.viewpoints().size());
    for (const auto& vp : traversal.viewpoints())
      std::printf("    \"%s\"\n", vp.description.c_str());
    const auto& diags = w.scene->diagnostics;
    const auto& tdiags = traversal.diagnostics();
    std::printf("  diagnostics: %zu errors, %zu warnings\n",
                diags.errorCount() + tdiags.errorCount(),
                diags.warningCount() + tdiags.warningCount());
    for (const auto* list : {&diags, &tdiags})
      for (const auto& d : list->items) std::printf("    %s\n", d.format().c_str());
    if (diags.errorCount() + tdiags.errorCount() > 0 && !options.infoExitZero) status = 1;
  }
  return status;
}

}  // namespace gs::app
