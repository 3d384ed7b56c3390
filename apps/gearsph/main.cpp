// gearsph: one executable, several subcommands.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>

#include <malloc.h>
#include <unistd.h>

#include "apps/gearsph/cli.hpp"
#include "solver/core/cache_aligned.hpp"
#ifdef GEARSPH_WITH_RESULTS
#include "results/register_outputs.hpp"
#endif
#ifdef GEARSPH_WITH_RENDER
#include "render/fillet_plot.hpp"
#endif
#ifdef GEARSPH_WITH_FE
#include "fe/fe_check.hpp"
#endif

namespace {

const char* kUsage = R"(gearsph - SPH simulation of rack-and-pinion gear meshing

usage:
  gearsph run JOB.json --out DIR [--threads N] [--quiet]
      run one job; writes DIR/summary.json and DIR/history.csv
  gearsph validate [--quick] [--only TEXT] [--out DIR] [--threads N]
      run the validation cases against their references (--only: the cases
      whose id contains TEXT); prints a table and writes DIR/validation.json
      (DIR defaults to ./validation)
  gearsph validate --study accuracy [--quick] [--cases N] [--out DIR] [--threads N]
                   [--fillet-tolerance T] [--replot DIR/accuracy.json]
      the accuracy map: static checks of pinions drawn from the space users work
      in (z 8-60, m 1-10 mm, 14.5-25 deg, x -0.5..+0.8, rims, 50-500 N/mm, pitch,
      HPSTC, tip), each against its FE check; 40 cases (--quick: 5); writes
      DIR/accuracy.json with the errors' median, 95th percentile and worst
      (DIR defaults to ./accuracy); --fillet-tolerance: fail when a fillet
      tension peak is further than T (0.05: 5 %) from FE; --replot draws an
      earlier map's accuracy_map.png again
  gearsph study stability [--out DIR] [--full] [--only TEXT] [--threads N] [--no-images]
      the stability study: failure-prone cases x methods, measured; writes
      DIR/stability.csv, stability.json, stability_table.png and fields/*.png
      (DIR defaults to ./stability; --full adds the long cells, docs/stability.md)
  gearsph study speed-sweep JOB.json --out DIR [--ratios 0.2,0.4,...] [--steady-periods N]
                [--threads N] [--max-particle-steps N] [--lumped-only] [--damping-ratio Z]
                [--stiffness iso|measured] [--stiffness-positions N]
      a loaded rack_pinion job at several speeds (ratios of the mesh frequency
      to the lumped model's natural frequency), each run until its steady mesh
      has lasted N (20) mesh periods, beside the lumped model and ISO 6336-1's
      resonance; writes DIR/speed_sweep.json, speed_sweep.png and runs/
      (docs/dynamics.md); the lumped model's mesh stiffness ISO's two levels
      or (measured) N (8) quasi-static checks of the same pair over a cycle
  gearsph bench [--quick] [--out DIR] [--repeats N] [--no-pysph] [--python PATH]
                [--pysph-script FILE] [--skip-full] [--max-particles N]
                [--skip-study] [--study-jobs N]
      speed side by side: plate and gear throughput at 1 and 2 threads (best of
      --repeats), PySPH's plate (run by --python with bench/pysph_plate.py or
      --pysph-script) bare and end to end, cost per particle-step 1e3..1e6,
      memory, the paper's full case (the default beside the paper's lattice),
      and a study of N (16) paper's cases through gearsph serve (--quick:
      their first 2 ms)
  gearsph bench pareto --out DIR [--quick] [--threads N] [--cases plate,hertz,gear]
      error against cost: plate (kernel, spacing, h/dx, CFL, UL/TL), Hertz p0
      and gear root bending (kernel, spacing); CSV + PNG per case
  gearsph schema
      print the job schema (JSON Schema draft-07)
  gearsph rate RATING.json [--out FILE]
      ISO 6336 rating of a gear pair (schemas/rating.schema.json, docs/rating.md):
      stresses, safety factors per gear, every factor, static safety and life
  gearsph geometry JOB.json --out DIR
      the scene's outlines and particles as SVG and CSV, without running it
  gearsph fe JOB.json --out DIR [--fillet-sizes-mm 0.2,0.1] [--threads N] [--rim-depth-mm D] [--teeth 3|all] [--compare RUN_DIR] [--keep-model-files] [--no-images] [--timeout-s S] [--quiet]
      finite-element check of a quasi-static rack_pinion job (gmsh, CalculiX): tooth 0
      under the job's load at its contact_point, meshed at each fillet element size
      (default: 1/12 and 1/24 of ISO's fillet radius, 0.2 and 0.1 mm for the paper's
      pinion; the finest is the reference); the teeth and rim the SPH static check
      models unless --rim-depth-mm or --teeth say otherwise; --compare takes the load and
      the structure from a finished SPH run and writes fe_comparison.json; writes DIR/fe_summary.json, fe_fillet_curves.csv/.json
      and PNG images; --keep-model-files keeps the .geo/.inp/.frd in DIR/fe_model
  gearsph render RUN_DIR|results.h5 --out FILE.png [--field von_mises] [--frame K] [--zoom x0,y0,x1,y1] [--range lo,hi] [--particles]
      a frame of a run as the service draws it (frame -1: the last); --range fixes the
      colour scale (SI); --frames all --out DIR writes every frame; a field is drawn as
      contours inside the outlines, smoothed for the drawing; --particles draws each
      particle as a disc of its own value
  gearsph plot RUN_DIR --columns A,B --out FILE.png [--title T] [--ylabel L] [--scale S]
      history.csv columns against time
  gearsph serve [options]
      the job service: HTTP API, job store, worker pool, dashboard (docs/api.md)
      --port P             TCP port (8080; 0: any free port, printed at start-up)
      --bind ADDR          address to listen on (127.0.0.1; 0.0.0.0: every interface)
      --allowed-host H     another name to answer to in the Host header: name,
                           name:port or * (repeatable; localhost, 127.0.0.1, [::1]
                           and the bound address with the port are always answered)
      --trusted-proxy A    a reverse proxy in front (IP address, repeatable): its
                           X-Forwarded-For names the client (none)
      --data DIR           job store DIR/gearsph.db and job directories DIR/jobs/ (./data)
      --workers N          jobs running at the same time (1)
      --threads-per-job M  most OpenMP threads a job gets (cores / N)
      --token-file F       every request for data needs the token on F's first line
      --cors-origin O      allow browser requests from origin O (* for any)
      --web DIR            the dashboard's files (the source tree's web/)
      --max-attempts N     a job interrupted by this many crashes fails (3)
      limits:   --max-body-bytes B (1048576)  --max-particles N (5e6)  --max-steps N (1e8)
                --max-particle-steps N (1e12)  --max-disk-gb G (50)  --max-study-jobs N (100)
                --max-connections N (512)  --image-cache-mb M (64, rendered images in memory)
                --build-budget N (2e5: a request builds the scene of at most N particles)
                --max-queued N (1000 jobs waiting, 503 beyond)
                --max-queued-per-client N (200 jobs waiting from one client: its
                session or token, else its address; 429 beyond)
      timeouts [s]: --header-timeout 10  --body-timeout 30  --idle-timeout 60
                --write-timeout 60  --keepalive 15 (comments on quiet event streams)
                --build-timeout 20 (a request's sizing and scene build)
      many machines (docs/scale-out.md): --store URL (postgresql://..., libpq's
                host=... dbname=..., or sqlite:PATH) or --store-file FILE (its first
                line; or the environment's GEARSPH_STORE: no password in argv)
                --results DIR  --no-local-workers  --lease S (30)  --dispatch local|slurm
                --sbatch-arg A (repeatable)  --slurm-gearsph PATH
      --job-grace S        on SIGTERM, running jobs may finish for S seconds (0)
                           before they are re-queued; a second signal: at once
      --retention-days D   delete jobs (and their files) that ended D days ago,
                           hourly (default: keep everything)
  gearsph submit JOB.json --server URL [--wait] [--out DIR] [--token-file F]
                 [--idempotency-key KEY] [--retry-for SECONDS]
      submit a job to a server (URL may hold a path: http://host/gearsph), print
      its id; --wait follows its progress, --out DIR also downloads its files;
      --idempotency-key: a retried submission with the same key and job makes
      no second job; --retry-for: how long --wait keeps trying while the server
      is unreachable (300); exit 0 successful, 3 failed, 4 dismissed, 2 invalid
  gearsph worker --store URL|--store-file FILE --results DIR [--workers N] [--threads-per-job M]
                 [--lease S] [--poll S] [--max-attempts N] [--job-grace S]
      run jobs from a shared job store (docs/scale-out.md): claims held for
      --lease seconds (30), the queue looked at every --poll seconds (0.5);
      SIGTERM lets running jobs finish for --job-grace seconds (0), then
      re-queues them (a second signal: at once)
  gearsph help

exit status: 0 success, 1 error, 2 invalid job or usage, 3 run diverged, 4 cancelled,
  5 FE unavailable (gmsh or CalculiX missing, or a build without the FE layer)
)";

// The usage lines of one command (its `  gearsph CMD ...` lines and their
// indented description), or all of them if `cmd` has none.
std::string command_usage(const std::string& cmd) {
  std::string out, line;
  bool inside = false;
  for (const char* c = kUsage; *c; ++c) {
    if (*c != '\n') {
      line += *c;
      continue;
    }
    const std::string head = "  gearsph " + cmd;
    if (line.rfind("  gearsph ", 0) == 0) {
      inside = line.rfind(head, 0) == 0 && (line.size() == head.size() || line[head.size()] == ' ');
    } else if (line.rfind("      ", 0) != 0) {
      inside = false;
    }
    if (inside) out += line + "\n";
    line.clear();
  }
  return out.empty() ? std::string(kUsage) : "usage:\n" + out;
}

bool asks_for_help(int argc, char** argv) {
  for (int i = 2; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) return true;
  }
  return false;
}

}  // namespace

namespace gearsph::cli {
int cmd_study(Args& args);             // cmd_study.cpp
int cmd_rate(Args& args);              // cmd_rate.cpp
int cmd_bench(int argc, char** argv);  // cmd_bench.cpp: `bench` and `bench pareto`
#ifdef GEARSPH_WITH_FE
int cmd_fe(Args& args);  // cmd_fe.cpp
#endif
}  // namespace gearsph::cli

#ifdef GEARSPH_WITH_SERVICE
namespace gearsph::cli {
int cmd_serve(Args& args);
int cmd_submit(Args& args);
int cmd_worker(Args& args);
#ifdef GEARSPH_WITH_RENDER
int cmd_render(Args& args);  // cmd_render.cpp
int cmd_plot(Args& args);
#endif
}  // namespace gearsph::cli
#endif

namespace {

// How OpenMP threads wait at a barrier. libgomp reads its policy once, when
// it is loaded, before main: only a fresh process image can choose one. A
// time step hands over between threads several times, so threads that sleep
// at once (passive) pay a wake-up at each, and threads that spin long (the
// default, 300,000 rounds) starve each other when two runs share the cores.
// A spin of 1,000 rounds, then sleep, is close to the fastest alone and,
// unlike a long spin, does not starve a run it shares the cores with. A
// policy the caller set (OMP_WAIT_POLICY, GOMP_SPINCOUNT) is kept.
// Measurements: docs/speed-accuracy-history.md, "Threads".
// A command told to run on one thread (`--threads 1`) never waits at a
// barrier, so it keeps its first image: the second start was 5 % of a short
// plate run (docs/speed-accuracy-history.md, "Outputs").
bool one_thread_asked(int argc, char** argv) {
  for (int k = 1; k + 1 < argc; ++k) {
    if (std::strcmp(argv[k], "--threads") == 0) return std::strcmp(argv[k + 1], "1") == 0;
  }
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--threads=1") == 0) return true;
  }
  return false;
}

void choose_openmp_wait(int argc, char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (one_thread_asked(argc, argv)) return;
  setenv("GOMP_SPINCOUNT", "1000", 1);
  execv("/proc/self/exe", argv);  // returns only on failure: carry on as we are
}

}  // namespace

int main(int argc, char** argv) {
  choose_openmp_wait(argc, argv);
  // Arrays of 1 MiB and more (every column of a scene past 130,000
  // particles) are mapped on their own and unmapped when freed, so a server
  // or bench that runs scenes of many sizes does not carve its heap into
  // holes that raise a later scene's peak memory; a fixed threshold also
  // stops glibc raising it after the first such free. Not lower: zlib's
  // buffers for each chunk HDF5 compresses would then be mapped and unmapped
  // every time. See docs/speed-accuracy-history.md, "Outputs".
  mallopt(M_MMAP_THRESHOLD, static_cast<int>(gearsph::kMapFrom));
  // And the heap's top is kept, up to 64 MiB, not handed back at every free:
  // with the mmap threshold fixed, glibc's trim threshold stays at 128 KiB
  // (same section).
  mallopt(M_TRIM_THRESHOLD, 64 << 20);
#ifdef GEARSPH_WITH_RESULTS
  gearsph::results::register_outputs();
#endif
#ifdef GEARSPH_WITH_FE
  // Runs of jobs with "fe_check" (run, serve, worker) add the FE check.
  gearsph::fe::register_fe_check();
#endif
#ifdef GEARSPH_WITH_RENDER
  // Static checks get their fillet curves as a picture (after the FE check,
  // whose curves it draws beside them).
  gearsph::render::register_fillet_plot();
#endif
  if (argc < 2 || !std::strcmp(argv[1], "help") || !std::strcmp(argv[1], "--help") ||
      !std::strcmp(argv[1], "-h")) {
    std::fputs(kUsage, argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string cmd = argv[1];
  if (asks_for_help(argc, argv)) {  // `gearsph render --help`
    std::fputs(command_usage(cmd).c_str(), stdout);
    return 0;
  }
  gearsph::cli::Args args(argc, argv, 2);
  try {
    if (cmd == "run") return gearsph::cli::cmd_run(args);
    if (cmd == "validate") return gearsph::cli::cmd_validate(args);
    if (cmd == "schema") return gearsph::cli::cmd_schema(args);
    if (cmd == "study") return gearsph::cli::cmd_study(args);
    if (cmd == "bench") return gearsph::cli::cmd_bench(argc, argv);
    if (cmd == "geometry") return gearsph::cli::cmd_geometry(args);
    if (cmd == "rate") return gearsph::cli::cmd_rate(args);
#ifdef GEARSPH_WITH_FE
    if (cmd == "fe") return gearsph::cli::cmd_fe(args);
#else
    if (cmd == "fe") {
      std::fprintf(stderr, "gearsph fe: FE unavailable: this build has no FE layer (GEARSPH_FE)\n");
      return 5;
    }
#endif
#ifdef GEARSPH_WITH_SERVICE
    if (cmd == "serve") return gearsph::cli::cmd_serve(args);
#endif
#ifdef GEARSPH_WITH_SERVICE
    if (cmd == "submit") return gearsph::cli::cmd_submit(args);
    if (cmd == "worker") return gearsph::cli::cmd_worker(args);
#ifdef GEARSPH_WITH_RENDER
    if (cmd == "render") return gearsph::cli::cmd_render(args);
    if (cmd == "plot") return gearsph::cli::cmd_plot(args);
#endif
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
