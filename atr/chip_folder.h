#pragma once
// Folders of PNG chips, for training and scoring on synthetic or real data.
//
// Layout:
//   ROOT/
//     labels.csv          optional: per-chip metadata (see below)
//     manta/  001.png 002.png ...     one subfolder per class, named after the class
//     rockan/ ...
// Each PNG is read as 8-bit grey (drivers/image/png.h: colour is converted to luma, 16-bit keeps
// its top byte) into float pixels 0..255. Class subfolders are sorted by name, chips by file
// name. Files and folders whose name starts with '.' are ignored. Inside a class folder only
// .png files (any letter case) are allowed; other files or nested folders are errors, as is an
// empty class folder, an unreadable PNG, or a chip of another size than the rest (when
// require_same_size). At the root, files other than PNGs are ignored (labels.csv is read);
// a root with no class subfolder is read as unlabelled chips when allowed.
//
// labels.csv: a header row naming its columns, then one row per chip; comma-separated, fields
// may be double-quoted ("" inside quotes is a quote). Columns used: `file` (required): the chip's
// path relative to ROOT ("manta/001.png"), or its bare file name when a `class` column says
// which subfolder; `class` (optional): must agree with the chip's folder; `aspect_deg`
// (optional): the target's aspect angle in degrees, empty when unknown. Other columns are
// ignored. A row naming a missing chip, a duplicate row, a class that disagrees, or an
// aspect_deg that is not a finite number is an error naming the line.
//
// Errors are std::runtime_error naming the file at fault and what is allowed.
#include <string>
#include <vector>

#include "atr/chip.h"
#include "drivers/image/png.h"

namespace sonarloop::atr {

struct ChipFolderOptions {
  bool require_classes = true;    // false: a root holding PNGs and no subfolder is unlabelled
  bool require_same_size = true;  // false: chips may differ in size (the classifier rejects them)
};

struct ChipFolder {
  std::string root;
  bool labelled = false;             // chips come from class subfolders
  std::vector<std::string> classes;  // class subfolder names, sorted (empty when unlabelled)
  // Sorted by class then file name; source = path relative to root ("manta/001.png"); label = the
  // class (empty when unlabelled); aspect_deg from labels.csv when given.
  std::vector<LabelledChip> chips;
  bool has_labels_csv = false;
  std::size_t aspect_count = 0;  // chips with a known aspect angle
};

ChipFolder read_chip_folder(const std::string& root, const ChipFolderOptions& options = {});

// One PNG file as an unlabelled chip (source = the path).
LabelledChip read_chip_png(const std::string& path);

// 8-bit grey pixels as float chip pixels 0..255.
Chip chip_from_gray8(const image::Gray8& g);

}  // namespace sonarloop::atr
