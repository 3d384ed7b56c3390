#pragma once
// The /frames group of results.h5: per-particle fields of every snapshot in
// frame-indexed datasets, written in two phases (fields, then the time/step
// commit markers) so that a reader trusts a frame only once all of it is on
// disk (results_writer.hpp).
#include <cstdint>
#include <vector>

#include "results/h5_series.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::results {

class FrameStore {
 public:
  FrameStore() = default;
  // Allocates `frames` frames up front (h5_series.hpp); `compress`: shuffle
  // + deflate each chunk (1.4-1.8x smaller fields, but zlib took a quarter
  // of a short run's time, docs/results.md).
  FrameStore(hid_t file, std::size_t particles, std::size_t frames, bool compress);

  // Phase 1: appends every field of the current state.
  void write_fields(const Simulation& sim);
  // Phase 2: appends time and step, which make the frame visible to readers.
  void commit(const Simulation& sim);
  std::size_t frames() const { return static_cast<std::size_t>(step_.written()); }

  // Chunks hold one frame of up to kChunkParticles particles (3 MiB for a
  // vector field): a frame is read by touching one chunk per field, and every
  // chunk is written once, whole (replacing its fill-value placeholder).
  static constexpr std::size_t kChunkParticles = std::size_t{1} << 17;
  // time/step: 8 KiB uncompressed chunks, rewritten in place.
  static constexpr hsize_t kMarkerChunkRows = 1024;
  static std::uint64_t chunks_per_frame(std::size_t particles);

 private:
  void write_field(std::size_t k, const Particles& p);

  h5::Id group_;
  bool compress_ = false;
  std::vector<h5::Series> fields_;  // in kFrameFields order
  h5::Series time_, step_;
  std::vector<double> values_;      // gather buffer, sized once
  std::vector<std::int32_t> ints_;  // gather buffer, sized once
};

}  // namespace gearsph::results
