#include "tools/commands.h"

#include <algorithm>
#include <cstring>

namespace sonarloop::tools {
namespace {

std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}

}  // namespace

bool register_command(const Command& c) {
  registry().push_back(c);
  return true;
}

std::vector<Command> commands() {
  std::vector<Command> out = registry();
  std::sort(out.begin(), out.end(), [](const Command& a, const Command& b) {
    return a.order != b.order ? a.order < b.order : std::strcmp(a.name, b.name) < 0;
  });
  return out;
}

}  // namespace sonarloop::tools
