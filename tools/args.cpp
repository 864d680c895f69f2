#include "tools/args.h"

#include <cerrno>
#include <cstdlib>

namespace sonarloop::tools {

Args::Args(const std::vector<std::string>& argv, const std::vector<OptionSpec>& specs) {
  auto find = [&](const std::string& name) -> const OptionSpec* {
    for (const auto& s : specs) {
      if (s.name == name) return &s;
    }
    return nullptr;
  };
  for (std::size_t i = 0; i < argv.size(); ++i) {
    const std::string& a = argv[i];
    if (a.size() < 2 || a.rfind("--", 0) != 0) {
      positionals_.push_back(a);
      continue;
    }
    std::string name = a;
    std::optional<std::string> value;
    if (const auto eq = a.find('='); eq != std::string::npos) {
      name = a.substr(0, eq);
      value = a.substr(eq + 1);
    }
    const OptionSpec* spec = find(name);
    if (!spec) throw UsageError("unknown option '" + name + "'");
    if (spec->takes_value) {
      if (!value) {
        if (i + 1 >= argv.size()) throw UsageError("option '" + name + "' needs a value");
        value = argv[++i];
      }
    } else if (value) {
      throw UsageError("option '" + name + "' takes no value");
    }
    if (!spec->repeatable && has(name)) {
      throw UsageError("option '" + name + "' given more than once");
    }
    values_.emplace_back(name, value.value_or(""));
  }
}

bool Args::has(const std::string& name) const {
  for (const auto& [k, v] : values_) {
    if (k == name) return true;
  }
  return false;
}

std::optional<std::string> Args::get(const std::string& name) const {
  std::optional<std::string> out;
  for (const auto& [k, v] : values_) {
    if (k == name) out = v;
  }
  return out;
}

std::vector<std::string> Args::get_all(const std::string& name) const {
  std::vector<std::string> out;
  for (const auto& [k, v] : values_) {
    if (k == name) out.push_back(v);
  }
  return out;
}

std::string Args::get_or(const std::string& name, const std::string& fallback) const {
  return get(name).value_or(fallback);
}

std::optional<double> Args::get_double(const std::string& name, double lo, double hi) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double x = std::strtod(v->c_str(), &end);
  if (v->empty() || *end != '\0' || errno != 0 || !(x >= lo && x <= hi)) {
    throw UsageError("option '" + name + "': '" + *v + "' is not a number in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return x;
}

std::optional<long long> Args::get_int(const std::string& name, long long lo, long long hi) const {
  const auto v = get(name);
  if (!v) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const long long x = std::strtoll(v->c_str(), &end, 10);
  if (v->empty() || *end != '\0' || errno != 0 || x < lo || x > hi) {
    throw UsageError("option '" + name + "': '" + *v + "' is not an integer in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  }
  return x;
}

}  // namespace sonarloop::tools
