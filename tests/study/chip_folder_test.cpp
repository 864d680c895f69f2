// Reading folders of PNG and JPEG chips (one subfolder per class, optional labels.csv) and the
// errors a user can make: mixed sizes, an empty class, non-PNG files, bad labels; and what is not
// a chip at all: a FIFO, a symbolic link loop, a class name not in UTF-8.
#include <sys/stat.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "drivers/image/jpeg.h"
#include "drivers/image/png.h"
#include "study/chip_folder.h"
#include "tests/support/temp_dir.h"

using namespace sonarloop;
using namespace sonarloop::atr;
using namespace sonarloop::study;
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
  const LabelledChip one = read_chip_file((root / "x.png").string());
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
                    Catch::Contains("empty/b") && Catch::Contains("holds no .png, .jpg or .jpeg"));
  // with skip_bad the empty class is listed and left out
  ChipFolderOptions skip;
  skip.skip_bad = true;
  const ChipFolder without_b = read_chip_folder((base / "empty").string(), skip);
  CHECK(without_b.classes == std::vector<std::string>{"a"});
  REQUIRE(without_b.skipped.size() == 1);
  CHECK(without_b.skipped[0].source == "b");
  CHECK_THAT(without_b.skipped[0].reason, Catch::Contains("left out"));

  // what operating systems leave among images is ignored: Thumbs.db, desktop.ini, __MACOSX
  write_chip(base / "os" / "a" / "1.png", 8, 8, 1);
  write_text(base / "os" / "a" / "Thumbs.db", "cache");
  write_text(base / "os" / "a" / "desktop.ini", "[.ShellClassInfo]");
  write_chip(base / "os" / "__MACOSX" / "a" / "._1.png", 8, 8, 1);
  const ChipFolder os = read_chip_folder((base / "os").string());
  CHECK(os.classes == std::vector<std::string>{"a"});
  CHECK(os.chips.size() == 1);

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
  CHECK_THROWS_WITH(read_chip_folder((base / "none").string()),
                    Catch::Contains("no PNG or JPEG chips"));
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

TEST_CASE("chip folder: JPEG chips, resampling, listing without pixels") {
  testing::TempDir dir("atr-chip-folder-jpeg");
  const fs::path root = dir.path() / "chips";
  write_chip(root / "a" / "1.png", 8, 6, 1);
  fs::create_directories(root / "b");
  const std::vector<std::uint8_t> flat(8 * 6, 90);
  image::write_jpeg((root / "b" / "2.JPG").string(), 8, 6, 1, flat);
  // a PNG named .jpg: the first bytes decide
  write_chip(root / "b" / "3.jpg", 8, 6, 3);
  const ChipFolder f = read_chip_folder(root.string());
  REQUIRE(f.chips.size() == 3);
  CHECK(f.chips[1].source == "b/2.JPG");
  CHECK(f.chips[1].chip.width == 8);
  CHECK(f.chips[1].chip.pixels == std::vector<float>(48, 90.0f));  // flat JPEG: exact
  CHECK(f.chips[2].chip.pixels[5] == static_cast<float>((3 * 37 + 5 * 11) % 251));

  // resampled on reading: every chip 4 x 3, the mean kept
  ChipFolderOptions o;
  o.size = ChipSize{4, 3};
  const ChipFolder small = read_chip_folder(root.string(), o);
  for (const auto& c : small.chips) {
    CHECK(c.chip.width == 4);
    CHECK(c.chip.height == 3);
  }
  CHECK(small.chips[1].chip.pixels == std::vector<float>(12, 90.0f));

  // listed only: no pixels until read_folder_chip
  o = {};
  o.read_pixels = false;
  const ChipFolder listed = read_chip_folder(root.string(), o);
  REQUIRE(listed.chips.size() == 3);
  CHECK(listed.chips[0].chip.pixels.empty());
  CHECK(read_folder_chip(listed, 0).pixels == f.chips[0].chip.pixels);
  CHECK(read_folder_chip(listed, 2, ChipSize{2, 2}).pixels.size() == 4);
  CHECK(read_chip_file((root / "b" / "2.JPG").string()).chip.width == 8);
}

TEST_CASE("chip folder: skip_bad lists a corrupt file, a wrong-size chip and a non-image") {
  testing::TempDir dir("atr-chip-folder-skip");
  const fs::path root = dir.path() / "chips";
  write_chip(root / "a" / "1.png", 8, 8, 1);
  write_chip(root / "a" / "2.png", 8, 8, 2);
  write_text(root / "a" / "3.png", "corrupt");  // not an image
  write_chip(root / "a" / "4.png", 8, 7, 4);    // wrong size
  write_text(root / "b" / "notes.txt", "a note");
  write_chip(root / "b" / "5.png", 8, 8, 5);
  write_chip(root / "b" / "deeper" / "6.png", 8, 8, 6);
  // without skip_bad the first problem stops the reading
  CHECK_THROWS_WITH(read_chip_folder(root.string()), Catch::Contains("b/deeper"));
  ChipFolderOptions o;
  o.skip_bad = true;
  const ChipFolder f = read_chip_folder(root.string(), o);
  REQUIRE(f.chips.size() == 3);
  CHECK(f.chips[2].source == "b/5.png");
  REQUIRE(f.skipped.size() == 4);
  CHECK(f.skipped[0].source == "b/deeper");
  CHECK_THAT(f.skipped[0].reason, Catch::Contains("unexpected folder"));
  CHECK(f.skipped[1].source == "b/notes.txt");
  CHECK_THAT(f.skipped[1].reason, Catch::Contains("unexpected file"));
  CHECK(f.skipped[2].source == "a/3.png");
  CHECK_THAT(f.skipped[2].reason, Catch::Contains("not a PNG or JPEG"));
  CHECK(f.skipped[3].source == "a/4.png");
  CHECK_THAT(f.skipped[3].reason, Catch::Contains("8 x 7") && Catch::Contains("--size"));
  // with a size, the odd chip is resampled instead of skipped
  o.size = ChipSize{8, 8};
  CHECK(read_chip_folder(root.string(), o).chips.size() == 4);
}

TEST_CASE("chip folder: a chip image over 4096 x 4096 pixels is refused before decoding") {
  // the fuzzers' finding (tests/fuzz/corpus/png_chip/huge_header.jpg): a 125-byte JPEG whose
  // header declares 65298 x 2301 pixels took seconds and 1 GB to turn into a chip
  const std::string found =
      std::string(SONARLOOP_SOURCE_DIR) + "/tests/fuzz/corpus/png_chip/huge_header.jpg";
  CHECK_THROWS_WITH(read_chip_file(found), Catch::Contains("huge_header.jpg") &&
                                               Catch::Contains("declares 65298 x 2301 pixels"));
  // the limit is on pixels, not on a side: 4097 x 64 is read, 4097 x 4096 is not
  testing::TempDir dir("atr-chip-folder-limit");
  image::write_png_gray8(dir.file("wide.png"), 4097, 64, std::vector<std::uint8_t>(4097 * 64, 9));
  CHECK(read_chip_file(dir.file("wide.png")).chip.width == 4097);
  image::write_png_gray8(dir.file("big.png"), 4097, 4096,
                         std::vector<std::uint8_t>(std::size_t{4097} * 4096, 9));
  CHECK_THROWS_WITH(read_chip_file(dir.file("big.png")),
                    Catch::Contains("declares 4097 x 4096 pixels"));
}

TEST_CASE(
    "chip folder: a FIFO, a symbolic link loop and a name not in UTF-8 are refused or skipped") {
  testing::TempDir dir("atr-chip-folder-hostile");
  const fs::path root = dir.path() / "chips";
  write_chip(root / "a" / "1.png", 8, 8, 1);
  write_chip(root / "b" / "2.png", 8, 8, 2);
  // a FIFO named like a chip: it would block the reader's open for ever (no writer comes)
  REQUIRE(::mkfifo((root / "a" / "x.png").c_str(), 0600) == 0);
  CHECK_THROWS_WITH(read_chip_folder(root.string()),
                    Catch::Contains("x.png") && Catch::Contains("not a regular file (a FIFO)"));
  // a symbolic link loop named like a chip
  fs::create_symlink(root / "b" / "loop2.png", root / "b" / "loop1.png");
  fs::create_symlink(root / "b" / "loop1.png", root / "b" / "loop2.png");
  // a class folder whose name is not UTF-8 (Latin-1 'é')
  write_chip(root / "\xE9pave" / "3.png", 8, 8, 3);
  ChipFolderOptions o;
  o.skip_bad = true;
  const ChipFolder f = read_chip_folder(root.string(), o);
  CHECK(f.classes == std::vector<std::string>{"a", "b"});
  REQUIRE(f.chips.size() == 2);
  std::vector<std::string> skipped;
  for (const auto& s : f.skipped)
    skipped.push_back(s.source + ": " + s.reason);
  INFO(Catch::Detail::stringify(skipped));
  REQUIRE(skipped.size() == 4);
  // the class folders are listed first, then their entries, then the pixels are read
  CHECK_THAT(skipped[0], Catch::StartsWith("\\xE9pave: class folder") &&
                             Catch::Contains("not valid UTF-8") &&
                             Catch::Contains("the class is left out"));
  CHECK_THAT(skipped[1],
             Catch::StartsWith("b/loop1.png: cannot read") && Catch::Contains("symbolic links"));
  CHECK_THAT(skipped[2], Catch::StartsWith("b/loop2.png: cannot read"));
  CHECK_THAT(skipped[3], Catch::StartsWith("a/x.png: chip") && Catch::Contains("a FIFO"));
  // without skip_bad the name is refused, printable
  fs::remove(root / "a" / "x.png");
  fs::remove(root / "b" / "loop1.png");
  fs::remove(root / "b" / "loop2.png");
  CHECK_THROWS_WITH(read_chip_folder(root.string()),
                    Catch::Contains("\\xE9pave") && Catch::Contains("not valid UTF-8"));
}
