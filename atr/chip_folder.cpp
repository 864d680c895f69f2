#include "atr/chip_folder.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

namespace sonarloop::atr {
namespace {

namespace fs = std::filesystem;

bool hidden(const fs::path& p) {
  const std::string n = p.filename().string();
  return !n.empty() && n[0] == '.';
}

bool is_png_name(const fs::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png";
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

LabelledChip read_png_chip(const fs::path& path, const std::string& source,
                           const std::string& label) {
  LabelledChip c;
  try {
    c.chip = chip_from_gray8(image::read_png_gray8(path.string()));
  } catch (const std::exception& e) {
    throw std::runtime_error("chip '" + source + "': " + e.what());
  }
  c.label = label;
  c.source = source;
  return c;
}

}  // namespace

Chip chip_from_gray8(const image::Gray8& g) {
  Chip c;
  c.width = g.width;
  c.height = g.height;
  c.pixels.assign(g.pixels.begin(), g.pixels.end());
  return c;
}

LabelledChip read_chip_png(const std::string& path) {
  return read_png_chip(path, path, "");
}

ChipFolder read_chip_folder(const std::string& root, const ChipFolderOptions& options) {
  ChipFolder folder;
  folder.root = root;
  const fs::path dir(root);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw std::runtime_error("'" + root +
                             "' is not a folder (expected a folder of PNG chips "
                             "with one subfolder per class)");
  }
  std::vector<fs::path> root_pngs;
  std::vector<fs::path> class_dirs;
  bool csv = false;
  for (const auto& e : sorted_entries(dir)) {
    if (e.is_directory()) {
      class_dirs.push_back(e.path());
    } else if (is_png_name(e.path())) {
      root_pngs.push_back(e.path());
    } else if (e.path().filename() == "labels.csv") {
      csv = true;
    }
  }

  if (!class_dirs.empty()) {
    if (!root_pngs.empty()) {
      throw std::runtime_error("'" + root_pngs[0].string() +
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
        if (e.is_directory()) {
          throw std::runtime_error("unexpected folder '" + (dir / rel).string() +
                                   "': a class folder holds only .png chips");
        }
        if (!is_png_name(e.path())) {
          throw std::runtime_error("unexpected file '" + (dir / rel).string() +
                                   "': a class folder holds only .png chips");
        }
        folder.chips.push_back(read_png_chip(e.path(), rel, cls));
        ++count;
      }
      if (count == 0) {
        throw std::runtime_error("class folder '" + cd.string() + "' holds no .png chips");
      }
    }
  } else if (!root_pngs.empty()) {
    if (options.require_classes) {
      throw std::runtime_error("'" + root +
                               "' holds PNG chips but no class subfolders: put each class's "
                               "chips in a subfolder named after the class");
    }
    for (const auto& p : root_pngs) {
      folder.chips.push_back(read_png_chip(p, p.filename().string(), ""));
    }
  } else {
    throw std::runtime_error("'" + root +
                             "' holds no PNG chips (expected one subfolder per "
                             "class with .png chips inside)");
  }

  if (options.require_same_size) {
    const LabelledChip& first = folder.chips.front();
    for (const auto& c : folder.chips) {
      if (c.chip.width != first.chip.width || c.chip.height != first.chip.height) {
        throw std::runtime_error(
            "chip '" + (dir / c.source).string() + "' is " + std::to_string(c.chip.width) + " x " +
            std::to_string(c.chip.height) + " pixels but '" + first.source + "' is " +
            std::to_string(first.chip.width) + " x " + std::to_string(first.chip.height) +
            ": all chips must have the same size");
      }
    }
  }
  if (csv) {
    folder.has_labels_csv = true;
    apply_labels_csv(dir / "labels.csv", folder);
  }
  return folder;
}

}  // namespace sonarloop::atr
