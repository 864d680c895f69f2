// Reading folders of PNG chips (one subfolder per class, optional labels.csv) and the errors a
// user can make: mixed sizes, an empty class, non-PNG files, bad labels.
#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "atr/chip_folder.h"
#include "drivers/image/png.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::atr;
namespace fs = std::filesystem;

namespace {

// A w x h chip whose pixels encode (seed, position), written as 8-bit grey PNG.
void write_chip(const fs::path& p, int w, int h, int seed) {
  fs::create_directories(p.parent_path());
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h);
  for (std::size_t i = 0; i < px.size(); ++i)
    px[i] = static_cast<std::uint8_t>((seed * 37 + i * 11) % 251);
  image::write_png_gray8(p.string(), w, h, px);
}

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

}  // namespace

TEST_CASE("chip folder: classes, chips in name order, pixels, labels.csv aspects") {
  testing::TempDir dir("atr-chip-folder");
  const fs::path root = dir.path() / "chips";
  write_chip(root / "rockan" / "b.png", 6, 4, 1);
  write_chip(root / "rockan" / "a.png", 6, 4, 2);
  write_chip(root / "manta" / "001.PNG", 6, 4, 3);
  write_text(root / ".hidden" / "x.txt", "ignored");
  write_text(root / "manta" / ".DS_Store", "ignored");
  write_text(root / "README.md", "root files other than PNGs are ignored");
  write_text(root / "labels.csv",
             "file,class,aspect_deg,resolution_cm\n"
             "rockan/a.png,rockan,30.5,5\n"
             "\"b.png\",rockan,,5\r\n"
             "manta/001.PNG,manta,-45,5\n");
  const ChipFolder f = read_chip_folder(root.string());
  CHECK(f.labelled);
  CHECK(f.has_labels_csv);
  CHECK(f.classes == std::vector<std::string>{"manta", "rockan"});
  REQUIRE(f.chips.size() == 3);
  CHECK(f.chips[0].source == "manta/001.PNG");
  CHECK(f.chips[0].label == "manta");
  CHECK(f.chips[1].source == "rockan/a.png");
  CHECK(f.chips[2].source == "rockan/b.png");
  CHECK(f.chips[0].chip.width == 6);
  CHECK(f.chips[0].chip.height == 4);
  CHECK(f.chips[0].chip.pixels[5] == static_cast<float>((3 * 37 + 5 * 11) % 251));
  CHECK(f.aspect_count == 2);
  CHECK(f.chips[0].aspect_deg == -45.0);
  CHECK(f.chips[1].aspect_deg == 30.5);
  CHECK_FALSE(f.chips[2].aspect_deg.has_value());
}

TEST_CASE("chip folder: unlabelled folders and single files") {
  testing::TempDir dir("atr-chip-folder-flat");
  const fs::path root = dir.path() / "flat";
  write_chip(root / "x.png", 5, 5, 1);
  write_chip(root / "y.png", 5, 5, 2);
  CHECK_THROWS_WITH(read_chip_folder(root.string()), Catch::Contains("no class subfolders"));
  ChipFolderOptions opt;
  opt.require_classes = false;
  const ChipFolder f = read_chip_folder(root.string(), opt);
  CHECK_FALSE(f.labelled);
  REQUIRE(f.chips.size() == 2);
  CHECK(f.chips[1].source == "y.png");
  CHECK(f.chips[1].label.empty());
  const LabelledChip one = read_chip_png((root / "x.png").string());
  CHECK(one.chip.width == 5);
  CHECK(one.source == (root / "x.png").string());
}

TEST_CASE("chip folder: errors name the file and say what is allowed") {
  testing::TempDir dir("atr-chip-folder-errors");
  const fs::path base = dir.path();
  CHECK_THROWS_WITH(read_chip_folder((base / "missing").string()), Catch::Contains("not a folder"));

  // mixed sizes
  write_chip(base / "mixed" / "a" / "1.png", 8, 8, 1);
  write_chip(base / "mixed" / "b" / "1.png", 8, 7, 2);
  CHECK_THROWS_WITH(read_chip_folder((base / "mixed").string()), Catch::Contains("b/1.png") &&
                                                                     Catch::Contains("8 x 7") &&
                                                                     Catch::Contains("same size"));
  ChipFolderOptions lax;
  lax.require_same_size = false;
  CHECK(read_chip_folder((base / "mixed").string(), lax).chips.size() == 2);

  // an empty class
  write_chip(base / "empty" / "a" / "1.png", 8, 8, 1);
  fs::create_directories(base / "empty" / "b");
  CHECK_THROWS_WITH(read_chip_folder((base / "empty").string()),
                    Catch::Contains("empty/b") && Catch::Contains("holds no .png"));

  // a file that is not a PNG chip
  write_chip(base / "txt" / "a" / "1.png", 8, 8, 1);
  write_text(base / "txt" / "a" / "notes.txt", "hello");
  CHECK_THROWS_WITH(read_chip_folder((base / "txt").string()),
                    Catch::Contains("notes.txt") && Catch::Contains("only .png"));
  // a .png that is not a PNG
  write_chip(base / "fake" / "a" / "1.png", 8, 8, 1);
  write_text(base / "fake" / "a" / "2.png", "not really a png");
  CHECK_THROWS_WITH(read_chip_folder((base / "fake").string()),
                    Catch::Contains("a/2.png") && Catch::Contains("not a PNG"));
  // nested folders
  write_chip(base / "nested" / "a" / "deeper" / "1.png", 8, 8, 1);
  CHECK_THROWS_WITH(read_chip_folder((base / "nested").string()),
                    Catch::Contains("deeper") && Catch::Contains("only .png"));
  // a PNG at the root next to classes
  write_chip(base / "stray" / "a" / "1.png", 8, 8, 1);
  write_chip(base / "stray" / "2.png", 8, 8, 1);
  CHECK_THROWS_WITH(read_chip_folder((base / "stray").string()),
                    Catch::Contains("2.png") && Catch::Contains("subfolder of its class"));
  // nothing at all
  fs::create_directories(base / "none");
  CHECK_THROWS_WITH(read_chip_folder((base / "none").string()), Catch::Contains("no PNG chips"));
}

TEST_CASE("chip folder: labels.csv errors name the line") {
  testing::TempDir dir("atr-chip-folder-csv");
  const fs::path root = dir.path() / "c";
  write_chip(root / "manta" / "1.png", 4, 4, 1);
  write_chip(root / "rock" / "1.png", 4, 4, 2);
  const auto with_csv = [&](const std::string& text) {
    write_text(root / "labels.csv", text);
    return root.string();
  };
  CHECK_THROWS_WITH(read_chip_folder(with_csv("name,aspect_deg\nmanta/1.png,3\n")),
                    Catch::Contains("line 1") && Catch::Contains("'file' column"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\nmanta/2.png,3\n")),
                    Catch::Contains("line 2") && Catch::Contains("manta/2.png"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,class\nmanta/1.png,rock\n")),
                    Catch::Contains("line 2") && Catch::Contains("disagrees"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\nmanta/1.png,north\n")),
                    Catch::Contains("line 2") && Catch::Contains("'north'"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\nmanta/1.png,nan\n")),
                    Catch::Contains("not a finite number"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\nmanta/1.png,1\n\nmanta/1.png,2\n")),
                    Catch::Contains("line 4") && Catch::Contains("second row"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\nmanta/1.png\n")),
                    Catch::Contains("1 fields"));
  CHECK_THROWS_WITH(read_chip_folder(with_csv("file,aspect_deg\n\"manta/1.png,1\n")),
                    Catch::Contains("unterminated"));
  // bare file names need the class column to say which folder
  const ChipFolder f = read_chip_folder(with_csv("file,class,aspect_deg\n1.png,rock,12\n"));
  CHECK(f.chips[1].aspect_deg == 12.0);
  CHECK_FALSE(f.chips[0].aspect_deg.has_value());
}
