#include "study/chip_labels.h"

#include <algorithm>
#include <stdexcept>

#include "atr/chip_label_name.h"
#include "drivers/image/png.h"

namespace sonarloop::study {

void write_chip_label_png(const std::filesystem::path& dir, const std::string& chip_file_name,
                          const render::ChipImage& chip) {
  if (chip.labels.size() != chip.pixels.size()) {
    throw std::logic_error("chip " + std::to_string(chip.params.index) + " has no label image");
  }
  const std::string name = atr::chip_label_file_name(chip_file_name);
  const std::filesystem::path tmp = dir / ("." + name + ".tmp");
  image::write_png_gray8(tmp.string(), chip.cols, chip.rows, chip.labels);
  std::filesystem::rename(tmp, dir / name);
}

std::string chip_label_csv_fields(const std::string& chip_file_name,
                                  const render::ChipImage& chip) {
  const auto count = [&](std::uint8_t v) {
    return std::to_string(std::count(chip.labels.begin(), chip.labels.end(), v));
  };
  return atr::chip_label_file_name(chip_file_name) + "," + count(render::kLabelHighlight) + "," +
         count(render::kLabelShadow);
}

}  // namespace sonarloop::study
