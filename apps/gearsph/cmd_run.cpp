// gearsph run JOB.json --out DIR
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <string>

#include "apps/gearsph/cli.hpp"
#include "apps/gearsph/progress.hpp"
#ifdef GEARSPH_WITH_RESULTS
#include "results/results_writer.hpp"
#endif
#ifdef GEARSPH_WITH_FE
#include "fe/external_program.hpp"
#endif
#include "solver/core/setup_progress.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"

namespace gearsph::cli {

namespace {

std::string threads_text(const PreparedJob& job) {
  char text[96];
  const int n = job.threads_by == "trial" ? job.trial_threads : job.scene.sim.threads;
  std::snprintf(text, sizeof text,
                job.threads_by == "trial" ? "1 to %d threads (timing a few steps picks)"
                : n == 1                  ? "%d thread"
                                          : "%d threads",
                n);
  return text;
}

// " (trial: 1 thread 131 us a step, 2 threads 77 us)", or "".
std::string trial_note(const nlohmann::json& summary) {
  if (!summary.contains("thread_trial")) return "";
  const nlohmann::json& t = summary.at("thread_trial");
  std::string note = " (trial:";
  for (std::size_t k = 0; k < t.at("threads").size(); ++k) {
    char part[80];
    const int n = t.at("threads")[k].get<int>();
    std::snprintf(part, sizeof part, "%s %d thread%s %.0f us%s", k ? "," : "", n, n == 1 ? "" : "s",
                  t.at("us_per_step")[k].get<double>(), k ? "" : " a step");
    note += part;
  }
  // The trial repeated during the run (run/thread_trial.hpp).
  const nlohmann::json& switches = t.value("switches", nlohmann::json::array());
  if (!switches.empty()) {
    char part[96];
    const nlohmann::json& last = switches.back();
    std::snprintf(part, sizeof part, "; %zu switch%s, the last at step %lld to %d", switches.size(),
                  switches.size() == 1 ? "" : "es", last.at("step").get<long long>(),
                  last.at("threads").get<int>());
    note += part;
  }
  return note + ")";
}

}  // namespace

int cmd_schema(Args& args) {
  args.positional();
  std::printf("%s\n", job_schema().dump(2).c_str());
  return 0;
}

int cmd_run(Args& args) {
  const auto out = args.option("out");
  const int threads = args.integer("threads", 0);
  const bool quiet = args.flag("quiet");
  const auto pos = args.positional();
  if (pos.size() != 1 || !out) throw std::invalid_argument("usage: gearsph run JOB.json --out DIR");
  const std::string& path = pos[0];

  // A scene of a million particles takes ~20 s to set up (its pairs and
  // stable step): say so first, then how long it took.
  if (!quiet) {
    std::fprintf(stderr, "gearsph run: setting up %s (scene, pairs, stable step)\n", path.c_str());
  }
  const auto setup_start = std::chrono::steady_clock::now();
  PreparedJob job;
  // A set-up past a second says what it is doing (a relaxation of body-
  // fitted particles, the pairs, the stable step), redrawn on a terminal.
  const bool tty = isatty(2) != 0;
  bool setup_said = false;
  try {
    SetupProgressScope setup([&](const SetupStatus& s) {
      if (quiet) return;
      std::fprintf(stderr, "%sgearsph run: setting up: %s %3.0f %% (%.1f s)%s", tty ? "\r" : "",
                   s.stage.c_str(), 100.0 * s.fraction, s.elapsed_s, tty ? "   " : "\n");
      setup_said = true;
    });
    job = prepare_job(parse_job_text(read_file(path)), threads);
  } catch (const InvalidJob& e) {
    if (setup_said && tty) std::fputc('\n', stderr);
    std::fprintf(stderr, "gearsph run: %s is not a valid job:\n", path.c_str());
    for (const JobIssue& i : e.issues) {
      std::fprintf(stderr, "  %s: %s\n", i.pointer.empty() ? "(document)" : i.pointer.c_str(),
                   i.message.c_str());
    }
    return 2;
  }
  if (setup_said && tty) std::fputc('\n', stderr);  // end the redrawn line
  // A job that asks for the FE check learns before its run that it cannot
  // have it (the service answers 501).
  if (job.job.at("scene").value("fe_check", false)) {
#ifdef GEARSPH_WITH_FE
    const std::string why = fe::fe_unavailable_reason();
#else
    const std::string why = "FE unavailable: this build has no FE layer (GEARSPH_FE)";
#endif
    if (!why.empty()) {
      std::fprintf(stderr, "gearsph run: %s asks for the FE check (/scene/fe_check): %s\n",
                   path.c_str(), why.c_str());
      return 5;
    }
  }
  std::filesystem::create_directories(*out);
  const Simulation& sim = job.scene.sim;
  if (!quiet) {
    std::fprintf(
        stderr,
        "gearsph run: %s: %s, %zu particles, %lld steps of %.4g s (%s; Courant %.3g, stable "
        "limit %.3g), %s; set up in %.2f s\n",
        job.job.at("name").get<std::string>().c_str(), job.scene.type.c_str(), sim.particles.n,
        static_cast<long long>(job.steps), sim.dt, job.time_step.chosen_by.c_str(),
        job.time_step.courant, job.time_step.courant_limit, threads_text(job).c_str(),
        std::chrono::duration<double>(std::chrono::steady_clock::now() - setup_start).count());
#ifdef GEARSPH_WITH_RESULTS
    // Disk use, stated before the run: an upper bound (ResultsRun tests).
    std::fprintf(stderr, "gearsph run: %lld frames (output.frames): results.h5 at most %.3g MB\n",
                 static_cast<long long>(job.frames),
                 1e-6 * double(results::estimate_results_bytes(job)));
#endif
  }
  ProgressPrinter printer(quiet);
  ExecuteOptions options;
  options.threads = threads;
  options.observer = &printer;
  const RunResult result = execute_prepared(job, *out, options).run;
  if (!quiet) {
    std::fprintf(stderr, "gearsph run: %s in %.2f s on %d thread%s%s; results in %s\n",
                 result.status.c_str(), result.wall_s, sim.threads, sim.threads == 1 ? "" : "s",
                 trial_note(result.summary).c_str(), out->c_str());
  }
  if (result.status == "diverged") {
    std::fprintf(stderr, "gearsph run: %s\n", result.message.c_str());
    return 3;
  }
  return result.status == "cancelled" ? 4 : 0;
}

}  // namespace gearsph::cli
