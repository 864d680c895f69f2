#include "drivers/image/npy.h"

#include <catch2/catch.hpp>
#include <fstream>
#include <vector>

#include "tests/support/temp_dir.h"

using namespace sonarloop::image;

TEST_CASE("npy: round trip and numpy reads it") {
  sonarloop::testing::TempDir dir("npy");
  std::vector<float> v(3 * 5);
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = 0.25f * static_cast<float>(i) - 1.0f;
  const std::string path = dir.file("h.npy");
  write_npy_f32(path, 3, 5, v);
  const NpyF32 back = read_npy_f32(path);
  CHECK(back.rows == 3);
  CHECK(back.cols == 5);
  CHECK(back.data == v);
  // numpy itself agrees on shape, dtype and values (row 2, column 4 is the last element)
  const std::string py = std::string(SONARLOOP_PYTHON) +
                         " -c \"import numpy as n,sys; a=n.load(sys.argv[1]); "
                         "sys.exit(0 if a.shape==(3,5) and a.dtype==n.float32 and a[2,4]==2.5 "
                         "else 1)\" " +
                         path;
  CHECK(sonarloop::testing::run_command(py) == 0);
}

TEST_CASE("npy: bad files give clear errors") {
  sonarloop::testing::TempDir dir("npyerr");
  std::ofstream(dir.file("x.npy")) << "hello";
  CHECK_THROWS_WITH(read_npy_f32(dir.file("x.npy")), Catch::Contains("x.npy"));
  std::vector<float> v(2);
  CHECK_THROWS(write_npy_f32(dir.file("y.npy"), 3, 3, v));
}
