#include "image_jpeg.hpp"

#include <csetjmp>
#include <cstdio>

#include <jpeglib.h>

namespace gs::render::detail {
namespace {

// libjpeg reports fatal errors through error_exit, which must not return: it jumps back
// to decodeInto's setjmp. Warnings are not printed.
struct ErrorManager {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void onError(j_common_ptr info) {
  auto* e = reinterpret_cast<ErrorManager*>(info->err);
  (*info->err->format_message)(info, e->message);
  std::longjmp(e->jump, 1);
}

void onMessage(j_common_ptr) {}

// No C++ object with a destructor lives in this frame between setjmp and longjmp.
// Returns 0 on success, 1 on a libjpeg error (message in err), 2 when a side is too
// large, 3 for an unsupported colour space, 4 for too many pixels.
int decodeInto(jpeg_decompress_struct& info, ErrorManager& err, const unsigned char* data,
               unsigned long size, int maxSide, std::size_t maxPixels,
               std::vector<std::uint8_t>& rgba) {
  if (setjmp(err.jump)) return 1;
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, data, size);
  jpeg_read_header(&info, TRUE);
  if (info.image_width == 0 || info.image_height == 0 ||
      info.image_width > static_cast<JDIMENSION>(maxSide) ||
      info.image_height > static_cast<JDIMENSION>(maxSide))
    return 2;
  if (static_cast<std::size_t>(info.image_width) * info.image_height > maxPixels) return 4;
  if (info.jpeg_color_space == JCS_CMYK || info.jpeg_color_space == JCS_YCCK) return 3;
  info.out_color_space = JCS_EXT_RGBA;
  jpeg_start_decompress(&info);
  rgba.resize(static_cast<std::size_t>(info.output_width) * info.output_height * 4);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row =
        rgba.data() + static_cast<std::size_t>(info.output_scanline) * info.output_width * 4;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  return 0;
}

}  // namespace

bool looksLikeJpeg(std::string_view bytes) {
  return bytes.size() >= 3 && static_cast<unsigned char>(bytes[0]) == 0xFF &&
         static_cast<unsigned char>(bytes[1]) == 0xD8 &&
         static_cast<unsigned char>(bytes[2]) == 0xFF;
}

bool decodeJpeg(std::string_view bytes, int maxSide, std::size_t maxPixels,
                std::vector<std::uint8_t>& rgba, int& width, int& height, int& components,
                std::string& error) {
  jpeg_decompress_struct info{};
  ErrorManager err{};
  info.err = jpeg_std_error(&err.pub);
  err.pub.error_exit = onError;
  err.pub.output_message = onMessage;
  const int rc = decodeInto(info, err, reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<unsigned long>(bytes.size()), maxSide, maxPixels, rgba);
  width = static_cast<int>(info.image_width);
  height = static_cast<int>(info.image_height);
  components = info.num_components == 1 ? 1 : 3;
  jpeg_destroy_decompress(&info);
  if (rc == 1) error = err.message;
  if (rc == 2) error = "size";
  if (rc == 3) error = "CMYK JPEG is not supported";
  if (rc == 4) error = "pixels";
  if (rc != 0) rgba.clear();
  return rc == 0;
}

}  // namespace gs::render::detail
