#pragma once
// NumPy .npy files (format version 1.0): little-endian float32 2-D arrays in C order, as
// numpy.load() reads them. Errors throw std::runtime_error naming the file.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

namespace sonarloop::image {

struct NpyF32 {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<float> data;  // (rows x cols), row-major
};

void write_npy_f32(const std::string& path, std::size_t rows, std::size_t cols,
                   std::span<const float> data);
NpyF32 read_npy_f32(const std::string& path);

}  // namespace sonarloop::image
