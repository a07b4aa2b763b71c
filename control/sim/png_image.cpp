// PNG output through libpng (see png_image.hpp).
#include "sim/png_image.hpp"

#include <png.h>

#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace mrqp::sim {

void writePng(const std::string& path, const RgbImage& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::runtime_error(path + ": cannot write an empty image");
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) {
    throw std::runtime_error(path + ": cannot open for writing: " + std::strerror(errno));
  }
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    throw std::runtime_error(path + ": libpng could not start");
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    std::fclose(f);
    throw std::runtime_error(path + ": libpng failed while writing");
  }
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, const_cast<png_bytep>(image.row(y)));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  if (std::fclose(f) != 0) {
    throw std::runtime_error(path + ": cannot finish writing: " + std::strerror(errno));
  }
}

RgbImage horizontalStrip(const std::vector<RgbImage>& images, int gap) {
  if (images.empty()) {
    return {};
  }
  int width = 0;
  const int height = images.front().height;
  for (const RgbImage& im : images) {
    if (im.height != height) {
      throw std::runtime_error("image strip: images of different heights");
    }
    width += im.width;
  }
  width += gap * static_cast<int>(images.size() - 1);
  RgbImage out(width, height);
  std::memset(out.pixels.data(), 40, out.pixels.size());
  int x0 = 0;
  for (const RgbImage& im : images) {
    for (int y = 0; y < height; ++y) {
      std::memcpy(out.row(y) + static_cast<std::size_t>(x0) * 3, im.row(y),
                  static_cast<std::size_t>(im.width) * 3);
    }
    x0 += im.width + gap;
  }
  return out;
}

}  // namespace mrqp::sim
