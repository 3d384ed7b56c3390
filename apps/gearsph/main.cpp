// gearsph: one executable, several subcommands.
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include "apps/gearsph/cli.hpp"

namespace {

const char* kUsage = R"(gearsph - SPH simulation of rack-and-pinion gear meshing

usage:
  gearsph run JOB.json --out DIR [--threads N] [--quiet]
      run one job; writes DIR/summary.json and DIR/history.csv
  gearsph validate [--quick] [--out DIR] [--threads N]
      run the validation cases against their references; prints a table
      and writes DIR/validation.json (DIR defaults to ./validation)
  gearsph schema
      print the job schema (JSON Schema draft-07)
  gearsph help

exit status: 0 success, 1 error, 2 invalid job or usage, 3 run diverged, 4 cancelled
)";

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") ||
      !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string cmd = argv[1];
  gearsph::cli::Args args(argc, argv, 2);
  try {
    if (cmd == "run") return gearsph::cli::cmd_run(args);
    if (cmd == "validate") return gearsph::cli::cmd_validate(args);
    if (cmd == "schema") return gearsph::cli::cmd_schema(args);
    std::fprintf(stderr, "gearsph: unknown command '%s'\n\n%s", cmd.c_str(), kUsage);
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "gearsph %s: %s\n", cmd.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gearsph %s: error: %s\n", cmd.c_str(), e.what());
    return 1;
  }
}
