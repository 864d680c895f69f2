#pragma once
// PNG files (libpng): 8- and 16-bit greyscale and 8-bit RGB, written and read.
// Pixels are row-major, row 0 at the top. Errors throw std::runtime_error naming the file.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace sonarloop::image {

struct Gray8 {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // (height x width)
  std::uint8_t at(int row, int col) const {
    return pixels[static_cast<std::size_t>(row) * width + col];
  }
};

void write_png_gray8(const std::string& path, int width, int height,
                     std::span<const std::uint8_t> pixels);
void write_png_gray16(const std::string& path, int width, int height,
                      std::span<const std::uint16_t> pixels);
// rgb holds 3 bytes per pixel (R, G, B).
void write_png_rgb8(const std::string& path, int width, int height,
                    std::span<const std::uint8_t> rgb);

// Reads any PNG (grey, grey+alpha, RGB, RGBA, palette, 1-16 bit) as 8-bit grey.
// Colour is converted with the ITU-R BT.601 luma weights, 16-bit samples keep their top byte.
Gray8 read_png_gray8(const std::string& path);

}  // namespace sonarloop::image
