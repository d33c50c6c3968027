// TIFF and OME-TIFF images as volumes, through libtiff (issue 42): one page per z slice.
//
// Sources: TIFF 6.0 (Adobe, 1992) and BigTIFF (libtiff 4), SampleFormat (TIFF 6.0 section
// 19); the OME data model and file format (OME-XML schema 2016-06, Pixels element:
// PhysicalSizeX/Y/Z and their units, SizeZ/C/T, DimensionOrder), stored in the first
// page's ImageDescription (OME-TIFF specification).
//
// Layout: x along the rows, y down the image (row 0 first), z the page order (the OME
// DimensionOrder's Z planes of the first channel and time point); the window's front view
// (render::volumeFrontOrientation) applies as to any stack.
//
// libtiff's error and warning handlers are replaced per file (TIFFOpenOptions), so libtiff
// prints nothing; its message, when there is one, ends ours in parentheses. Every size is
// checked before any allocation: a page of at most qnv::kMaxSliceVoxels, the whole at most
// qnv::kMaxVoxels, and libtiff's single allocations capped at 1 GiB.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "formats/volume_readers.hpp"

namespace gs::formats {

/// What the OME-XML of an OME-TIFF says about its first image (the first Pixels element).
struct OmePixels {
  bool found = false;  // an OME-XML Pixels element was read
  /// PhysicalSizeX, PhysicalSizeY, PhysicalSizeZ converted to micrometres (units Ym..ym,
  /// Å, thou, li, in, ft, yd, mi and their OME symbols; µm when no unit is given); 1 where
  /// a size is absent, not a positive number, or in a unit that is not a length (pixel,
  /// reference frame).
  glm::vec3 spacing{1, 1, 1};
  bool hasSpacing[3] = {false, false, false};
  std::uint64_t sizeZ = 1, sizeC = 1, sizeT = 1;  // each >= 1
  std::string dimensionOrder = "XYZCT";           // XY then a permutation of Z, C, T

  /// The page that holds slice z of channel 0 at time point 0 (pages run over the
  /// dimensions in DimensionOrder, the first fastest).
  std::uint64_t pageOfSlice(std::uint64_t z) const;
};

/// Parses the OME-XML `xml` (an ImageDescription; namespace prefixes such as "ome:" are
/// accepted). found = false when there is no Pixels element. Never throws: malformed
/// attributes leave their defaults.
OmePixels parseOmeXml(std::string_view xml);

/// Whether `head` starts with a TIFF header: "II*\0" or "MM\0*" (classic), "II+\0" or
/// "MM\0+" (BigTIFF).
bool hasTiffMagic(std::string_view head);

/// A TIFF read as a volume, with what its description said.
struct TiffVolume {
  Volume volume;            // dims = (width, height, slices); spacing from OME-XML, else 1
  OmePixels ome;            // found = false for a plain TIFF
  std::uint32_t pages = 0;  // pages in the file
};

/// Reads the TIFF in `bytes` (`name` names it in errors): every page a slice of one grey
/// sample (8, 16 or 32-bit unsigned or signed integers, 32 or 64-bit IEEE floats), striped
/// or tiled, any compression libtiff decodes; all pages of the first page's size and type.
/// With OME-XML, the slices are the SizeZ planes of channel 0 at time 0 and the spacing its
/// physical sizes (micrometres).
/// Throws InputError "name: cannot open as TIFF (libtiff: ...)", "name: TIFF slices with 3
/// samples per pixel are not supported (expected one grey sample)", "name: page 4 is 64 x
/// 64 uint8, expected 128 x 128 uint8 as the first slice", "name: the OME-XML describes 40
/// planes, the file has 10 pages (multi-file OME-TIFF is not supported)", and limits.
TiffVolume readTiff(std::string_view bytes, const std::string& name);

}  // namespace gs::formats
