#pragma once
// Shared by the command-line tests: the sonarloop binary of this build tree, the inputs several
// of them use, and the ways they run the binary.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>

#include "tests/support/temp_dir.h"

namespace sonarloop::testing {

inline const std::string kBinary = std::string(SONARLOOP_BINARY_DIR) + "/tools/sonarloop";
inline const std::string kPython = SONARLOOP_PYTHON;
inline const std::string kRealXtf =
    std::string(SONARLOOP_SOURCE_DIR) + "/tests/data/xtf/scotsman-iver2.xtf";

// Runs the binary with stdout and stderr discarded; returns the exit status.
inline int run_quiet(const std::string& args) {
  return run_command(kBinary + " " + args + " > /dev/null 2>&1");
}

// Runs the binary, stdout to `log`.out and stderr to `log`.err in `dir`; returns the exit status.
inline int run_logged(const TempDir& dir, const std::string& args, const std::string& log) {
  return run_command(kBinary + " " + args + " > " + dir.file(log + ".out") + " 2> " +
                     dir.file(log + ".err"));
}

// Waits for a child that should end on its own (a hang detector, not a timing check): its wait
// status, or nullopt after `seconds`, when it has been killed (SIGKILL) and reaped.
inline std::optional<int> wait_exit_within(pid_t pid, int seconds) {
  int status = 0;
  for (int k = 0; k < seconds * 20; ++k) {
    if (waitpid(pid, &status, WNOHANG) == pid) return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return std::nullopt;
}

// Every regular file below `root`, relative to it, with its bytes.
inline std::map<std::string, std::string> file_tree(const std::filesystem::path& root) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file()) out[fs::relative(e.path(), root).generic_string()] = slurp(e.path());
  }
  return out;
}

}  // namespace sonarloop::testing
