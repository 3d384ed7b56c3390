#include "solver/run/execute.hpp"

#include <fstream>
#include <mutex>
#include <stdexcept>

namespace gearsph {

namespace {

std::mutex& registry_mutex() {
  static std::mutex m;
  return m;
}

std::vector<OutputFactory>& registry() {
  static std::vector<OutputFactory> r;
  return r;
}

std::vector<SummaryAddition>& additions() {
  static std::vector<SummaryAddition> a;
  return a;
}

}  // namespace

void register_output(OutputFactory factory) {
  std::lock_guard<std::mutex> lock(registry_mutex());
  registry().push_back(std::move(factory));
}

void register_summary_addition(SummaryAddition addition) {
  std::lock_guard<std::mutex> lock(registry_mutex());
  additions().push_back(std::move(addition));
}

void write_file_atomic(const std::filesystem::path& path, const std::string& content) {
  std::filesystem::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string());
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("failed writing " + tmp.string());
  }
  std::filesystem::rename(tmp, path);
}

Execution execute_job(const nlohmann::json& job, const std::filesystem::path& dir,
                      const ExecuteOptions& options) {
  PreparedJob prepared = prepare_job(job, options.threads);
  return execute_prepared(prepared, dir, options);
}

Execution execute_prepared(PreparedJob& job, const std::filesystem::path& dir,
                           const ExecuteOptions& options) {
  std::filesystem::create_directories(dir);
  // summary.json marks a complete run (it is written last): one left by an
  // earlier run in this directory must not vouch for this run's files.
  std::filesystem::remove(dir / "summary.json");
  Execution out;
  write_file_atomic(dir / "job.json", job.job.dump(2) + "\n");
  out.files.push_back("job.json");

  std::vector<std::unique_ptr<RunObserver>> writers;
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    for (const OutputFactory& f : registry()) writers.push_back(f(job, dir));
  }
  ObserverList observers;
  observers.add(options.observer);
  for (auto& w : writers) observers.add(w.get());

  out.run = run_job(job, &observers);
  std::vector<SummaryAddition> adds;
  {
    std::lock_guard<std::mutex> lock(registry_mutex());
    adds = additions();
  }
  for (const SummaryAddition& add : adds) {
    try {
      add(job, out.run, dir, options, out.run.summary);
    } catch (const std::exception& e) {
      out.run.summary["warnings"].push_back(std::string("after the run: ") + e.what());
    }
  }
  write_file_atomic(dir / "history.csv", out.run.history.to_csv());
  out.files.push_back("history.csv");
  // The summary goes last: its presence means the run's files are complete.
  write_file_atomic(dir / "summary.json", out.run.summary.dump(2) + "\n");
  out.files.push_back("summary.json");
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name != "job.json" && name != "history.csv" && name != "summary.json" &&
        entry.is_regular_file() && entry.path().extension() != ".tmp") {
      out.files.push_back(name);
    }
  }
  return out;
}

}  // namespace gearsph
