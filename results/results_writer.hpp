#pragma once
// ResultsWriter: the RunObserver that writes results.h5 (layout in
// results_layout.hpp) while a job runs, appending each snapshot and the
// history samples as they arrive, and keeps results.xmf in step with it.
//
// Crash safety. A run killed with SIGKILL at any moment must leave a
// results.h5 that h5dump, h5ls, ParaView and ResultsFile open, holding every
// frame completed before the kill.
//
// Why not SWMR: HDF5 1.10 single-writer/multiple-reader needs the 1.10 file
// format (superblock v3), whose "open for writing" flags stay set when the
// writer dies. Until someone runs `h5clear -s`, h5dump, h5ls and ParaView
// (none opens with H5F_ACC_SWMR_READ) refuse such a file, and they refuse a
// live SWMR file as well (tried: "unable to open file"; the same holds for
// any 1.10-format file whose writer was killed). So the writer uses the
// default, 1.8-compatible format, which has no such flags, and H5Fflush,
// arranged so that no interrupted write can damage a committed frame:
//  1. Structure first. Every group, dataset and attribute is created at the
//     start with all planned frames and history rows allocated
//     (H5D_ALLOC_TIME_EARLY: each chunk holds the fill value and each chunk
//     index, a v1 B-tree, is complete). The file appears as results.h5
//     (rename of results.h5.tmp) only once this is on disk.
//  2. Then nothing changes shape. Writing a frame replaces its chunks: the
//     compressed data goes to new space (or to the placeholder space it
//     frees) and only that frame's entries in the B-tree change, in place;
//     uncompressed marker and history chunks are rewritten in place. No
//     node is inserted or split, no dataset extended, nothing a committed
//     frame uses is freed. A write cut short by the kill (Linux stops a
//     write between pages on SIGKILL) or read half-done by a live reader can
//     only mix old and new bytes, and the bytes that differ belong to the
//     frame being written. The superblock (end-of-file address) is written
//     last: HDF5 flushes its ring after the user-data ring.
//  3. Commit markers. A frame goes in two phases, each ended by H5Fflush:
//     all fields, then /frames/time and /frames/step. Readers count the
//     frames whose step holds a value (fill -1); a kill before that leaves a
//     frame they ignore. History samples ride along, with /histories/time_s
//     as their marker.
// Appending by extending the datasets instead (tried first) rewrites a
// growing B-tree node, entry count included, on every frame: a torn node can
// misdirect the binary search for older chunks, and in one of ~100 killed
// runs of the test a committed frame did read back wrong.
// Rows not (yet) written read as the fill value, so a run that ended early
// shows NaN frames in h5dump; readers and results.xmf see only committed
// ones. More frames or samples than planned make the datasets grow, outside
// this guarantee (the runner produces exactly PreparedJob::frames).
// The writer takes no file lock, so ParaView and h5dump can open the file of
// a running job. ResultsCrash.* in tests/test_results.cpp kills `gearsph run`
// at random moments and checks every committed frame bit for bit.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>

#include "results/frame_store.hpp"
#include "results/history_store.hpp"
#include "results/results_layout.hpp"
#include "results/xdmf_writer.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::results {

class ResultsWriter final : public RunObserver {
 public:
  explicit ResultsWriter(std::filesystem::path dir);
  ~ResultsWriter() override;
  ResultsWriter(const ResultsWriter&) = delete;
  ResultsWriter& operator=(const ResultsWriter&) = delete;

  void on_start(const PreparedJob& job) override;
  void on_sample(const Simulation& sim, const History& history) override;
  void on_snapshot(const Simulation& sim, std::int64_t frame) override;
  void on_finish(const PreparedJob& job, const RunResult& result) override;

  std::filesystem::path path() const { return dir_ / kResultsFile; }

  // History samples reach the file at least this often, even between frames.
  static constexpr std::chrono::seconds kHistoryFlushInterval{2};

 private:
  void start_histories(const History& history);
  void take_new_rows(const History& history);
  void commit_histories();
  void publish();

  std::filesystem::path dir_;
  std::filesystem::path temp_path_;
  h5::Id file_;
  FrameStore frames_;
  HistoryStore histories_;
  std::optional<XdmfWriter> xdmf_;
  std::size_t planned_rows_ = 0;
  std::size_t rows_taken_ = 0;
  bool published_ = false;
  std::chrono::steady_clock::time_point last_flush_{};
};

// The history rows a run records: the runner samples the initial state,
// every history_every steps and the last step (runner.cpp).
std::uint64_t planned_history_rows(const PreparedJob& job);

// Upper bound on the size of the run's results.h5 with nothing compressed,
// so that a run can state its disk use before it starts.
std::uint64_t estimate_results_bytes(const PreparedJob& job);

}  // namespace gearsph::results
