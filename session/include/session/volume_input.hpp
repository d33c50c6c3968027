// Volume files from disk: NRRD (attached or detached header), NIfTI-1 (.nii, .nii.gz),
// DICOM (formats/dicom_reader.hpp), TIFF (formats/tiff_reader.hpp) and headerless raw
// grids, read into qnv::Volume. The parsing is
// formats/volume_readers.hpp's; this layer reads the files, decompresses gzip and finds detached
// data files.
#pragma once

#include <string>

#include "formats/volume_readers.hpp"
#include "qnv/volume.hpp"

namespace gs::session {

/// Reads the volume file at `path`. A DICOM input (formats::classifyFile says dicom: a
/// file, a folder holding a series, or a DICOMDIR) is read by formats::loadDicom; a TIFF
/// file by formats::readTiff, a folder of TIFF slices by formats::openVolumeSlabs. A file
/// formats::classifyInput takes for NRRD (the NRRD magic, else the name .nrrd or .nhdr) is read as
/// NRRD: attached data follow the header; a detached "data file:" is looked for in the header's
/// folder only (an absolute path or a ".." component is refused, so that a header from elsewhere
/// cannot read arbitrary local files); gzip data are decompressed (at most the size the header
/// describes plus 1 MiB). Anything else is read as NIfTI-1, decompressed first when it is
/// gzip (.nii.gz).
/// Throws qnv::InputError naming the file for every problem: unreadable file, corrupt
/// gzip, malformed header, short data.
qnv::Volume loadVolumeFile(const std::string& path);

/// Reads the headerless raw volume at `path` laid out as `layout` says (decompressed
/// first when the name ends with .gz, any case). Throws qnv::InputError naming the file.
qnv::Volume loadRawVolumeFile(const std::string& path, const formats::RawLayout& layout);

}  // namespace gs::session
