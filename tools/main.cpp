// sonarloop: a real-time sidescan sonar emulator. One binary, one subcommand per job.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include "ranks/mpi_world.h"
#include "tools/args.h"
#include "tools/commands.h"

namespace {

void print_overview() {
  std::printf(
      "sonarloop %s: a real-time sidescan sonar emulator for AUVs\n"
      "(Pailhas, Petillot & Capus, EURASIP J. Adv. Signal Process. 2010)\n\n"
      "usage: sonarloop COMMAND [ARGS...]\n"
      "       sonarloop COMMAND --help     full help and examples for one command\n\n"
      "commands:\n",
      SONARLOOP_VERSION);
  for (const auto& c : sonarloop::tools::commands()) {
    std::printf("  %-9s %s\n", c.name, c.summary);
  }
  std::printf(
      "\nexamples:\n"
      "  sonarloop run --duration 30 --udp 127.0.0.1:5600          # the main job, live\n"
      "  sonarloop scene config/default.yaml --out out/scene\n"
      "  sonarloop render --out out/render --resolution-cm 5\n"
      "  sonarloop dataset --out out/chips --count 80\n"
      "  sonarloop train out/chips --out out/atr.slpca\n"
      "  sonarloop replay tests/data/xtf/scotsman-iver2.xtf --udp 127.0.0.1:5600\n"
      "  sonarloop run --help\n");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") ||
      !std::strcmp(argv[1], "help")) {
    print_overview();
    return argc < 2 ? 2 : 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::printf("sonarloop %s\n", SONARLOOP_VERSION);
    return 0;
  }
  const std::string name = argv[1];
  std::vector<std::string> args(argv + 2, argv + argc);
  for (const auto& c : sonarloop::tools::commands()) {
    if (name != c.name) continue;
    for (const auto& a : args) {
      if (a == "--help" || a == "-h") {
        std::printf("%s", c.usage);
        return 0;
      }
    }
    try {
      return c.run(args);
    } catch (const sonarloop::tools::UsageError& e) {
      std::fprintf(stderr, "sonarloop %s: %s\n(see 'sonarloop %s --help')\n", c.name, e.what(),
                   c.name);
      return sonarloop::ranks::mpi::end_after_error(2);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "sonarloop %s: error: %s\n", c.name, e.what());
      // under mpirun the other ranks would wait for this one forever: end them all
      return sonarloop::ranks::mpi::end_after_error(1);
    }
  }
  std::fprintf(stderr, "sonarloop: unknown command '%s' (see 'sonarloop --help')\n", name.c_str());
  return 2;
}
