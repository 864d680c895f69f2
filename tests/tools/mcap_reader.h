#pragma once
// The command-line tests' independent MCAP reader: tests/tools/mcap_read.mjs under node, with the
// npm registry's MCAP and ROS 2 message libraries (installed once per build tree, under a lock:
// two tests may ask at once).
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "tests/support/temp_dir.h"

namespace sonarloop::testing {

inline const std::string kMcapReaderDir = std::string(SONARLOOP_BINARY_DIR) + "/npm-mcap";

// Makes the reader ready: "" when it is, else the reason it cannot be (no node, no npm, no npm
// registry), for the test to skip or to leave that check out.
inline std::string prepare_mcap_reader() {
  if (run_command("node --version > /dev/null 2>&1") != 0) return "node is not installed";
  if (run_command("npm --version > /dev/null 2>&1") != 0) return "npm is not installed";
  std::filesystem::create_directories(kMcapReaderDir);
  const int lock = ::open((kMcapReaderDir + "/.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0) return "cannot lock " + kMcapReaderDir;
  std::string why;
  if (!std::filesystem::exists(kMcapReaderDir +
                               "/node_modules/@foxglove/rosmsg2-serialization/package.json")) {
    const std::string log = kMcapReaderDir + "/install.log";
    if (run_command("cd " + kMcapReaderDir +
                    " && npm install --no-audit --no-fund --loglevel=error @mcap/core@2 "
                    "@mcap/support@1 @foxglove/rosmsg@5 @foxglove/rosmsg2-serialization@3 > " +
                    log + " 2>&1") != 0) {
      why = "npm install of the MCAP reader failed (no npm registry?): " + slurp(log);
    }
  }
  if (why.empty()) {
    std::filesystem::copy_file(std::string(SONARLOOP_SOURCE_DIR) + "/tests/tools/mcap_read.mjs",
                               kMcapReaderDir + "/mcap_read.mjs",
                               std::filesystem::copy_options::overwrite_existing);
  }
  ::close(lock);  // and with it the lock
  return why;
}

// Reads `mcap` with the reader: one JSON object per line to `out` (a summary, then the messages
// in log-time order), its errors to `err`. Returns the exit status.
inline int read_mcap(const std::string& mcap, const std::string& out, const std::string& err) {
  return run_command("node " + kMcapReaderDir + "/mcap_read.mjs " + mcap + " > " + out + " 2> " +
                     err);
}

}  // namespace sonarloop::testing
