#include "drivers/image/png.h"

#include <png.h>

#include <cstdio>
#include <memory>
#include <stdexcept>

#include "drivers/io/input_file.h"

namespace sonarloop::image {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

FilePtr open_or_throw(const std::string& path, const char* mode) {
  FilePtr f(std::fopen(path.c_str(), mode));
  if (!f) throw std::runtime_error("cannot open '" + path + "' (" + mode + ")");
  return f;
}

[[noreturn]] void png_error_fn(png_structp png, png_const_charp msg) {
  auto* path = static_cast<const std::string*>(png_get_error_ptr(png));
  throw std::runtime_error("PNG error in '" + *path + "': " + msg);
}

void png_warning_fn(png_structp, png_const_charp) {}

void check_size(const std::string& path, int width, int height, std::size_t n, std::size_t per) {
  if (width <= 0 || height <= 0 ||
      n != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * per) {
    throw std::runtime_error("cannot write '" + path + "': pixel buffer does not match " +
                             std::to_string(width) + "x" + std::to_string(height));
  }
}

// rows: pointers to each row's first byte; libpng only reads them.
void write_rows(const std::string& path, int width, int height, int bit_depth, int color_type,
                const std::uint8_t* data, std::size_t row_bytes, bool swap16) {
  FilePtr f = open_or_throw(path, "wb");
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, const_cast<std::string*>(&path),
                                            png_error_fn, png_warning_fn);
  if (!png) throw std::runtime_error("libpng: out of memory writing '" + path + "'");
  png_infop info = png_create_info_struct(png);
  struct Guard {
    png_structp* p;
    png_infop* i;
    ~Guard() { png_destroy_write_struct(p, i); }
  } guard{&png, &info};
  png_init_io(png, f.get());
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height),
               bit_depth, color_type, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT,
               PNG_FILTER_TYPE_DEFAULT);
  png_set_compression_level(png, 6);
  png_write_info(png, info);
  // PNG stores 16-bit samples big-endian; our buffers are host (little-endian) order
  if (swap16) png_set_swap(png);
  for (int r = 0; r < height; ++r) {
    png_write_row(png, data + static_cast<std::size_t>(r) * row_bytes);
  }
  png_write_end(png, nullptr);
  if (std::fflush(f.get()) != 0) throw std::runtime_error("write failed for '" + path + "'");
}

}  // namespace

void write_png_gray8(const std::string& path, int width, int height,
                     std::span<const std::uint8_t> pixels) {
  check_size(path, width, height, pixels.size(), 1);
  write_rows(path, width, height, 8, PNG_COLOR_TYPE_GRAY, pixels.data(),
             static_cast<std::size_t>(width), false);
}

void write_png_gray16(const std::string& path, int width, int height,
                      std::span<const std::uint16_t> pixels) {
  check_size(path, width, height, pixels.size(), 1);
  write_rows(path, width, height, 16, PNG_COLOR_TYPE_GRAY,
             reinterpret_cast<const std::uint8_t*>(pixels.data()),
             static_cast<std::size_t>(width) * 2, true);
}

void write_png_rgb8(const std::string& path, int width, int height,
                    std::span<const std::uint8_t> rgb) {
  check_size(path, width, height, rgb.size(), 3);
  write_rows(path, width, height, 8, PNG_COLOR_TYPE_RGB, rgb.data(),
             static_cast<std::size_t>(width) * 3, false);
}

std::string too_many_pixels_message(const std::string& path, std::size_t width, std::size_t height,
                                    std::size_t max_pixels) {
  return "'" + path + "' declares " + std::to_string(width) + " x " + std::to_string(height) +
         " pixels, more than the " + std::to_string(max_pixels) +
         " this reader accepts (a corrupt header, or not an image for this purpose)";
}

Gray8 read_png_gray8(const std::string& path, std::size_t max_pixels) {
  io::check_input_file(path, "image", kMaxImageFileBytes);
  FilePtr f = open_or_throw(path, "rb");
  unsigned char sig[8] = {};
  if (std::fread(sig, 1, 8, f.get()) != 8 || png_sig_cmp(sig, 0, 8) != 0) {
    throw std::runtime_error("'" + path + "' is not a PNG file");
  }
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, const_cast<std::string*>(&path),
                                           png_error_fn, png_warning_fn);
  if (!png) throw std::runtime_error("libpng: out of memory reading '" + path + "'");
  png_infop info = png_create_info_struct(png);
  struct Guard {
    png_structp* p;
    png_infop* i;
    ~Guard() { png_destroy_read_struct(p, i, nullptr); }
  } guard{&png, &info};
  png_init_io(png, f.get());
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  const std::size_t declared_width = png_get_image_width(png, info);
  const std::size_t declared_height = png_get_image_height(png, info);
  if (declared_width * declared_height > max_pixels) {
    throw std::runtime_error(
        too_many_pixels_message(path, declared_width, declared_height, max_pixels));
  }
  // normalise every colour type and depth to 8-bit grey without alpha
  const png_byte color = png_get_color_type(png, info);
  if (png_get_bit_depth(png, info) == 16) png_set_strip_16(png);
  if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color == PNG_COLOR_TYPE_GRAY && png_get_bit_depth(png, info) < 8) {
    png_set_expand_gray_1_2_4_to_8(png);
  }
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  if (color & PNG_COLOR_MASK_ALPHA || png_get_valid(png, info, PNG_INFO_tRNS)) {
    png_set_strip_alpha(png);
  }
  if (color == PNG_COLOR_TYPE_RGB || color == PNG_COLOR_TYPE_RGB_ALPHA ||
      color == PNG_COLOR_TYPE_PALETTE) {
    png_set_rgb_to_gray_fixed(png, 1, 29900, 58700);  // BT.601: 0.299 R + 0.587 G (+ 0.114 B)
  }
  png_read_update_info(png, info);
  Gray8 img;
  img.width = static_cast<int>(png_get_image_width(png, info));
  img.height = static_cast<int>(png_get_image_height(png, info));
  if (png_get_rowbytes(png, info) != static_cast<std::size_t>(img.width)) {
    throw std::runtime_error("'" + path + "': unsupported PNG layout");
  }
  img.pixels.resize(static_cast<std::size_t>(img.width) * img.height);
  for (int r = 0; r < img.height; ++r) {
    png_read_row(png, img.pixels.data() + static_cast<std::size_t>(r) * img.width, nullptr);
  }
  png_read_end(png, nullptr);
  return img;
}

}  // namespace sonarloop::image
