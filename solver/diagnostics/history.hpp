#pragma once
// Time histories: named columns sampled every k steps (first column time_s).
#include <cstddef>
#include <string>
#include <vector>

namespace gearsph {

class History {
 public:
  explicit History(std::vector<std::string> columns = {}) : columns_(std::move(columns)) {}
  const std::vector<std::string>& columns() const { return columns_; }
  std::size_t rows() const { return columns_.empty() ? 0 : data_.size() / columns_.size(); }
  // Index of a column, or -1.
  int index(const std::string& name) const;
  std::vector<double> column(const std::string& name) const;
  double at(std::size_t row, std::size_t col) const { return data_[row * columns_.size() + col]; }
  void add_row(const std::vector<double>& row);
  void reserve_rows(std::size_t n) { data_.reserve(n * columns_.size()); }
  // CSV with a header row; full double precision.
  std::string to_csv() const;

 private:
  std::vector<std::string> columns_;
  std::vector<double> data_;
};

}  // namespace gearsph
