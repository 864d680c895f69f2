#include "tools/cli_helpers.h"

#include <signal.h>

#include <atomic>
#include <sstream>

namespace sonarloop::tools {
namespace {

std::atomic<bool> g_stop_flag{false};
static_assert(std::atomic<bool>::is_always_lock_free);

void on_stop_flag_signal(int) {
  g_stop_flag.store(true);
}

}  // namespace

std::vector<std::string> split_comma_list(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto first = item.find_first_not_of(" \t");
    if (first == std::string::npos) continue;
    out.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
  }
  return out;
}

void install_stop_flag() {
  g_stop_flag.store(false);
  struct sigaction action {};
  action.sa_handler = on_stop_flag_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool stop_requested() {
  return g_stop_flag.load();
}

}  // namespace sonarloop::tools
