#include "drivers/image/png.h"

#include <catch2/catch.hpp>
#include <fstream>
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
