#pragma once
// The label image of a chip: `sonarloop dataset` writes, next to chip NAME.png, NAME_label.png of
// the same size whose pixels are 0 (seabed), 1 (target highlight) or 2 (target shadow)
// (sim/render/bin_labels.h). Chip folder readers (chip_folder.h) skip such files: they are not
// chips.
#include <string>
#include <string_view>

namespace sonarloop::atr {

inline constexpr std::string_view kChipLabelSuffix = "_label.png";

// "000001.png" -> "000001_label.png" (the chip's extension, whatever it is, is replaced).
inline std::string chip_label_file_name(std::string_view chip_file_name) {
  const auto dot = chip_file_name.rfind('.');
  return std::string(chip_file_name.substr(0, dot)) + std::string(kChipLabelSuffix);
}

// True for a label image's file name (exact, lower-case suffix).
inline bool is_chip_label_file_name(std::string_view file_name) {
  return file_name.size() > kChipLabelSuffix.size() &&
         file_name.substr(file_name.size() - kChipLabelSuffix.size()) == kChipLabelSuffix;
}

}  // namespace sonarloop::atr
