#include "drivers/image/png.h"

#include <catch2/catch.hpp>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "tests/support/temp_dir.h"

using namespace sonarloop::image;

TEST_CASE("png: 8-bit grey round trip") {
  sonarloop::testing::TempDir dir("png8");
  std::vector<std::uint8_t> px(37 * 21);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = static_cast<std::uint8_t>(i * 7);
  write_png_gray8(dir.file("a.png"), 37, 21, px);
  const Gray8 back = read_png_gray8(dir.file("a.png"));
  REQUIRE(back.width == 37);
  REQUIRE(back.height == 21);
  CHECK(back.pixels == px);
}

TEST_CASE("png: 16-bit grey keeps the top byte when read as 8-bit") {
  sonarloop::testing::TempDir dir("png16");
  std::vector<std::uint16_t> px = {0x0000, 0x1234, 0xABCD, 0xFFFF};
  write_png_gray16(dir.file("b.png"), 2, 2, px);
  const Gray8 back = read_png_gray8(dir.file("b.png"));
  REQUIRE(back.pixels.size() == 4);
  CHECK(back.pixels[1] == 0x12);
  CHECK(back.pixels[2] == 0xAB);
  CHECK(back.pixels[3] == 0xFF);
}

TEST_CASE("png: RGB is read back as BT.601 luma") {
  sonarloop::testing::TempDir dir("pngrgb");
  std::vector<std::uint8_t> rgb = {255, 0, 0, 0, 255, 0, 0, 0, 255, 200, 200, 200};
  write_png_rgb8(dir.file("c.png"), 4, 1, rgb);
  const Gray8 back = read_png_gray8(dir.file("c.png"));
  CHECK(std::abs(back.pixels[0] - 76) <= 1);
  CHECK(std::abs(back.pixels[1] - 150) <= 1);
  CHECK(std::abs(back.pixels[2] - 29) <= 1);
  CHECK(std::abs(back.pixels[3] - 200) <= 1);
}

TEST_CASE("png: errors name the file") {
  sonarloop::testing::TempDir dir("pngerr");
  CHECK_THROWS_WITH(read_png_gray8(dir.file("missing.png")), Catch::Contains("missing.png"));
  std::ofstream(dir.file("junk.png")) << "not a png";
  CHECK_THROWS_WITH(read_png_gray8(dir.file("junk.png")), Catch::Contains("not a PNG"));
  std::vector<std::uint8_t> px(3);
  CHECK_THROWS(write_png_gray8(dir.file("bad.png"), 2, 2, px));
}

namespace {

// CRC-32 of PNG chunks (ISO 3309, polynomial 0xEDB88320), bit by bit.
std::uint32_t crc32(const std::uint8_t* p, std::size_t n) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    c ^= p[i];
    for (int k = 0; k < 8; ++k)
      c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
  }
  return c ^ 0xFFFFFFFFu;
}

void put_be32(std::vector<std::uint8_t>& b, std::size_t at, std::uint32_t v) {
  for (int k = 0; k < 4; ++k)
    b[at + static_cast<std::size_t>(k)] = static_cast<std::uint8_t>(v >> (24 - 8 * k));
}

}  // namespace

TEST_CASE("png: an image over the pixel limit is refused from its header") {
  sonarloop::testing::TempDir dir("pnglimit");
  const std::vector<std::uint8_t> px(8 * 8, 7);
  write_png_gray8(dir.file("a.png"), 8, 8, px);
  CHECK(read_png_gray8(dir.file("a.png"), 64).pixels == px);  // at the limit: read
  CHECK_THROWS_WITH(read_png_gray8(dir.file("a.png"), 63),
                    Catch::Contains("a.png") && Catch::Contains("declares 8 x 8 pixels"));
  // a few hundred bytes whose header declares 20000 x 20000 pixels (400 MB of grey): refused by
  // default before anything is allocated for the pixels
  std::ifstream in(dir.file("a.png"), std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  REQUIRE(bytes.size() > 33);
  REQUIRE(std::string(bytes.begin() + 12, bytes.begin() + 16) == "IHDR");
  put_be32(bytes, 16, 20000);                             // width
  put_be32(bytes, 20, 20000);                             // height
  put_be32(bytes, 29, crc32(bytes.data() + 12, 4 + 13));  // the chunk's type and data
  std::ofstream(dir.file("bomb.png"), std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
  CHECK_THROWS_WITH(read_png_gray8(dir.file("bomb.png")),
                    Catch::Contains("declares 20000 x 20000 pixels"));
}
