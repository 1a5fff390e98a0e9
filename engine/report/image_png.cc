#include "engine/report/image_png.h"

#include <cairo.h>

#include <memory>

#include "engine/core/error.h"
#include "engine/core/files.h"

namespace recon::report {

void WritePng(const RgbImage& image, const std::string& path) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * image.height * 3) {
    throw std::invalid_argument("WritePng: the image's size and pixel count disagree");
  }
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surface(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height),
      cairo_surface_destroy);
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int r = 0; r < image.height; ++r) {
    auto* row = reinterpret_cast<uint32_t*>(data + static_cast<size_t>(r) * stride);
    for (int c = 0; c < image.width; ++c) {
      const uint8_t* px = image.Pixel(r, c);
      row[c] = (uint32_t{px[0]} << 16) | (uint32_t{px[1]} << 8) | uint32_t{px[2]};
    }
  }
  cairo_surface_mark_dirty(surface.get());
  // Encoded in memory and written by WriteFileAtomically, which says why a write failed (a full
  // disk) and never leaves a temporary behind.
  std::string png;
  const cairo_status_t status = cairo_surface_write_to_png_stream(
      surface.get(),
      [](void* closure, const unsigned char* bytes, unsigned int length) {
        static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(bytes), length);
        return CAIRO_STATUS_SUCCESS;
      },
      &png);
  if (status != CAIRO_STATUS_SUCCESS) {
    throw UserError("cannot encode the image " + path + ": " + cairo_status_to_string(status));
  }
  WriteFileAtomically(path, png);
}

}  // namespace recon::report
