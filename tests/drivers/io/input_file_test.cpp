// Inputs are regular files of a sane size (drivers/io/input_file.h): a FIFO is refused without
// blocking, a device, a folder, a symbolic link loop and a missing file are refused naming the
// path and what it is, a file over the limit naming its size; a regular file gives its size.
#include "drivers/io/input_file.h"

#include <sys/stat.h>
#include <unistd.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/temp_dir.h"

using namespace sonarloop;
using io::check_input_file;

TEST_CASE("input file: regular files pass with their size; anything else is refused, named") {
  testing::TempDir dir("input-file");
  { std::ofstream(dir.file("m.slpca")) << "12345"; }
  CHECK(check_input_file(dir.file("m.slpca"), "model file") == 5);
  // through a symbolic link too
  std::filesystem::create_symlink(dir.file("m.slpca"), dir.file("link.slpca"));
  CHECK(check_input_file(dir.file("link.slpca"), "model file") == 5);

  const auto refused = [](const std::string& path, const std::string& what) {
    INFO(path);
    CHECK_THROWS_WITH(check_input_file(path, "model file"),
                      Catch::Contains("model file '" + path + "'") && Catch::Contains(what));
  };
  // a FIFO: stat does not open it, so nothing blocks (no writer ever comes)
  REQUIRE(::mkfifo(dir.file("x.png").c_str(), 0600) == 0);
  refused(dir.file("x.png"), "not a regular file (a FIFO)");
  refused("/dev/zero", "not a regular file (a character device)");
  refused(dir.path().string(), "not a regular file (a directory)");
  refused(dir.file("missing"), "cannot open: No such file");
  std::filesystem::create_symlink(dir.file("loop_b"), dir.file("loop_a"));
  std::filesystem::create_symlink(dir.file("loop_a"), dir.file("loop_b"));
  refused(dir.file("loop_a"), "Too many levels of symbolic links");
  // over the limit: a sparse file of 3 GB, refused by its size before any byte is read
  { std::ofstream(dir.file("big.slpca")); }
  std::filesystem::resize_file(dir.file("big.slpca"), 3'000'000'000ull);
  CHECK_THROWS_WITH(check_input_file(dir.file("big.slpca"), "model file", 1'000'000'000),
                    Catch::Contains("3.0 GB, more than the 1.0 GB a model file may be"));
  CHECK(check_input_file(dir.file("big.slpca"), "model file") == 3'000'000'000ull);
}
