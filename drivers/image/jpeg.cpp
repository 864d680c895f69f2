#include "drivers/image/jpeg.h"

// jpeglib.h needs size_t and FILE declared before it
#include <csetjmp>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

#include <jpeglib.h>
// (after jpeglib.h: the message codes, JWRN_JPEG_EOF)
#include <jerror.h>

#include "drivers/io/input_file.h"

namespace sonarloop::image {
namespace {

// libjpeg reports errors through error_exit, which must not return. We leave the library with
// longjmp (no C++ exception crosses its C frames) and turn the message into an exception after
// the jump, in a frame that owns no object with a destructor between setjmp and longjmp.
struct ErrorManager {
  jpeg_error_mgr pub;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
  bool truncated;  // the data ended before the image (libjpeg's JWRN_JPEG_EOF warning)
};

void error_exit(j_common_ptr cinfo) {
  auto* err = reinterpret_cast<ErrorManager*>(cinfo->err);
  (*cinfo->err->format_message)(cinfo, err->message);
  std::longjmp(err->jump, 1);
}

// Warnings (e.g. a few corrupt bytes that the decoder worked around) are not fatal, and are not
// printed; but the data ending before the image is: libjpeg then fills the missing rows with grey
// and reports it as a warning only ("Premature end of JPEG file"), which would make half an image
// a valid chip.
void silent_output(j_common_ptr) {}
void note_message(j_common_ptr cinfo, int msg_level) {
  if (msg_level < 0 && cinfo->err->msg_code == JWRN_JPEG_EOF)
    reinterpret_cast<ErrorManager*>(cinfo->err)->truncated = true;
}

// The library's standard error handler, with our exit and no message output.
jpeg_error_mgr* use_error_manager(ErrorManager& err) {
  jpeg_std_error(&err.pub);
  err.pub.error_exit = error_exit;
  err.pub.output_message = silent_output;
  err.pub.emit_message = note_message;
  err.truncated = false;
  return &err.pub;
}

// Decodes `data` into out (sized here). Returns false with err.message set on failure; an image
// of more than max_pixels pixels sets only width and height (from its header) and returns false
// with an empty message. Plain C style on purpose: only trivially destructible locals live
// across setjmp.
bool decode(const std::uint8_t* data, std::size_t size, std::size_t max_pixels, ErrorManager& err,
            std::vector<std::uint8_t>& out, int& width, int& height) {
  jpeg_decompress_struct cinfo{};
  cinfo.err = use_error_manager(err);
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  if (static_cast<std::size_t>(cinfo.image_width) * cinfo.image_height > max_pixels) {
    width = static_cast<int>(cinfo.image_width);
    height = static_cast<int>(cinfo.image_height);
    jpeg_destroy_decompress(&cinfo);
    return false;
  }
  // colour images: the library keeps the luminance channel (YCbCr -> Y)
  cinfo.out_color_space = JCS_GRAYSCALE;
  jpeg_start_decompress(&cinfo);
  width = static_cast<int>(cinfo.output_width);
  height = static_cast<int>(cinfo.output_height);
  out.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = out.data() + static_cast<std::size_t>(cinfo.output_scanline) * width;
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return true;
}

bool encode(std::FILE* f, int width, int height, int components, const std::uint8_t* pixels,
            int quality, ErrorManager& err) {
  jpeg_compress_struct cinfo{};
  cinfo.err = use_error_manager(err);
  if (setjmp(err.jump)) {
    jpeg_destroy_compress(&cinfo);
    return false;
  }
  jpeg_create_compress(&cinfo);
  jpeg_stdio_dest(&cinfo, f);
  cinfo.image_width = static_cast<JDIMENSION>(width);
  cinfo.image_height = static_cast<JDIMENSION>(height);
  cinfo.input_components = components;
  cinfo.in_color_space = components == 1 ? JCS_GRAYSCALE : JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  jpeg_start_compress(&cinfo, TRUE);
  const std::size_t row_bytes = static_cast<std::size_t>(width) * components;
  while (cinfo.next_scanline < cinfo.image_height) {
    // libjpeg only reads the rows
    JSAMPROW row = const_cast<std::uint8_t*>(pixels) + cinfo.next_scanline * row_bytes;
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  return true;
}

}  // namespace

bool looks_like_jpeg(std::span<const std::uint8_t> head) {
  return head.size() >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
}

Gray8 read_jpeg_gray8(const std::string& path, std::size_t max_pixels) {
  io::check_input_file(path, "image", kMaxImageFileBytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "' (rb)");
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                        std::istreambuf_iterator<char>());
  if (in.bad()) throw std::runtime_error("cannot read '" + path + "'");
  if (!looks_like_jpeg(bytes)) throw std::runtime_error("'" + path + "' is not a JPEG file");
  Gray8 img;
  ErrorManager err{};
  if (!decode(bytes.data(), bytes.size(), max_pixels, err, img.pixels, img.width, img.height)) {
    if (err.message[0] == '\0') {
      throw std::runtime_error(too_many_pixels_message(path, static_cast<std::size_t>(img.width),
                                                       static_cast<std::size_t>(img.height),
                                                       max_pixels));
    }
    throw std::runtime_error("JPEG error in '" + path + "': " + err.message);
  }
  if (err.truncated) {
    throw std::runtime_error("'" + path + "' is a truncated JPEG file (the data ends before the " +
                             std::to_string(img.height) + " rows of the image)");
  }
  return img;
}

void write_jpeg(const std::string& path, int width, int height, int components,
                std::span<const std::uint8_t> pixels, int quality) {
  if (components != 1 && components != 3) {
    throw std::runtime_error("cannot write '" + path + "': components must be 1 or 3");
  }
  if (quality < 1 || quality > 100) {
    throw std::runtime_error("cannot write '" + path + "': quality must be 1 to 100");
  }
  if (width <= 0 || height <= 0 ||
      pixels.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                           static_cast<std::size_t>(components)) {
    throw std::runtime_error("cannot write '" + path + "': pixel buffer does not match " +
                             std::to_string(width) + "x" + std::to_string(height));
  }
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot open '" + path + "' (wb)");
  ErrorManager err{};
  const bool ok = encode(f, width, height, components, pixels.data(), quality, err);
  const bool flushed = std::fclose(f) == 0;
  if (!ok) throw std::runtime_error("JPEG error writing '" + path + "': " + err.message);
  if (!flushed) throw std::runtime_error("write failed for '" + path + "'");
}

}  // namespace sonarloop::image
