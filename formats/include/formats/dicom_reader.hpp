// DICOM images as volumes (issue 42), read through GDCM (Grassroots DICOM, libgdcm-dev):
// one file (single- or multi-frame), a folder holding a series, or a DICOMDIR.
//
// Sources: DICOM PS3.10 (file format: 128-byte preamble, "DICM", file meta information),
// PS3.5 (data elements, transfer syntaxes), PS3.3 C.7.6.2 (Image Plane module: Image
// Position (Patient) (0020,0032), Image Orientation (Patient) (0020,0037), Pixel Spacing
// (0028,0030)), C.7.6.3 (Image Pixel module), C.11.1 (Modality LUT: Rescale Intercept
// (0028,1052), Rescale Slope (0028,1053), Rescale Type (0028,1054)), C.11.2 (VOI LUT:
// Window Center (0028,1050), Window Width (0028,1051)), F.3 (DICOMDIR records).
//
// Layout of the volume made (the front-view convention of render::volumeFrontOrientation,
// the one CThead has): x runs along the image rows (the first vector of Image Orientation
// (Patient), column index), y down the columns (the second vector, row index), and z
// through the slices in *decreasing* position along the slice normal n = row x column. For
// an axial series in the patient frame (LPS: x to the patient's left, y to the back, z up)
// row 0 is the front of the body and slice 0 the top, as in CThead, so the window opens on
// the face. The orientation itself is reported (DicomVolume::rowDirection, ...) and not
// otherwise applied: an oblique or sagittal series is shown in its own index frame.
//
// Untrusted input: a file's element structure is walked before GDCM sees it, and every
// value length is checked against the bytes that remain, so that GDCM never allocates
// more than the file holds; the decoded pixel buffer is capped by qnv::kMaxVoxels samples
// and by what the header's dimensions need. Every problem is InputError naming the file.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>

#include "formats/volume_readers.hpp"

namespace gs::formats {

/// A VOI LUT window (DICOM PS3.3 C.11.2.1.2): values in [center - width/2, center +
/// width/2] span the display range. In rescaled units (Hounsfield units for CT).
struct DicomWindow {
  float center = 0.0f;
  float width = 1.0f;       // > 0
  std::string explanation;  // Window Center & Width Explanation (0028,1055), may be empty
};

/// A DICOM image or series read as a volume, with what the files say about it.
struct DicomVolume {
  /// Samples after the Modality LUT rescale: value = stored * slope + intercept (Hounsfield
  /// units for CT). dims = (columns, rows, slices or frames); spacing in millimetres:
  /// (column spacing, row spacing from Pixel Spacing; the step between slice positions
  /// along the normal, not Slice Thickness); origin = the first slice's Image Position
  /// (Patient). sourceType: the stored sample type (int16 for most CT).
  Volume volume;
  std::string modality;     // (0008,0060), e.g. "CT", "MR"; may be empty
  std::string rescaleType;  // (0028,1054), or "HU" for CT when absent; may be empty
  float slope = 1.0f, intercept = 0.0f;
  /// Every window the first slice lists (Window Center/Width may be multi-valued), in
  /// file order; empty when none.
  std::vector<DicomWindow> windows;
  /// Image Orientation (Patient): the directions of increasing x and y in the patient
  /// frame (unit vectors, LPS), and z's (the negated slice normal; see the layout above).
  glm::vec3 rowDirection{1, 0, 0}, columnDirection{0, 1, 0}, sliceDirection{0, 0, -1};
  std::string transferSyntax;  // of the first file, e.g. "1.2.840.10008.1.2.4.80"
  std::size_t files = 0;       // image files read
  /// Things worth telling the user that did not stop the read: the series chosen among
  /// several, a fall-back to Instance Number order, uneven slice steps.
  std::vector<std::string> notes;
};

/// Whether `head` (a file's first bytes) has "DICM" at byte 128 (PS3.10 7.1).
bool hasDicomMagic(std::string_view head);

/// Reads the DICOM PS3.10 file in `bytes` (`name` names it in errors) as a volume of its
/// frames: a single-frame image gives dims.z = 1, a multi-frame one (Number of Frames
/// (0028,0008) > 1) one slice per frame, spaced by the frames' positions (enhanced
/// multi-frame), else Spacing Between Slices (0018,0088), else Slice Thickness, else 1.
/// Pixel data may be in any transfer syntax GDCM decodes: implicit or explicit VR little
/// endian, explicit big endian, RLE, JPEG (baseline, extended, lossless), JPEG-LS, JPEG
/// 2000. Greyscale only (Samples per Pixel 1; MONOCHROME1 values are kept as stored).
/// Throws InputError: "name: not a DICOM file (no 'DICM' at byte 128)", "name: not a DICOM
/// image (no Pixel Data)", "name: colour images (3 samples per pixel) are not read as
/// volumes; expected greyscale", "name: cannot decode pixel data in transfer syntax X",
/// "name: element (gggg,eeee) at byte N claims L bytes, the file has M left" and the like.
DicomVolume readDicom(std::string_view bytes, const std::string& name);

/// Reads `path` as a DICOM volume: a file (readDicom's rules), a DICOMDIR (every IMAGE
/// record's Referenced File ID (0004,1500), files inside the DICOMDIR's folder only), or
/// a folder (every file in it and below it, up to 100,000, that has the DICOM magic; a
/// DICOMDIR in it is used instead when present). The images of the series with the most
/// images (Series Instance UID (0020,000E)) that stacks (one size, one orientation,
/// distinct positions; a larger one that does not is skipped with a note) are sorted by Image
/// Position (Patient) along their slice normal and stacked (see the layout above); without
/// positions, by Instance Number (0020,0013), spaced by Spacing Between Slices or Slice Thickness
/// (a note says so). Throws InputError: "path: no DICOM images in the folder", "path: series has
/// slices of different sizes: a.dcm 512x512, b.dcm 256x256", "path: two slices at the same
/// position: a.dcm, b.dcm", "path: series mixes orientations: ...", readDicom's errors for a file.
DicomVolume loadDicom(const std::string& path);

/// Whether the local `path` is a DICOM input by content: a file with the magic, a folder
/// holding a DICOMDIR or a file with the magic (the first 64 regular files looked at).
/// Never throws.
bool isDicomPath(const std::string& path);

}  // namespace gs::formats
