#include "results/results_writer.hpp"

#include <algorithm>

#include "results/outlines.hpp"
#include "results/run_description.hpp"

namespace gearsph::results {

namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t ceil_div(std::uint64_t a, std::uint64_t b) {
  return (a + b - 1) / b;
}

}  // namespace

std::uint64_t planned_history_rows(const PreparedJob& job) {
  const std::int64_t every = std::max<std::int64_t>(job.history_every, 1);
  const std::int64_t steps = std::max<std::int64_t>(job.steps, 0);
  return static_cast<std::uint64_t>(1 + steps / every + (steps % every ? 1 : 0));
}

ResultsWriter::ResultsWriter(std::filesystem::path dir) : dir_(std::move(dir)) {}

ResultsWriter::~ResultsWriter() {
  h5::QuietErrors quiet;
  file_.reset();
  // A file that never became complete is not left behind.
  std::error_code ignored;
  if (!published_ && !temp_path_.empty()) std::filesystem::remove(temp_path_, ignored);
}

namespace {

// The cracks as they ended (a grown crack's path, one vertex per increment
// after the drawn tip), or as drawn if the run stopped: /cracks.
void write_crack_paths(hid_t file, const Simulation& sim) {
  std::vector<StoredOutline> list;
  for (const geometry::Crack& c : sim.cracks) {
    StoredOutline o{"crack", c.body, {}, false};
    for (const geometry::Point q : c.path) o.points.push_back({q.x, q.y});
    list.push_back(std::move(o));
  }
  if (!list.empty()) write_outlines(file, list, "cracks");
}

}  // namespace

void ResultsWriter::on_start(const PreparedJob& job) {
  h5::QuietErrors quiet;
  const Simulation& sim = job.scene.sim;
  if (sim.particles.n == 0) throw std::runtime_error("results.h5: the scene has no particles");
  temp_path_ = dir_ / (std::string(kResultsFile) + ".tmp");
  file_ = h5::create_file(temp_path_);
  write_meta(file_.get(), job);
  write_bodies(file_.get(), sim);
  write_initial(file_.get(), sim.particles);
  write_scene_outlines(file_.get(), job.scene);
  const auto frames = static_cast<std::size_t>(std::max<std::int64_t>(job.frames, 0));
  frames_ = FrameStore(file_.get(), sim.particles.n, frames, job.compress_frames);
  planned_rows_ = planned_history_rows(job);
  xdmf_.emplace(dir_ / kXdmfFile, kResultsFile, sim.particles.n, frames);
}

// The history columns are known from the first sample on; with them the
// file's structure is complete.
void ResultsWriter::start_histories(const History& history) {
  histories_ = HistoryStore(file_.get(), history.columns(), planned_rows_);
  write_units(file_.get(), histories_.names());
}

void ResultsWriter::publish() {
  if (published_) return;
  std::filesystem::rename(temp_path_, path());
  published_ = true;
}

void ResultsWriter::take_new_rows(const History& history) {
  for (; rows_taken_ < history.rows(); ++rows_taken_) histories_.add_row(history, rows_taken_);
}

// Histories alone, between frames: the same two phases as a frame.
void ResultsWriter::commit_histories() {
  histories_.write_pending();
  h5::flush(file_.get());
  histories_.commit();
  h5::flush(file_.get());
  last_flush_ = Clock::now();
}

void ResultsWriter::on_sample(const Simulation&, const History& history) {
  h5::QuietErrors quiet;
  if (!histories_.created()) start_histories(history);
  take_new_rows(history);
  // Due at the first sample too (last_flush_ starts at the clock's epoch),
  // after which the complete file is published.
  if (Clock::now() - last_flush_ >= kHistoryFlushInterval) commit_histories();
  publish();
}

void ResultsWriter::on_snapshot(const Simulation& sim, std::int64_t) {
  h5::QuietErrors quiet;
  frames_.write_fields(sim);
  histories_.write_pending();
  h5::flush(file_.get());  // phase 1: the frame's data is on disk
  frames_.commit(sim);
  histories_.commit();
  h5::flush(file_.get());  // phase 2: and now readers count it
  last_flush_ = Clock::now();
  xdmf_->add_frame(sim.time);
  if (published_) xdmf_->write_throttled();
}

void ResultsWriter::on_finish(const PreparedJob& job, const RunResult& result) {
  h5::QuietErrors quiet;
  if (!file_.valid()) return;
  if (!histories_.created()) start_histories(result.history);
  take_new_rows(result.history);
  commit_histories();
  write_status(file_.get(), result.status, result.steps_done);
  write_crack_paths(file_.get(), job.scene.sim);
  file_.reset();  // closes: the file is complete
  publish();
  if (xdmf_->frames() > 0) xdmf_->write();
}

std::uint64_t estimate_results_bytes(const PreparedJob& job) {
  const Simulation& sim = job.scene.sim;
  const std::uint64_t n = sim.particles.n;
  const std::uint64_t frames = static_cast<std::uint64_t>(std::max<std::int64_t>(job.frames, 0));
  std::uint64_t per_particle = 0;
  for (const FieldSpec& f : kFrameFields) per_particle += f.components * (f.integer ? 4 : 8);
  // Chunks are allocated whole.
  const std::uint64_t markers =
      ceil_div(frames, FrameStore::kMarkerChunkRows) * FrameStore::kMarkerChunkRows * 16;
  // The runner's own columns (9 today) plus the scene's; 16 leaves room.
  const std::uint64_t columns = job.scene.columns.size() + 16;
  const std::uint64_t histories = ceil_div(planned_history_rows(job), HistoryStore::kRowsPerChunk) *
                                  HistoryStore::kRowsPerChunk * 8 * columns;
  const std::uint64_t initial = n * (24 + 4 + 4 + 8);
  const std::uint64_t bodies = sim.bodies.size() * (256 + 16 + 24);
  // Metadata: per frame chunk a B-tree entry and its fill-value placeholder
  // (< 256 bytes together); per dataset an object header; the attributes'
  // text; a fixed allowance for groups and the superblock.
  const std::uint64_t chunks = frames * FrameStore::chunks_per_frame(n) * kFrameFields.size();
  const std::uint64_t datasets = kFrameFields.size() + 2 + columns + 10;
  const std::uint64_t text = 2 * job.job.dump().size() + 4096 + 128 * columns;
  const std::uint64_t metadata = chunks * 256 + datasets * 4096 + text + 64 * 1024;
  return frames * n * per_particle + markers + histories + initial + bodies + metadata;
}

}  // namespace gearsph::results
