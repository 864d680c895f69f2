#pragma once
// The label image of each chip of `sonarloop dataset` (atr/chip_label_name.h: NAME_label.png next
// to NAME.png), and the labels.csv columns that describe it.
#include <filesystem>
#include <string>

#include "sim/render/chip_renderer.h"

namespace sonarloop::study {

// labels.csv columns after the chip's own: the label image's file name (in the chip's folder)
// and how many pixels it labels highlight and shadow.
inline constexpr const char* kChipLabelCsvColumns = "label_file,highlight_pixels,shadow_pixels";

// Writes dir/<chip_file_name's stem>_label.png: 8-bit, rows x cols as the chip, pixel values
// 0/1/2 (render::kLabel*). Written to a dot-file, then renamed (chip readers ignore dot-files).
void write_chip_label_png(const std::filesystem::path& dir, const std::string& chip_file_name,
                          const render::ChipImage& chip);

// The values of kChipLabelCsvColumns for a chip, comma-separated.
std::string chip_label_csv_fields(const std::string& chip_file_name, const render::ChipImage& chip);

}  // namespace sonarloop::study
