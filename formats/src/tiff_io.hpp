// A TIFF file or buffer open through libtiff with its messages collected instead of
// printed (formats/tiff_reader.hpp, formats/volume_slabs.hpp): pages of one grey sample.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "formats/volume_readers.hpp"

typedef struct tiff TIFF;

namespace gs::formats::detail {

// The size and sample type of one slice image.
struct SliceShape {
  std::uint32_t width = 0, height = 0;
  ScalarType type = ScalarType::uint8;
  bool operator==(const SliceShape&) const = default;
};

/// "64 x 64 uint8".
std::string shapeText(const SliceShape& s);

class TiffFile {
 public:
  /// Opens the file at `path`.
  explicit TiffFile(const std::string& path);
  /// Reads `bytes` (kept by the caller for the object's life); `name` names it in errors.
  TiffFile(std::string_view bytes, const std::string& name);
  ~TiffFile();
  TiffFile(const TiffFile&) = delete;
  TiffFile& operator=(const TiffFile&) = delete;

  [[noreturn]] void fail(const std::string& what) const;
  std::uint32_t pages();
  /// The shape of `page` (it becomes the current page); InputError for an unsupported one.
  SliceShape shape(std::uint32_t page);
  /// The first page's ImageDescription (OME-XML in an OME-TIFF); empty when none.
  std::string description();
  /// Whether `page`'s stored data (the sum of its strip or tile byte counts) can hold
  /// `sampleBytes`: at least that many when uncompressed, at most 1032 times as many
  /// (deflate's largest ratio) plus 1 MiB when compressed. InputError when not, so that a
  /// header cannot make the caller allocate far more than the file holds.
  void checkStoredBytes(std::uint32_t page, std::uint64_t sampleBytes);
  /// Reads `page` (whose shape must be `expect`) into `out` (width * height floats).
  void read(std::uint32_t page, const SliceShape& expect, float* out);

  struct Memory {
    std::string_view bytes;
    std::uint64_t at = 0;
  };

 private:
  void open(const char* mode);
  std::string name_;
  std::string message_;
  Memory memory_;
  std::uint64_t fileBytes_ = 0;
  bool inMemory_ = false;
  TIFF* tif_ = nullptr;
};

}  // namespace gs::formats::detail
