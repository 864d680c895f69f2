#include "study/chip_folder.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <span>
#include <stdexcept>

#include "atr/chip_label_name.h"
#include "atr/chip_resample.h"
#include "drivers/image/jpeg.h"
#include "drivers/io/input_file.h"
#include "drivers/json/utf8.h"

namespace sonarloop::study {

// the classifier this study code trains and scores (atr/)
using namespace sonarloop::atr;
namespace {

namespace fs = std::filesystem;

// dot-files; the files operating systems leave in folders of images (Windows' thumbnail caches
// and folder settings, the __MACOSX folder of a zip made on a Mac); and the label images
// `sonarloop dataset` writes next to its chips
bool hidden(const fs::path& p) {
  const std::string n = p.filename().string();
  std::string lower = n;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return (!n.empty() && n[0] == '.') || lower == "thumbs.db" || lower == "ehthumbs.db" ||
         lower == "desktop.ini" || n == "__MACOSX" || is_chip_label_file_name(n);
}

bool lower_ext_is_image(std::string ext) {
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg";
}

bool is_image_name(const fs::path& p) {
  return lower_ext_is_image(p.extension().string());
}

// Directory entries sorted by name (directory_iterator order is unspecified).
std::vector<fs::directory_entry> sorted_entries(const fs::path& dir) {
  std::vector<fs::directory_entry> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!hidden(it->path())) out.push_back(*it);
  }
  if (ec) throw std::runtime_error("cannot list folder '" + dir.string() + "': " + ec.message());
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) {
    return a.path().filename().string() < b.path().filename().string();
  });
  return out;
}

// Whether a folder entry can be looked at (a symbolic link loop or a dangling link cannot): if
// not, the reason stops the reading, or with skip_bad the entry is listed as skipped.
bool readable_entry(const fs::directory_entry& e, const std::string& rel,
                    const ChipFolderOptions& options, ChipFolder& folder) {
  std::error_code ec;
  e.status(ec);
  if (!ec) return true;
  const std::string reason =
      "cannot read '" + json::printable_bytes(e.path().string()) + "': " + ec.message();
  if (!options.skip_bad) throw std::runtime_error(reason);
  folder.skipped.push_back({json::printable_bytes(rel), reason});
  return false;
}

// One CSV record split into fields (RFC 4180 quoting, no embedded newlines).
std::vector<std::string> split_csv(const std::string& line, const std::string& where) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < line.size() && line[i + 1] == '"') {
          field += '"';
          ++i;
        } else {
          quoted = false;
        }
      } else {
        field += c;
      }
    } else if (c == '"' && field.empty()) {
      quoted = true;
    } else if (c == ',') {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  if (quoted) throw std::runtime_error(where + ": unterminated quoted field");
  out.push_back(field);
  return out;
}

std::string trim(std::string s) {
  const auto ws = [](unsigned char c) { return std::isspace(c) != 0; };
  while (!s.empty() && ws(static_cast<unsigned char>(s.back())))
    s.pop_back();
  std::size_t i = 0;
  while (i < s.size() && ws(static_cast<unsigned char>(s[i])))
    ++i;
  return s.substr(i);
}

// Applies labels.csv to the chips (aspect angles; checks class agreement).
void apply_labels_csv(const fs::path& csv, ChipFolder& folder) {
  std::ifstream in(csv);
  if (!in) throw std::runtime_error("cannot open '" + csv.string() + "'");
  std::map<std::string, std::size_t> by_path;  // relative path -> chip index
  for (std::size_t i = 0; i < folder.chips.size(); ++i)
    by_path[folder.chips[i].source] = i;
  std::vector<bool> seen(folder.chips.size(), false);

  std::string line;
  int line_no = 0;
  int col_file = -1, col_class = -1, col_aspect = -1;
  std::size_t columns = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = csv.string() + " line " + std::to_string(line_no);
    if (line_no == 1 && line.size() >= 3 && line.compare(0, 3, "\xEF\xBB\xBF") == 0) {
      line.erase(0, 3);  // UTF-8 byte order mark
    }
    if (trim(line).empty()) continue;
    std::vector<std::string> f = split_csv(line, where);
    for (auto& x : f)
      x = trim(x);
    if (col_file < 0) {
      // the header row
      for (std::size_t c = 0; c < f.size(); ++c) {
        if (f[c] == "file") col_file = static_cast<int>(c);
        if (f[c] == "class") col_class = static_cast<int>(c);
        if (f[c] == "aspect_deg") col_aspect = static_cast<int>(c);
      }
      if (col_file < 0) {
        throw std::runtime_error(where +
                                 ": the header row has no 'file' column (expected columns "
                                 "file,class,aspect_deg,...)");
      }
      columns = f.size();
      continue;
    }
    if (f.size() != columns) {
      throw std::runtime_error(where + ": " + std::to_string(f.size()) +
                               " fields, the header has " + std::to_string(columns));
    }
    std::string file = f[static_cast<std::size_t>(col_file)];
    std::replace(file.begin(), file.end(), '\\', '/');
    if (file.rfind("./", 0) == 0) file.erase(0, 2);
    const std::string cls = col_class >= 0 ? f[static_cast<std::size_t>(col_class)] : "";
    std::string key = file;
    if (file.find('/') == std::string::npos && !cls.empty() && folder.labelled) {
      key = cls + "/" + file;
    }
    const auto it = by_path.find(key);
    if (it == by_path.end()) {
      throw std::runtime_error(where + ": chip '" + key + "' is not in the folder '" + folder.root +
                               "'");
    }
    const std::size_t i = it->second;
    if (seen[i]) throw std::runtime_error(where + ": second row for chip '" + key + "'");
    seen[i] = true;
    LabelledChip& chip = folder.chips[i];
    if (!cls.empty() && folder.labelled && cls != chip.label) {
      throw std::runtime_error(where + ": class '" + cls + "' disagrees with the chip's folder '" +
                               chip.label + "'");
    }
    if (col_aspect >= 0) {
      const std::string& a = f[static_cast<std::size_t>(col_aspect)];
      if (!a.empty()) {
        char* end = nullptr;
        const double v = std::strtod(a.c_str(), &end);
        if (end == a.c_str() || *end != '\0' || !std::isfinite(v)) {
          throw std::runtime_error(where + ": aspect_deg '" + a +
                                   "' is not a finite number of degrees (leave it empty when "
                                   "unknown)");
        }
        chip.aspect_deg = v;
        ++folder.aspect_count;
      }
    }
  }
  if (col_file < 0) throw std::runtime_error("'" + csv.string() + "' has no header row");
}

// The pixels of one PNG or JPEG file (told by its first bytes), resampled when asked; errors
// name `source`.
Chip read_image_chip(const fs::path& path, const std::string& source,
                     const std::optional<ChipSize>& size) {
  try {
    // a regular file of a sane size: a FIFO named x.png would block the open for ever
    io::check_input_file(path.string(), "chip", image::kMaxImageFileBytes);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot open '" + path.string() + "'");
    std::uint8_t head[8] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const std::span<const std::uint8_t> got(head, static_cast<std::size_t>(in.gcount()));
    Chip c;
    if (image::looks_like_jpeg(got)) {
      c = chip_from_gray8(image::read_jpeg_gray8(path.string(), kMaxChipPixels));
    } else if (got.size() == 8 && got[0] == 0x89 && got[1] == 'P' && got[2] == 'N' &&
               got[3] == 'G') {
      c = chip_from_gray8(image::read_png_gray8(path.string(), kMaxChipPixels));
    } else {
      throw std::runtime_error("'" + path.string() +
                               "' is not a PNG or JPEG image (by its first bytes)");
    }
    if (size && (c.width != size->width || c.height != size->height))
      c = resample_chip(c.view(), size->width, size->height);
    return c;
  } catch (const std::runtime_error&) {
    throw;  // the readers' messages name the file already
  } catch (const std::exception& e) {
    throw std::runtime_error("chip '" + source + "': " + e.what());
  }
}

// The reason a chip of another size than the first is left out, or stops the reading.
std::string wrong_size_reason(const fs::path& dir, const LabelledChip& c,
                              const LabelledChip& first) {
  return "chip '" + (dir / c.source).string() + "' is " + std::to_string(c.chip.width) + " x " +
         std::to_string(c.chip.height) + " pixels but '" + first.source + "' is " +
         std::to_string(first.chip.width) + " x " + std::to_string(first.chip.height) +
         ": all chips must have the same size (resample them with --size WxH)";
}

// Reads every listed chip's pixels; with skip_bad, unreadable and wrong-size chips move to
// folder.skipped.
void read_all_pixels(const fs::path& dir, const ChipFolderOptions& options, ChipFolder& folder) {
  std::vector<LabelledChip> kept;
  kept.reserve(folder.chips.size());
  for (std::size_t i = 0; i < folder.chips.size(); ++i) {
    LabelledChip& c = folder.chips[i];
    try {
      c.chip = read_image_chip(dir / c.source, c.source, options.size);
      if (options.require_same_size && !kept.empty() &&
          (c.chip.width != kept.front().chip.width || c.chip.height != kept.front().chip.height)) {
        throw std::runtime_error(wrong_size_reason(dir, c, kept.front()));
      }
    } catch (const std::runtime_error& e) {
      if (!options.skip_bad) throw;
      folder.skipped.push_back({c.source, e.what()});
      continue;
    }
    kept.push_back(std::move(c));
  }
  folder.chips = std::move(kept);
}

}  // namespace

Chip chip_from_gray8(const image::Gray8& g) {
  Chip c;
  c.width = g.width;
  c.height = g.height;
  c.pixels.assign(g.pixels.begin(), g.pixels.end());
  return c;
}

Chip read_folder_chip(const ChipFolder& folder, std::size_t index,
                      const std::optional<ChipSize>& size) {
  const LabelledChip& c = folder.chips.at(index);
  return read_image_chip(fs::path(folder.root) / c.source, c.source, size);
}

LabelledChip read_chip_file(const std::string& path, const std::optional<ChipSize>& size) {
  LabelledChip c;
  c.chip = read_image_chip(path, path, size);
  c.source = path;
  return c;
}

ChipFolder read_chip_folder(const std::string& root, const ChipFolderOptions& options) {
  ChipFolder folder;
  folder.root = root;
  const fs::path dir(root);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::runtime_error("'" + root +
                             "' is not a folder (expected a folder of PNG or JPEG chips "
                             "with one subfolder per class)");
  }
  std::vector<fs::path> root_images;
  std::vector<fs::path> class_dirs;
  bool csv = false;
  for (const auto& e : sorted_entries(dir)) {
    if (!readable_entry(e, e.path().filename().string(), options, folder)) continue;
    if (e.is_directory(ec)) {
      const std::string cls = e.path().filename().string();
      if (!json::is_valid_utf8(cls)) {
        // it would be a class name in every report, and JSON holds only UTF-8
        const std::string reason = "class folder '" + json::printable_bytes(e.path().string()) +
                                   "': its name is not valid UTF-8 (rename it)";
        if (!options.skip_bad) throw std::runtime_error(reason);
        folder.skipped.push_back({json::printable_bytes(cls), reason + ": the class is left out"});
        continue;
      }
      class_dirs.push_back(e.path());
    } else if (is_image_name(e.path())) {
      root_images.push_back(e.path());
    } else if (e.path().filename() == "labels.csv") {
      csv = true;
    }
  }

  if (!class_dirs.empty()) {
    if (!root_images.empty()) {
      throw std::runtime_error("'" + root_images[0].string() +
                               "' lies at the root next to class subfolders: each chip belongs "
                               "in the subfolder of its class");
    }
    folder.labelled = true;
    for (const auto& cd : class_dirs) {
      const std::string cls = cd.filename().string();
      folder.classes.push_back(cls);
      std::size_t count = 0;
      for (const auto& e : sorted_entries(cd)) {
        const std::string rel = cls + "/" + e.path().filename().string();
        if (!readable_entry(e, rel, options, folder)) continue;
        const bool is_dir = e.is_directory(ec);
        if (is_dir || !is_image_name(e.path())) {
          const std::string what = is_dir ? "unexpected folder '" : "unexpected file '";
          const std::string reason = what + (dir / rel).string() +
                                     "': a class folder holds only .png, .jpg or .jpeg chips";
          if (!options.skip_bad) throw std::runtime_error(reason);
          folder.skipped.push_back({rel, reason});
          continue;
        }
        LabelledChip c;
        c.label = cls;
        c.source = rel;
        folder.chips.push_back(std::move(c));
        ++count;
      }
      if (count == 0) {
        const std::string reason =
            "class folder '" + cd.string() + "' holds no .png, .jpg or .jpeg chips";
        if (!options.skip_bad) throw std::runtime_error(reason);
        // skipped: the class is left out (its name listed as the source)
        folder.skipped.push_back({cls, reason + ": the class is left out"});
        folder.classes.pop_back();
      }
    }
  } else if (!root_images.empty()) {
    if (options.require_classes) {
      throw std::runtime_error("'" + root +
                               "' holds chip images but no class subfolders: put each class's "
                               "chips in a subfolder named after the class");
    }
    for (const auto& p : root_images) {
      LabelledChip c;
      c.source = p.filename().string();
      folder.chips.push_back(std::move(c));
    }
  } else {
    throw std::runtime_error("'" + root +
                             "' holds no PNG or JPEG chips (expected one subfolder per "
                             "class with .png, .jpg or .jpeg chips inside)");
  }

  // labels.csv names every chip listed, readable or not: apply it before reading pixels
  if (csv) {
    folder.has_labels_csv = true;
    apply_labels_csv(dir / "labels.csv", folder);
  }
  if (options.read_pixels) {
    read_all_pixels(dir, options, folder);
    folder.aspect_count = static_cast<std::size_t>(
        std::count_if(folder.chips.begin(), folder.chips.end(),
                      [](const LabelledChip& c) { return c.aspect_deg.has_value(); }));
  }
  return folder;
}

}  // namespace sonarloop::study
