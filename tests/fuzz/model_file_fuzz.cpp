// The classifier's model file decoder (atr/model_file.h), and a classification with what it
// accepts.
#include <exception>
#include <vector>

#include "atr/model_file.h"
#include "tests/fuzz/fuzz_support.h"

using namespace sonarloop;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    atr::Model m = atr::decode_model(fuzz::bytes(data, size), "fuzz");
    const int w = m.chip_width, h = m.chip_height;
    if (static_cast<long>(w) * h > 1'000'000) return 0;
    atr::Classifier c(std::move(m));
    std::vector<float> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    for (std::size_t i = 0; i < px.size(); ++i)
      px[i] = static_cast<float>(i % 7);
    (void)c.classify(atr::ChipView{w, h, px});
  } catch (const std::exception&) {
  }
  return 0;
}
