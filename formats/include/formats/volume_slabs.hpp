// Volume files read slab by slab (issue 13, part 2: out-of-core encoding): a run of whole
// z slices at a time, so that a volume larger than memory can be encoded. Memory is
// bounded by what one readSlices call asks for plus a fixed buffer (a few MiB), never by
// the volume.
//
// Sources:
//   - NRRD (.nrrd, .nhdr; formats/volume_readers.hpp's header parser), raw or gzip
//     encoding, attached or detached data, and teem's multi-file forms
//     "data file: FORMAT MIN MAX STEP [SUBDIM]" and "data file: LIST [SUBDIM]"
//     (http://teem.sourceforge.net/nrrd/format.html, section 3). gzip data are inflated
//     forward with zlib's streaming inflate, never whole; reading backwards restarts the
//     stream. ascii data are read whole (bounded by qnv::kMaxVoxels).
//   - NIfTI-1 single files (.nii and .nii.gz), readNifti's rules.
//   - DICOM files, series folders and DICOMDIRs (formats/dicom_reader.hpp), read whole
//     (GDCM decodes whole frames) and served as slabs; bounded by qnv::kMaxVoxels.
//   - OpenVDB grids (formats/vdb_reader.hpp): a child process reads the file and sends
//     the active box's slices forward; reading backwards starts it again.
//   - headerless raw files laid out as a RawLayout says (.gz: inflated forward).
//   - stacks of 2-D slices, one image per z: a folder (every .png, .tif, .tiff file in
//     it, in natural name order: "s2" before "s10"), a printf-style pattern
//     ("slices/ct_%04d.png": every index present in the folder, which must run without
//     gaps), or one multi-page TIFF (one page per slice). PNG through libpng (grey, 1 to
//     16 bits; grey + alpha drops the alpha), TIFF through libtiff (one sample per pixel:
//     8/16/32-bit unsigned or signed integers, 32/64-bit floats). All slices must have
//     the first one's size and type. Spacing 1, origin 0, except for OME-TIFF
//     (formats/tiff_reader.hpp): the physical sizes in micrometres, and for a multi-page
//     file the Z planes of channel 0 at time 0 in its DimensionOrder.
// Untrusted input: every size is checked against the file before any allocation; a grid
// may have up to qnv::kMaxSlabVolumeVoxels voxels and qnv::kMaxSliceVoxels per slice.
// Every error is qnv::InputError naming the file (and the byte offset of a bad read).
#pragma once

#include <memory>
#include <string>

#include "formats/volume_readers.hpp"
#include "qnv/volume_slabs.hpp"

namespace gs::formats {

using qnv::readWholeVolume;
using qnv::VolumeGridInfo;
using qnv::VolumeSlabReader;

/// Opens `path` for reading slab by slab. With `raw`, the file is a headerless raw grid
/// laid out as *raw says. Otherwise: a DICOM input (classifyFile says dicom) is read
/// whole by loadDicom; a folder or a path containing '%' is a slice stack;
/// .png / .tif / .tiff is a one-file stack (a multi-page TIFF gives one slice per page);
/// anything else is classified by formats::classifyFile (NRRD or NIfTI-1). Headers are
/// read at once, and the data files' sizes checked against the header (an uncompressed
/// file must hold every sample; compressed data must be able to hold them at deflate's
/// largest ratio, 1032:1); samples are read by readSlices.
/// Throws InputError for an unknown kind, a malformed header, a missing or short data or
/// slice file, sizes over the limits.
std::unique_ptr<VolumeSlabReader> openVolumeSlabs(const std::string& path,
                                                  const RawLayout* raw = nullptr);

}  // namespace gs::formats
