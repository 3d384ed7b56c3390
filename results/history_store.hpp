#pragma once
// The /histories group of results.h5: one float64 dataset per History
// column, the planned rows allocated up front (h5_series.hpp). Samples are
// buffered and written in the writer's data phase; the first column (time_s)
// is written last, in the commit phase, so a row counts only once every
// column holds it.
#include <string>
#include <vector>

#include "results/h5_series.hpp"
#include "solver/diagnostics/history.hpp"

namespace gearsph::results {

class HistoryStore {
 public:
  HistoryStore() = default;
  // Allocates `rows` rows up front (h5_series.hpp).
  HistoryStore(hid_t file, const std::vector<std::string>& columns, std::size_t rows);

  bool created() const { return group_.valid(); }
  void add_row(const History& history, std::size_t row);
  bool has_pending() const { return !pending_.empty() && !pending_[0].empty(); }
  void write_pending();  // phase 1: every column but the first
  void commit();         // phase 2: the first column
  const std::vector<std::string>& names() const { return names_; }
  // Committed rows (those of the first column).
  std::size_t rows() const { return columns_.empty() ? 0 : columns_[0].written(); }

  // 8 KiB chunks, uncompressed: a chunk holding committed rows is rewritten
  // in place with the same bytes for those rows, never moved (a compressed
  // one would be reallocated, and its old space reused, at every append).
  static constexpr hsize_t kRowsPerChunk = 1024;

  // The dataset name of a column: HDF5 link names cannot hold '/'.
  static std::string dataset_name(const std::string& column);
  // The unit a column name ends with (time_s -> s, max_von_mises_Pa -> Pa), or "".
  static std::string unit_of(const std::string& column);

 private:
  h5::Id group_;
  std::vector<std::string> names_;
  std::vector<h5::Series> columns_;
  std::vector<std::vector<double>> pending_;
};

}  // namespace gearsph::results
