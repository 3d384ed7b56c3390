#pragma once
// ResultsFile: reads a results.h5 (layout in results_layout.hpp), also one
// that is still being written or was left by a killed run: it sees the
// frames and history rows committed when it was opened (open it again to
// see later ones). Every failure is a ResultsError with a message a user
// understands.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "results/h5_util.hpp"
#include "results/outlines.hpp"

namespace gearsph::results {

class ResultsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct BodyInfo {
  std::string name;
  std::int64_t begin = 0, end = 0;  // particle index range [begin, end)
  double E_Pa = 0.0, nu = 0.0, rho_kg_m3 = 0.0;
};

struct InitialState {
  std::vector<double> position;  // N x 3, row-major, z = 0
  std::vector<std::int32_t> body_id, particle_id;
  std::vector<double> mass;  // kg per metre of thickness
};

struct Frame {
  std::size_t index = 0;
  std::int64_t step = 0;
  double time_s = 0.0;
  std::vector<double> position, velocity, displacement;            // N x 3, row-major
  std::vector<double> stress_xx, stress_yy, stress_xy, stress_zz;  // Cauchy stress [Pa]
  std::vector<double> pressure, von_mises, density;
  std::vector<std::int32_t> body_id, particle_id;
};

class ResultsFile {
 public:
  explicit ResultsFile(const std::filesystem::path& path);

  const std::filesystem::path& path() const { return path_; }
  std::int64_t format_version() const;
  std::string solver_version() const;
  std::string created() const;
  // running (also: a run killed while running) | completed | cancelled | diverged
  std::string status() const;
  std::int64_t steps_done() const;
  nlohmann::json job() const;
  nlohmann::json units() const;

  std::size_t particle_count() const { return particles_; }
  std::size_t frame_count() const { return steps_.size(); }
  const std::vector<double>& frame_times() const { return times_; }
  const std::vector<std::int64_t>& frame_steps() const { return steps_; }
  Frame frame(std::size_t index) const;
  // One field of one frame (names as in kFrameFields): float64 fields, and
  // the int32 ones (body_id, particle_id).
  std::vector<double> field(std::size_t frame, const std::string& name) const;
  std::vector<std::int32_t> int_field(std::size_t frame, const std::string& name) const;

  std::vector<BodyInfo> bodies() const;
  InitialState initial() const;
  std::vector<StoredOutline> outlines() const;

  // History columns in their recorded order (the first is time_s).
  const std::vector<std::string>& history_columns() const { return columns_; }
  std::size_t history_rows() const { return history_rows_; }
  std::vector<double> history(const std::string& column) const;

 private:
  void check_format(hid_t file) const;
  void read_frame_index(hid_t file);
  void read_history_index(hid_t file);
  template <class T>
  std::vector<T> frame_row(std::size_t frame, const std::string& name, bool integer) const;
  hid_t meta() const { return meta_.get(); }

  std::filesystem::path path_;
  h5::Id file_, meta_;
  std::size_t particles_ = 0;
  std::vector<double> times_;
  std::vector<std::int64_t> steps_;
  std::vector<std::string> columns_;
  std::size_t history_rows_ = 0;
};

}  // namespace gearsph::results
