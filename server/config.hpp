#pragma once
// Everything `gearsph serve` can be told, with the defaults a single
// workstation wants: loopback only, no token, no CORS, one job at a time
// using every core.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "server/image_provider.hpp"

namespace gearsph::server {

// Refusals made before anything is stored or run.
struct Limits {
  std::uint64_t max_body_bytes = 1 << 20;     // request bodies (413 above)
  std::uint32_t max_header_bytes = 16 << 10;  // request line + headers (431 above)
  std::int64_t max_particles = 5'000'000;
  std::int64_t max_steps = 100'000'000;
  double max_particle_steps = 1e12;            // particles x steps: the work of a run
  std::uint64_t max_disk_bytes = 50ull << 30;  // estimated results on disk
  std::int64_t max_study_jobs = 100;           // jobs one POST /studies may create
  // A request (preview, submission, study) builds the whole scene only for
  // jobs estimated (gearsph::estimate_job_size) at this many particles or
  // fewer: about 5 s of set-up on one core (docs/api.md, Admission). Larger
  // jobs are answered from the estimate and built by the worker that runs them.
  std::int64_t max_built_particles = 200'000;
  int max_connections = 512;  // open connections (503 above)
  // Queued jobs (not yet running): all together (503 beyond) and from one
  // client address (429 beyond); a study counts all its jobs.
  std::int64_t max_queued = 1000;
  std::int64_t max_queued_per_client = 200;
};

struct Timeouts {
  std::chrono::milliseconds header{10'000};  // from a request's first byte to its last header
  std::chrono::milliseconds body{30'000};    // reading the body
  std::chrono::milliseconds idle{60'000};    // keep-alive: waiting for the next request
  std::chrono::milliseconds write{60'000};   // a client that takes no bytes for this long
  std::chrono::milliseconds sse_keepalive{15'000};  // comment lines on quiet event streams
  std::chrono::milliseconds build{20'000};  // a request's sizing and scene build (422 after)
};

struct ServerConfig {
  std::string bind = "127.0.0.1";
  unsigned short port = 8080;  // 0: any free port (printed at start-up)
  std::filesystem::path data_dir = "data";
  // Job store: "" for SQLite at data_dir/gearsph.db (this server alone), or
  // a location other processes share: postgresql://... or sqlite:PATH.
  std::string store;
  std::filesystem::path results_dir;     // the job directories; "" for data_dir/jobs
  bool local_workers = true;             // false: the API only; workers run elsewhere
  std::string dispatch = "local";        // "local" (worker pool) or "slurm" (sbatch per job)
  double lease_s = 30.0;                 // claims on a shared store expire unless renewed
  std::vector<std::string> sbatch_args;  // --dispatch slurm: more sbatch options
  std::filesystem::path
      gearsph_executable;   // --dispatch slurm: what the nodes run; "" for this one
  int workers = 0;          // jobs run at the same time; 0: chosen by resolve_defaults
  int threads_per_job = 0;  // OpenMP threads of each job; 0: chosen by resolve_defaults
  int core_budget = 0;      // > 0: jobs share this many cores, threads chosen per job
  std::string token;        // non-empty: every request needs "Authorization: Bearer <token>"
  std::string cors_origin;  // non-empty: CORS for this origin ("*" for any)
  // Host header values answered besides localhost, 127.0.0.1, [::1] and the
  // bound address (each with the server's port): "name" (any port),
  // "name:port", or "*" (any Host: a proxy in front checks it).
  std::vector<std::string> allowed_hosts;
  // Proxies (IP addresses) whose X-Forwarded-For names the client, for
  // failed logins and the queue quota (client_identity.hpp); none by default.
  std::vector<std::string> trusted_proxies;
  std::filesystem::path web_root;  // the dashboard; empty: the compiled-in source path
  int max_attempts = 3;            // runs interrupted by a crash this often are failed
  int io_threads = 2;              // threads of the io_context (network only)
  int handler_threads = 2;  // threads for slow handlers (job preparation, rendering, deletion)
  int store_threads = 2;    // threads for handlers that read the job store or a job's files
  std::chrono::milliseconds progress_interval{250};  // at most 4 progress events/s per job
  std::chrono::milliseconds flush_interval{1000};    // progress batches to the store
  std::chrono::milliseconds shutdown_grace{3000};    // for in-flight responses on SIGTERM
  // SIGTERM: running jobs may finish for this long (a warm shutdown) before
  // they stop and go back to the queue; a second signal cuts it short.
  std::chrono::milliseconds job_grace{0};
  // > 0: jobs that ended longer ago than this (and their files, studies
  // left empty, idempotency keys, silent workers) are deleted, hourly.
  double retention_s = 0;
  Limits limits;
  Timeouts timeouts;
  ImageProvider image_provider;                // empty: the images endpoint answers 501
  std::uint64_t image_cache_bytes = 64 << 20;  // rendered images kept in memory (0: none)
  // Why jobs asking for the FE check ("fe_check": true) cannot run here, ""
  // when they can (gmsh and CalculiX found). Empty: a build without the FE
  // layer. Either way such jobs are refused with 501.
  std::function<std::string()> fe_check_unavailable;
};

// Where the job directories are; whether other processes share the store.
std::filesystem::path results_dir_of(const ServerConfig& config);
bool shared_store(const ServerConfig& config);
// "host:pid": names this process's claims in a shared store.
std::string process_name();

// Fills workers / threads_per_job so that workers x threads <= cores. By
// default the cores are a budget (core_budget) that jobs share: up to one
// job per core, each taking the threads its size is worth while no other
// job waits, one thread while others do (two paper-size jobs at once on two
// cores; a lone large run still gets every core). With either given, the
// fixed split: the other one divides the cores.
void resolve_defaults(ServerConfig& config, int cores);

// The token in a file: its first line without surrounding white space.
// Throws if the file cannot be read or holds no token.
std::string read_token_file(const std::filesystem::path& file);

// --web, else the source tree's web/ compiled in, else web/ next to the
// executable's directory; empty if none exists.
std::filesystem::path default_web_root();

const char* version();

}  // namespace gearsph::server
