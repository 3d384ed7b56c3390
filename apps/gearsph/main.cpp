// gearsph: one executable, several subcommands.
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include "apps/gearsph/cli.hpp"
#ifdef GEARSPH_WITH_RESULTS
#include "results/register_outputs.hpp"
#endif

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
  gearsph geometry JOB.json --out DIR
      the scene's outlines and particles as SVG and CSV, without running it
  gearsph serve [--port 8080] [--bind 127.0.0.1] [--data DIR] [--workers N] [--threads-per-job M] [--token-file F] [--cors-origin ORIGIN] [--web DIR]
      the job service: HTTP API, job store, worker pool (docs/api.md lists every option)
  gearsph submit JOB.json --server URL [--wait] [--out DIR] [--token-file F]
      submit a job to a server, follow its progress, download its results
  gearsph help

exit status: 0 success, 1 error, 2 invalid job or usage, 3 run diverged, 4 cancelled
)";

}  // namespace

#ifdef GEARSPH_WITH_SERVICE
namespace gearsph::cli {
int cmd_serve(Args& args);
int cmd_submit(Args& args);
}  // namespace gearsph::cli
#endif

int main(int argc, char** argv) {
#ifdef GEARSPH_WITH_RESULTS
  gearsph::results::register_outputs();
#endif
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
    if (cmd == "geometry") return gearsph::cli::cmd_geometry(args);
#ifdef GEARSPH_WITH_SERVICE
    if (cmd == "serve") return gearsph::cli::cmd_serve(args);
#endif
#ifdef GEARSPH_WITH_SERVICE
    if (cmd == "submit") return gearsph::cli::cmd_submit(args);
#endif
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
