#include "drivers/image/npy.h"

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "drivers/io/input_file.h"

namespace sonarloop::image {

// Layout (numpy/lib/format.py, version 1.0): "\x93NUMPY", major 1, minor 0, u16 header length,
// an ASCII Python dict literal padded with spaces and ended by '\n' so that the data starts at
// a multiple of 64 bytes, then the raw array.
void write_npy_f32(const std::string& path, std::size_t rows, std::size_t cols,
                   std::span<const float> data) {
  if (data.size() != rows * cols) {
    throw std::runtime_error("cannot write '" + path + "': data size does not match shape");
  }
  std::string dict = "{'descr': '<f4', 'fortran_order': False, 'shape': (" + std::to_string(rows) +
                     ", " + std::to_string(cols) + "), }";
  const std::size_t preamble = 10;
  std::size_t total = preamble + dict.size() + 1;
  const std::size_t padded = (total + 63) / 64 * 64;
  dict.append(padded - total, ' ');
  dict.push_back('\n');
  const auto header_len = static_cast<std::uint16_t>(dict.size());
  std::ofstream out(path, std::ios::binary);
  if (!out) throw std::runtime_error("cannot open '" + path + "' for writing");
  out.write("\x93NUMPY\x01\x00", 8);
  const char len[2] = {static_cast<char>(header_len & 0xFF), static_cast<char>(header_len >> 8)};
  out.write(len, 2);
  out.write(dict.data(), static_cast<std::streamsize>(dict.size()));
  out.write(reinterpret_cast<const char*>(data.data()),
            static_cast<std::streamsize>(data.size() * sizeof(float)));
  out.flush();
  if (!out) throw std::runtime_error("write failed for '" + path + "'");
}

NpyF32 read_npy_f32(const std::string& path) {
  io::check_input_file(path, ".npy file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open '" + path + "'");
  char pre[10] = {};
  in.read(pre, 10);
  if (!in || std::memcmp(pre, "\x93NUMPY\x01", 7) != 0) {
    throw std::runtime_error("'" + path + "' is not a version 1 .npy file");
  }
  const std::size_t hlen = static_cast<unsigned char>(pre[8]) |
                           (static_cast<std::size_t>(static_cast<unsigned char>(pre[9])) << 8);
  std::string dict(hlen, '\0');
  in.read(dict.data(), static_cast<std::streamsize>(hlen));
  if (!in) throw std::runtime_error("'" + path + "': truncated .npy header");
  if (dict.find("'descr': '<f4'") == std::string::npos ||
      dict.find("'fortran_order': False") == std::string::npos) {
    throw std::runtime_error("'" + path + "': only little-endian float32 C-order arrays are read");
  }
  const auto open = dict.find("'shape': (");
  if (open == std::string::npos) throw std::runtime_error("'" + path + "': no shape in header");
  NpyF32 arr;
  if (std::sscanf(dict.c_str() + open + 10, "%zu, %zu", &arr.rows, &arr.cols) != 2) {
    throw std::runtime_error("'" + path + "': only 2-D arrays are read");
  }
  arr.data.resize(arr.rows * arr.cols);
  in.read(reinterpret_cast<char*>(arr.data.data()),
          static_cast<std::streamsize>(arr.data.size() * sizeof(float)));
  if (!in) throw std::runtime_error("'" + path + "': truncated .npy data");
  return arr;
}

}  // namespace sonarloop::image
