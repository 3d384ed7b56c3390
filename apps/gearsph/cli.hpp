#pragma once
// Small command-line helpers shared by the subcommands.
#include <optional>
#include <string>
#include <vector>

namespace gearsph::cli {

// The values a seconds option takes: from `lo` (or above it, when `lo_open`)
// to `hi`; `allowed` says so in the error.
struct SecondsRange {
  double lo = 0.0;
  bool lo_open = false;
  double hi = 86400.0;
  const char* allowed = "0 to 86400";
};

// argv after the subcommand, with "--name value" and "--flag" options.
class Args {
 public:
  Args(int argc, char** argv, int first);
  // The value of --name (removes it); nullopt if absent. Throws if it has no value.
  std::optional<std::string> option(const std::string& name);
  bool flag(const std::string& name);
  int integer(const std::string& name, int fallback);
  // --name in seconds, within `range`; `fallback` if absent.
  double seconds(const std::string& name, double fallback, const SecondsRange& range);
  // --name in seconds, 0 to a day; 0 if absent.
  double grace_seconds(const std::string& name);
  // Remaining positional arguments; throws on a leftover --option.
  std::vector<std::string> positional() const;
  // The first argument when it is not an option (a sub-subcommand), else "".
  std::string positional_first() const;

 private:
  std::vector<std::string> args_;
};

std::string read_file(const std::string& path);

int cmd_run(Args& args);
int cmd_validate(Args& args);
int cmd_schema(Args& args);
int cmd_geometry(Args& args);

}  // namespace gearsph::cli
