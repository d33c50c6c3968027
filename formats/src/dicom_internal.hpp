// What dicom_reader.cpp tells dicom_series.cpp about one DICOM file.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "formats/dicom_reader.hpp"

namespace gs::formats::detail {

/// One DICOM file read: its frames as a volume, and what stacking it with others needs.
struct DicomSlice {
  DicomVolume image;         // dims.z = number of frames
  bool hasPosition = false;  // Image Position (Patient) present
  glm::dvec3 position{0.0};  // of the first frame (mm, LPS)
  bool hasOrientation = false;
  glm::dvec3 row{1, 0, 0}, column{0, 1, 0};  // Image Orientation (Patient)
  std::string seriesUid;                     // (0020,000E); may be empty
  long long instance = 0;                    // Instance Number (0020,0013); 0 when absent
  double thickness = 0.0;                    // Slice Thickness (0018,0050); 0 when absent
  double between = 0.0;                      // Spacing Between Slices (0018,0088); 0 when absent
  std::string sopClass;                      // Media Storage SOP Class UID (0002,0002)
};

/// Reads one DICOM PS3.10 file (readDicom's rules).
DicomSlice readDicomSlice(std::string_view bytes, const std::string& name);

/// readDicom and loadDicom in this process; the public ones run these in a child process
/// (dicom_isolated.cpp): GDCM allocates lengths read from a file before it reads them.
DicomVolume readDicomHere(std::string_view bytes, const std::string& name);
DicomVolume loadDicomHere(const std::string& path);

/// What the file meta information says, after a walk over every element of the file that
/// checks each value length against the bytes left (see dicom_reader.hpp).
struct DicomMeta {
  std::string transferSyntax;      // (0002,0010), trailing NUL and spaces removed
  std::string sopClass;            // (0002,0002)
  std::size_t pixelDataBytes = 0;  // defined length of Pixel Data; 0 if encapsulated or none
  bool hasPixelData = false;
  bool encapsulated = false;
};

/// Walks `bytes` (a PS3.10 file). Throws InputError naming `name` for a missing magic, a
/// truncated element, a length beyond the file, nesting deeper than 16, or the deflated
/// transfer syntax.
DicomMeta scanDicomFile(std::string_view bytes, const std::string& name);

/// The Media Storage SOP Class of a DICOMDIR (PS3.10 8.6).
inline constexpr std::string_view kDicomdirSopClass = "1.2.840.10008.1.3.10";

/// Runs `step(argument)`, a call into GDCM, so that a failed assertion inside GDCM ends it
/// (returns false) instead of aborting the program (dicom_assert_guard.cpp). `step` must
/// catch every exception itself. After false, the GDCM objects `step` used are in no known
/// state: the caller leaks them rather than destroy them.
bool runGdcmGuarded(void (*step)(void*), void* argument);

/// Marks `object`, a GDCM object left by a failed assertion, as leaked on purpose (for
/// LeakSanitizer; nothing in other builds).
void leakGdcmObject(const void* object);

}  // namespace gs::formats::detail
