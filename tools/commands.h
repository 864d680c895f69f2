#pragma once
// The sonarloop subcommands. Each lives in tools/cmd_<name>.cpp and registers itself with
// SONARLOOP_REGISTER_COMMAND, so adding a command touches only its own file and
// tools/CMakeLists.txt.
#include <string>
#include <vector>

namespace sonarloop::tools {

struct Command {
  const char* name;
  const char* summary;  // one line for `sonarloop --help`
  const char* usage;    // full help with examples for `sonarloop NAME --help`
  int (*run)(const std::vector<std::string>& args);
  int order = 100;  // position in `sonarloop --help` (smaller first)
};

// All registered subcommands, sorted by order then name.
std::vector<Command> commands();

// Adds a command to the registry (used by SONARLOOP_REGISTER_COMMAND at static initialisation).
bool register_command(const Command& c);

}  // namespace sonarloop::tools

#define SONARLOOP_REGISTER_COMMAND(cmd) \
  static const bool sonarloop_registered_##cmd = ::sonarloop::tools::register_command(cmd)
