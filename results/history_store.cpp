#include "results/history_store.hpp"

#include <array>
#include <limits>
#include <utility>

namespace gearsph::results {

std::string HistoryStore::dataset_name(const std::string& column) {
  std::string name = column;
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  return name == "." || name.empty() ? "_" + name : name;
}

std::string HistoryStore::unit_of(const std::string& column) {
  // Unit suffixes used by the solver's column names, longest first.
  static const std::array<std::pair<const char*, const char*>, 14> kSuffixes = {{
      {"_J_per_m", "J/m"},
      {"_Nm", "N*m"},
      {"_N_per_m", "N/m"},
      {"_kg_m_s", "kg*m/s"},
      {"_rad_s", "rad/s"},
      {"_m_s", "m/s"},
      {"_rad", "rad"},
      {"_Pa", "Pa"},
      {"_kg", "kg"},
      {"_J", "J"},
      {"_N", "N"},
      {"_W", "W"},
      {"_m", "m"},
      {"_s", "s"},
  }};
  for (const auto& [suffix, unit] : kSuffixes) {
    const std::string s = suffix;
    if (column.size() > s.size() && column.compare(column.size() - s.size(), s.size(), s) == 0) {
      return unit;
    }
  }
  return "";
}

HistoryStore::HistoryStore(hid_t file, const std::vector<std::string>& columns, std::size_t rows)
    : group_(h5::create_group(file, "histories")), pending_(columns.size()) {
  h5::Series::Shape shape;
  shape.chunk = {kRowsPerChunk};
  const double fill = std::numeric_limits<double>::quiet_NaN();
  for (const std::string& c : columns) {
    names_.push_back(dataset_name(c));
    columns_.emplace_back(group_.get(), names_.back(), H5T_IEEE_F64LE, shape, rows, &fill);
  }
  h5::write_attribute(group_.get(), "columns", names_);
}

void HistoryStore::add_row(const History& history, std::size_t row) {
  for (std::size_t c = 0; c < pending_.size(); ++c) pending_[c].push_back(history.at(row, c));
}

void HistoryStore::write_pending() {
  for (std::size_t c = 1; c < columns_.size(); ++c) {
    columns_[c].append(pending_[c], pending_[c].size());
    pending_[c].clear();
  }
}

void HistoryStore::commit() {
  if (columns_.empty()) return;
  columns_[0].append(pending_[0], pending_[0].size());
  pending_[0].clear();
}

}  // namespace gearsph::results
