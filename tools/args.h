#pragma once
// A small command-line parser for the sonarloop subcommands: `--name value`, `--name=value`,
// repeatable options, flags and positionals. Unknown options and bad values are errors that name
// the option and say what is allowed.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace sonarloop::tools {

// A usage error: printed with a hint to run --help, exit status 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct OptionSpec {
  std::string name;  // "--out"
  bool takes_value = true;
  bool repeatable = false;
};

class Args {
 public:
  // Parses argv (without the program and subcommand names) against the allowed options.
  Args(const std::vector<std::string>& argv, const std::vector<OptionSpec>& specs);

  bool has(const std::string& name) const;
  // The option's value (last one if given twice), or nullopt.
  std::optional<std::string> get(const std::string& name) const;
  std::vector<std::string> get_all(const std::string& name) const;
  std::string get_or(const std::string& name, const std::string& fallback) const;
  // Numeric values with range checks; errors name the option.
  std::optional<double> get_double(const std::string& name, double lo, double hi) const;
  std::optional<long long> get_int(const std::string& name, long long lo, long long hi) const;

  const std::vector<std::string>& positionals() const { return positionals_; }

 private:
  std::vector<std::pair<std::string, std::string>> values_;
  std::vector<std::string> positionals_;
};

}  // namespace sonarloop::tools
