#pragma once
// JPEG files (libjpeg / libjpeg-turbo): read as 8-bit grey, written from grey or RGB pixels.
// Reading decodes baseline and progressive JPEGs; colour (YCbCr) images are converted by the
// library to their luminance Y = 0.299 R + 0.587 G + 0.114 B (ITU-R BT.601, the JFIF colour
// transform), the same weights as read_png_gray8. CMYK and YCCK JPEGs are not supported.
// Pixels are row-major, row 0 at the top. Errors throw std::runtime_error naming the file.
#include <cstdint>
#include <span>
#include <string>

#include "drivers/image/png.h"

namespace sonarloop::image {

// Whether bytes start with the JPEG start-of-image marker (FF D8 FF).
bool looks_like_jpeg(std::span<const std::uint8_t> head);

// Reads a JPEG file as 8-bit grey. An image of more than max_pixels pixels is refused from its
// header (std::runtime_error naming its size), before anything is decoded.
Gray8 read_jpeg_gray8(const std::string& path, std::size_t max_pixels = kMaxImagePixels);

// Writes 8-bit pixels, `components` per pixel (1 grey, 3 RGB), at a quality of 1 to 100.
// Lossy: pixels read back differ by a few levels (exactly equal only for flat areas).
void write_jpeg(const std::string& path, int width, int height, int components,
                std::span<const std::uint8_t> pixels, int quality = 90);

}  // namespace sonarloop::image
