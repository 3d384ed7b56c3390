// gearsph validate: every validation case against its reference, as a table
// and as JSON.
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "apps/gearsph/cli.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#include "solver/run/runner.hpp"
#include "solver/validation/cases.hpp"

namespace gearsph::cli {

namespace {
// A case's summary and what it took: a job is run; a rating document is
// answered by the calculator (no particles, no steps).
struct CaseRun {
  nlohmann::json summary;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  double wall_s = 0.0;
};

CaseRun run_case(const validation::Case& c, int threads) {
  if (c.input == validation::Case::Input::Rating) {
    const auto start = std::chrono::steady_clock::now();
    CaseRun r;
    r.summary = validation::rating_summary(c.job);
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return r;
  }
  PreparedJob job = prepare_job(c.job, threads);
  const RunResult result = run_job(job);
  return {result.summary, job.scene.sim.particles.n, result.steps_done, result.wall_s};
}

const char* kind_name(validation::Case::Kind k) {
  switch (k) {
    case validation::Case::Kind::Relative:
      return "relative";
    case validation::Case::Kind::Bound:
      return "bound";
    case validation::Case::Kind::Outcome:
      return "outcome";
  }
  return "";
}
}  // namespace

#ifdef GEARSPH_WITH_FE
int cmd_accuracy_map(Args& args);  // cmd_fe_accuracy_map.cpp
#endif

int cmd_validate(Args& args) {
  if (const auto study = args.option("study")) {
#ifdef GEARSPH_WITH_FE
    if (*study == "accuracy") return cmd_accuracy_map(args);
    throw std::invalid_argument("--study takes accuracy, not '" + *study + "'");
#else
    throw std::invalid_argument("--study " + *study +
                                ": FE unavailable: this build has no FE layer (GEARSPH_FE)");
#endif
  }
  const bool quick = args.flag("quick");
  const std::string out = args.option("out").value_or("validation");
  const int threads = args.integer("threads", 0);
  const auto filter = args.option("only");
  args.positional();
  std::filesystem::create_directories(out);

  nlohmann::json report = nlohmann::json::array();
  int failures = 0;
  std::printf("%-48s %-8s %12s %12s %10s %10s %5s %9s %8s\n", "case", "section", "reference",
              "measured", "error", "tolerance", "pass", "particles", "wall_s");
  for (const validation::Case& c : validation::cases(quick)) {
    if (filter && c.id.find(*filter) == std::string::npos) continue;
    const CaseRun result = run_case(c, threads);
    const validation::Measurement m = c.measure(result.summary, c.tolerance);
    const bool reported = !c.disagreement.empty();  // shown, not claimed to pass
    failures += m.pass || reported ? 0 : 1;
    // Relative cases: signed error in percent; bounds: the ratio to the scale.
    char err[32], tol[32];
    if (c.kind == validation::Case::Kind::Relative) {
      std::snprintf(err, sizeof err, "%+.2f%%", 100.0 * m.error);
      std::snprintf(tol, sizeof tol, "+-%.0f%%", 100.0 * c.tolerance);
    } else if (c.kind == validation::Case::Kind::Outcome) {
      std::snprintf(err, sizeof err, "%s", m.measured > 0.5 ? "yes" : "no");
      std::snprintf(tol, sizeof tol, "%s", m.reference > 0.5 ? "yes" : "no");
    } else {
      std::snprintf(err, sizeof err, "%.3g", m.error);
      std::snprintf(tol, sizeof tol, "<= %.3g", c.tolerance);
    }
    std::printf("%-48s %-8s %12.5g %12.5g %10s %10s %5s %9zu %8.2f\n", c.id.c_str(),
                ("sec. " + c.section).c_str(), m.reference, m.measured, err, tol,
                m.pass ? "yes" : (reported ? "(no)" : "NO"), result.particles, result.wall_s);
    if (reported && !m.pass) std::printf("    reported, not claimed: %s\n", c.disagreement.c_str());
    std::fflush(stdout);
    report.push_back({{"case", c.id},
                      {"section", c.section},
                      {"quantity", c.quantity},
                      {"reference_formula", c.reference},
                      {"reference", m.reference},
                      {"measured", m.measured},
                      {"error", m.error},
                      {"tolerance", c.tolerance},
                      {"kind", kind_name(c.kind)},
                      {"pass", m.pass},
                      {"note", m.note},
                      {"disagreement", c.disagreement},
                      {"particles", result.particles},
                      {"steps", result.steps},
                      {"wall_s", result.wall_s},
                      {"job", c.job},
                      {"summary", result.summary}});
  }
  write_file_atomic(out + "/validation.json", report.dump(2) + "\n");
  std::printf("%d case(s) failed; report in %s/validation.json\n", failures, out.c_str());
  return failures == 0 ? 0 : 1;
}

}  // namespace gearsph::cli
