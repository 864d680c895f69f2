// The PNG and JPEG chip reader (study/chip_folder.h, drivers/image/png.h, jpeg.h) on a file holding
// the input.
#include <exception>

#include "study/chip_folder.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string& path = fuzz::write_input_file(data, size, ".png");
  try {
    (void)study::read_chip_file(path);
  } catch (const std::exception&) {
  }
  return 0;
}
