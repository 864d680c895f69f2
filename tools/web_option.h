#pragma once
// `--web HOST:PORT` of `run` and `onboard` (docs/web.md): the option. The view is web/web_view.h,
// its emulator device web/emulator_device.h.
#include <optional>

#include "drivers/net/host_port.h"
#include "tools/args.h"

namespace sonarloop::tools {

// --web HOST:PORT or --web PORT (127.0.0.1); nullopt without it. UsageError for a bad value or
// a build without web support.
std::optional<net::HostPort> web_option(const Args& args);

}  // namespace sonarloop::tools
