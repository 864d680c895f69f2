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

// The largest image the readers decode by default, width x height: 2^26 pixels (64 MiB of grey).
// A header declaring more is refused before any pixel is decoded, so that a corrupt or hostile
// file cannot make a reader allocate gigabytes (fuzzing found a 125-byte JPEG declaring
// 65298 x 2301 pixels: 150 Mpixels, 0.6 GB once converted to a float chip).
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;
// The largest image file the readers open (a regular file: drivers/io/input_file.h): 256 MB, far
// above any compressed image of kMaxImagePixels.
inline constexpr std::uint64_t kMaxImageFileBytes = std::uint64_t{256} << 20;

// Reads any PNG (grey, grey+alpha, RGB, RGBA, palette, 1-16 bit) as 8-bit grey.
// Colour is converted with the ITU-R BT.601 luma weights, 16-bit samples keep their top byte.
// An image of more than max_pixels pixels is refused (std::runtime_error naming its size).
Gray8 read_png_gray8(const std::string& path, std::size_t max_pixels = kMaxImagePixels);

// The error message of an image over the limit (both readers).
std::string too_many_pixels_message(const std::string& path, std::size_t width, std::size_t height,
                                    std::size_t max_pixels);

}  // namespace sonarloop::image
