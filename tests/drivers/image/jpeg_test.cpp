#include "drivers/image/jpeg.h"

#include <catch2/catch.hpp>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

using namespace sonarloop::image;

namespace {

// A smooth 8-bit gradient (JPEG keeps smooth images within a few levels).
std::vector<std::uint8_t> gradient(int w, int h) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c)
      px[static_cast<std::size_t>(r * w + c)] = static_cast<std::uint8_t>(40 + 2 * r + c);
  }
  return px;
}

int max_abs_diff(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  int d = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    d = std::max(d, std::abs(int{a[i]} - int{b[i]}));
  return d;
}

}  // namespace

TEST_CASE("jpeg: grey written with libjpeg reads back within a few levels") {
  sonarloop::testing::TempDir dir("jpeg8");
  const std::vector<std::uint8_t> px = gradient(40, 24);
  write_jpeg(dir.file("a.jpg"), 40, 24, 1, px, 95);
  const Gray8 back = read_jpeg_gray8(dir.file("a.jpg"));
  REQUIRE(back.width == 40);
  REQUIRE(back.height == 24);
  REQUIRE(back.pixels.size() == px.size());
  CHECK(max_abs_diff(back.pixels, px) <= 4);
  // a flat image is exact
  const std::vector<std::uint8_t> flat(16 * 8, 123);
  write_jpeg(dir.file("flat.jpg"), 16, 8, 1, flat);
  CHECK(read_jpeg_gray8(dir.file("flat.jpg")).pixels == flat);
}

TEST_CASE("jpeg: colour is read as its BT.601 luminance") {
  sonarloop::testing::TempDir dir("jpegrgb");
  // four flat 16 x 16 blocks: red, green, blue, grey (flat blocks survive compression)
  const int w = 64, h = 16;
  const std::uint8_t colours[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {200, 200, 200}};
  std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w * h * 3));
  for (int r = 0; r < h; ++r) {
    for (int c = 0; c < w; ++c) {
      for (int k = 0; k < 3; ++k)
        rgb[static_cast<std::size_t>((r * w + c) * 3 + k)] = colours[c / 16][k];
    }
  }
  write_jpeg(dir.file("c.jpg"), w, h, 3, rgb, 100);
  const Gray8 back = read_jpeg_gray8(dir.file("c.jpg"));
  REQUIRE(back.width == w);
  // centre pixel of each block: 0.299 R + 0.587 G + 0.114 B
  const int expected[4] = {76, 150, 29, 200};
  for (int b = 0; b < 4; ++b)
    CHECK(std::abs(back.at(8, 16 * b + 8) - expected[b]) <= 3);
}

TEST_CASE("jpeg: errors name the file") {
  sonarloop::testing::TempDir dir("jpegerr");
  CHECK_THROWS_WITH(read_jpeg_gray8(dir.file("missing.jpg")), Catch::Contains("missing.jpg"));
  std::ofstream(dir.file("junk.jpg")) << "not a jpeg";
  CHECK_THROWS_WITH(read_jpeg_gray8(dir.file("junk.jpg")), Catch::Contains("not a JPEG"));
  // a JPEG cut short after its header: the library's error, naming the file
  const std::vector<std::uint8_t> px = gradient(32, 32);
  write_jpeg(dir.file("whole.jpg"), 32, 32, 1, px);
  std::ifstream in(dir.file("whole.jpg"), std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir.file("cut.jpg"), std::ios::binary).write(bytes.data(), 20);
  CHECK_THROWS_WITH(read_jpeg_gray8(dir.file("cut.jpg")),
                    Catch::Contains("cut.jpg") && Catch::Contains("JPEG"));
  CHECK(looks_like_jpeg(std::vector<std::uint8_t>{0xFF, 0xD8, 0xFF, 0xE0}));
  CHECK_FALSE(looks_like_jpeg(std::vector<std::uint8_t>{0x89, 'P', 'N', 'G'}));
  CHECK_THROWS(write_jpeg(dir.file("bad.jpg"), 2, 2, 1, std::vector<std::uint8_t>(3)));
  CHECK_THROWS(write_jpeg(dir.file("bad.jpg"), 2, 2, 2, std::vector<std::uint8_t>(8)));
}

TEST_CASE("jpeg: a file cut in the middle of its image data is refused, not grey-filled") {
  sonarloop::testing::TempDir dir("jpegcut");
  const std::vector<std::uint8_t> px = gradient(64, 64);
  write_jpeg(dir.file("whole.jpg"), 64, 64, 1, px);
  std::ifstream in(dir.file("whole.jpg"), std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  REQUIRE(read_jpeg_gray8(dir.file("whole.jpg")).height == 64);
  // half the file: the header whole, the image data cut (libjpeg itself only warns)
  std::ofstream(dir.file("half.jpg"), std::ios::binary)
      .write(bytes.data(), static_cast<std::streamsize>(bytes.size() / 2));
  CHECK_THROWS_WITH(read_jpeg_gray8(dir.file("half.jpg")),
                    Catch::Contains("half.jpg") && Catch::Contains("truncated"));
}

TEST_CASE("jpeg: an image over the pixel limit is refused from its header") {
  sonarloop::testing::TempDir dir("jpeglimit");
  const std::vector<std::uint8_t> px = gradient(40, 24);
  write_jpeg(dir.file("a.jpg"), 40, 24, 1, px);
  CHECK(read_jpeg_gray8(dir.file("a.jpg"), 40 * 24).width == 40);  // at the limit: read
  CHECK_THROWS_WITH(read_jpeg_gray8(dir.file("a.jpg"), 40 * 24 - 1),
                    Catch::Contains("a.jpg") && Catch::Contains("declares 40 x 24 pixels") &&
                        Catch::Contains("more than the 959"));
  // the fuzzers' finding: 125 bytes declaring 65298 x 2301 pixels, refused by default
  const std::string found =
      std::string(SONARLOOP_SOURCE_DIR) + "/tests/fuzz/corpus/png_chip/huge_header.jpg";
  CHECK_THROWS_WITH(read_jpeg_gray8(found), Catch::Contains("declares 65298 x 2301 pixels"));
}
