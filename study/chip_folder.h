#pragma once
// Folders of PNG or JPEG chips, for training and scoring on synthetic or real data.
//
// Layout:
//   ROOT/
//     labels.csv          optional: per-chip metadata (see below)
//     manta/  001.png 002.jpg ...     one subfolder per class, named after the class
//     rockan/ ...
// Each image is read as 8-bit grey into float pixels 0..255: PNG by drivers/image/png.h (colour
// converted to luma, 16-bit keeps its top byte), JPEG by drivers/image/jpeg.h (colour converted
// to luminance). The format is told by the file's first bytes, not its name. With
// ChipFolderOptions::size every chip is resampled to that size (atr/chip_resample.h). Class
// subfolders are sorted by name, chips by file name. Files and folders whose name starts with
// '.' are ignored, and so are chips' label images (NAME_label.png, atr/chip_label_name.h). Inside a
// class folder only chip images (.png, .jpg, .jpeg, any letter case) are allowed; other files or
// nested folders are errors, as is an empty class folder, an unreadable image, or a chip of another
// size than the rest (when require_same_size). With skip_bad, those files are listed in
// ChipFolder::skipped instead, one entry each, and reading goes on; an empty class folder is
// listed too and its class left out. Files operating systems leave among images (Thumbs.db,
// ehthumbs.db, desktop.ini, a __MACOSX folder) are ignored like dot-files. At the
// root, files other than chip images are ignored (labels.csv is read); a root with no class
// subfolder is read as unlabelled chips when allowed.
//
// Large folders: with read_pixels = false only the list is made (names, labels, aspects; no
// pixels, so no size check and no unreadable file found yet); read_folder_chip() then reads one
// chip at a time, so that training and classification never hold every chip's pixels.
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

#include <optional>

#include "atr/chip.h"
#include "drivers/image/png.h"

namespace sonarloop::study {

// The largest chip image read, width x height: 4096 x 4096 pixels (a 3 m chip at 1 mm). A file
// declaring more is refused from its header, before it is decoded (drivers/image/png.h).
inline constexpr std::size_t kMaxChipPixels = std::size_t{4096} * 4096;

// A chip size in pixels.
struct ChipSize {
  int width = 0;
  int height = 0;
};

struct ChipFolderOptions {
  bool require_classes = true;    // false: a root holding images and no subfolder is unlabelled
  bool require_same_size = true;  // false: chips may differ in size (the classifier rejects them)
  bool read_pixels = true;        // false: list the chips only (see read_folder_chip)
  // List non-image files, nested folders, unreadable images, chips of another size than the
  // first and empty class folders (their class left out) in ChipFolder::skipped instead of
  // stopping with an error.
  bool skip_bad = false;
  std::optional<ChipSize> size;  // resample every chip to this size (area average)
};

struct ChipFolder {
  std::string root;
  bool labelled = false;             // chips come from class subfolders
  std::vector<std::string> classes;  // class subfolder names, sorted (empty when unlabelled)
  // Sorted by class then file name; source = path relative to root ("manta/001.png"); label = the
  // class (empty when unlabelled); aspect_deg from labels.csv when given.
  std::vector<atr::LabelledChip> chips;
  bool has_labels_csv = false;
  std::size_t aspect_count = 0;  // chips with a known aspect angle
  // Files left out with ChipFolderOptions::skip_bad (source relative to root, and why).
  std::vector<atr::SkippedChip> skipped;
};

ChipFolder read_chip_folder(const std::string& root, const ChipFolderOptions& options = {});

// The pixels of folder.chips[index], read from its file (and resampled to size when given).
// Throws std::runtime_error naming the chip when the file cannot be read.
atr::Chip read_folder_chip(const ChipFolder& folder, std::size_t index,
                           const std::optional<ChipSize>& size = std::nullopt);

// One PNG or JPEG file as an unlabelled chip (source = the path), resampled to size when given.
atr::LabelledChip read_chip_file(const std::string& path,
                                 const std::optional<ChipSize>& size = std::nullopt);

// 8-bit grey pixels as float chip pixels 0..255.
atr::Chip chip_from_gray8(const image::Gray8& g);

}  // namespace sonarloop::study
