// Volume files from disk: NRRD (attached or detached header), NIfTI-1 (.nii, .nii.gz) and
// headerless raw grids, read into qnv::Volume. The parsing is qnv's (qnv/volume_readers.hpp);
// this layer reads the files, decompresses gzip and finds detached data files.
#pragma once

#include <string>

#include "qnv/volume.hpp"
#include "qnv/volume_readers.hpp"

namespace gs::app {

/// True when `path` ends with .nrrd, .nhdr, .nii or .nii.gz (any case).
bool isVolumeFile(const std::string& path);

/// Reads the volume file at `path`. A file starting with the NRRD magic (or named .nrrd
/// or .nhdr) is read as NRRD: attached data follow the header; a detached "data file:"
/// is looked for in the header's folder only (an absolute path or a ".." component is
/// refused, so that a header from elsewhere cannot read arbitrary local files); gzip
/// data are decompressed (at most the size the header describes plus 1 MiB). Anything
/// else is read as NIfTI-1, decompressed first when it is gzip (.nii.gz).
/// Throws qnv::InputError naming the file for every problem: unreadable file, corrupt
/// gzip, malformed header, short data.
qnv::Volume loadVolumeFile(const std::string& path);

/// Reads the headerless raw volume at `path` laid out as `layout` says (decompressed
/// first when the name ends with .gz). Throws qnv::InputError naming the file.
qnv::Volume loadRawVolumeFile(const std::string& path, const qnv::RawLayout& layout);

}  // namespace gs::app
