// An RGB image (8 bits per channel, rows top to bottom) and writing it as PNG with Debian's
// libpng. Host-side: allocates, throws std::runtime_error naming the file.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrqp::sim {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  ///< width · height · 3, row-major from the top row

  RgbImage() = default;
  RgbImage(int w, int h)
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3, 0) {}
  std::uint8_t* row(int y) {
    return pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 3;
  }
  const std::uint8_t* row(int y) const {
    return pixels.data() + static_cast<std::size_t>(y) * static_cast<std::size_t>(width) * 3;
  }
};

void writePng(const std::string& path, const RgbImage& image);

/// Images side by side (same height), separated by `gap` pixels of a dark grey.
RgbImage horizontalStrip(const std::vector<RgbImage>& images, int gap = 4);

}  // namespace mrqp::sim
