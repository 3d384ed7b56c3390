#pragma once
// results.xmf: an XDMF2 sidecar that lets ParaView (XDMF Reader) open
// results.h5 directly. A temporal collection of Polyvertex grids, one per
// committed frame; every array is a HyperSlab DataItem picking frame k out of
// the frame-indexed datasets in /frames. Rewritten atomically (temporary
// file + rename) so that ParaView can open a run that is still going.
#include <chrono>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace gearsph::results {

// The XDMF document for `times.size()` frames of `particles` particles
// stored in `h5_name` (a path relative to the .xmf file), whose /frames
// datasets hold `dataset_frames` rows (allocated, not necessarily written).
std::string xdmf_document(const std::string& h5_name, std::size_t particles,
                          const std::vector<double>& times, std::size_t dataset_frames);

class XdmfWriter {
 public:
  XdmfWriter(std::filesystem::path path, std::string h5_name, std::size_t particles,
             std::size_t dataset_frames);

  void add_frame(double time_s) { times_.push_back(time_s); }
  std::size_t frames() const { return times_.size(); }
  // Writes the document now.
  void write();
  // Writes the first time, then at most once a second and at most one part
  // in 50 of the wall time (the document grows with the frames: thousands
  // take milliseconds to write). Rewriting it at every frame cost 5 % of a
  // short run (docs/speed-accuracy-history.md, "Outputs"); a viewer of a running
  // job sees frames at most a second late. The writer calls write() at the
  // end of the run to catch up.
  void write_throttled();

 private:
  using Clock = std::chrono::steady_clock;
  std::filesystem::path path_;
  std::string h5_name_;
  std::size_t particles_;
  std::size_t dataset_frames_;
  std::vector<double> times_;
  bool written_ = false;
  Clock::time_point last_write_{};
  Clock::duration last_duration_{};
};

}  // namespace gearsph::results
