// io::LineFile: one whole line per write, and a full disk (the kernel's /dev/full, which fails
// every write with ENOSPC) reported by name and in words, the file left with whole lines.
#include "drivers/io/line_file.h"

#include <catch2/catch.hpp>
#include <csignal>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "drivers/can/candump_log.h"
#include "drivers/xtf/xtf_file.h"
#include "tests/support/temp_dir.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

using sonarloop::io::LineFile;
using sonarloop::testing::slurp;
using sonarloop::testing::TempDir;

namespace {

// /dev/full exists on every Linux system; its writes fail with ENOSPC.
constexpr char kFullDisk[] = "/dev/full";

}  // namespace

TEST_CASE("line file: records are appended whole, in order") {
  TempDir dir("line-file");
  LineFile f(dir.file("a.csv"), "truth");
  f.append("a,b\n");
  f.append("1,2\n");
  CHECK(f.bytes_written() == 8);
  // written at once: readable before close (no user-space buffer)
  CHECK(slurp(dir.file("a.csv")) == "a,b\n1,2\n");
  f.close();
  f.close();  // idempotent
  CHECK_THROWS_WITH(f.append("x\n"), Catch::Contains("write after close"));
  CHECK_THROWS_WITH(LineFile(dir.file("missing/a.csv"), "truth"),
                    Catch::Contains("truth " + dir.file("missing/a.csv") + ": cannot create"));
}

TEST_CASE("line file: a full disk is an error naming the file and saying the disk is full") {
  REQUIRE(std::filesystem::exists(kFullDisk));
  LineFile f(kFullDisk, "truth");
  CHECK_THROWS_WITH(f.append("1,2\n"),
                    Catch::Contains("truth /dev/full: write of 4 bytes at byte offset 0 failed") &&
                        Catch::Contains("ENOSPC: the disk is full"));
  CHECK_THAT(f.error(), Catch::Contains("ENOSPC"));
  // later records are refused with the same error, nothing half written
  CHECK_THROWS_WITH(f.append("3,4\n"), Catch::Contains("byte offset 0"));
  CHECK(f.bytes_written() == 0);
}

TEST_CASE("line file: a record cut short by a size limit is cut back off the file") {
  // RLIMIT_FSIZE makes the kernel write part of the record that crosses the limit and fail the
  // rest (EFBIG): a torn line, unless the writer cuts it back. In a child process, so that the
  // limit stays there.
  TempDir dir("line-file-limit");
  const std::string path = dir.file("limited.csv");
  const pid_t pid = fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
    const rlimit limit{100, 100};
    if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(3);
    try {
      LineFile f(path, "truth");
      const std::string row(29, 'x');
      for (int i = 0; i < 4; ++i)
        f.append(row + "\n");  // the 4th crosses 100 bytes
      _exit(1);
    } catch (const std::runtime_error& e) {
      const std::string msg = e.what();
      _exit(msg.find("at byte offset 90 failed") != std::string::npos ? 0 : 2);
    }
  }
  int status = 0;
  waitpid(pid, &status, 0);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  const std::string text = slurp(path);
  CHECK(text.size() == 90);  // three whole lines, nothing of the fourth
  CHECK(text.back() == '\n');
}

TEST_CASE("line file: the candump log writer reports a full disk the same way") {
  sonarloop::can::CandumpLogWriter log(kFullDisk);
  sonarloop::can::CanFrame frame;
  frame.id = 0x09F80123;
  frame.extended = true;
  frame.len = 1;
  CHECK_THROWS_WITH(log.write(frame, 1'000'000'000),
                    Catch::Contains("candump log /dev/full") &&
                        Catch::Contains("No space left on device (ENOSPC: the disk is full)"));
}

TEST_CASE("line file: the XTF writer says the disk is full too") {
  // a 1024-byte file header into /dev/full: the writer's first write fails
  sonarloop::xtf::XtfFileHeader header;
  CHECK_THROWS_WITH(sonarloop::xtf::XtfWriter(kFullDisk, header),
                    Catch::Contains("/dev/full") && Catch::Contains("ENOSPC: the disk is full"));
}
