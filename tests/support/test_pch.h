// The precompiled header of the test executables (cmake/SonarloopTests.cmake): the heavy headers
// nearly every test file includes, parsed once per build instead of once per file. Only
// third-party and standard headers: a project header here would rebuild every test on each edit.
#pragma once
#include <catch2/catch.hpp>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <numeric>
#include <optional>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>
