#include "solver/diagnostics/history.hpp"

#include <cstdio>
#include <stdexcept>

namespace gearsph {

int History::index(const std::string& name) const {
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (columns_[c] == name) return static_cast<int>(c);
  }
  return -1;
}

std::vector<double> History::column(const std::string& name) const {
  const int c = index(name);
  if (c < 0) throw std::out_of_range("history has no column '" + name + "'");
  std::vector<double> out(rows());
  for (std::size_t r = 0; r < out.size(); ++r) out[r] = at(r, static_cast<std::size_t>(c));
  return out;
}

void History::add_row(const std::vector<double>& row) {
  if (row.size() != columns_.size()) throw std::invalid_argument("history row has wrong width");
  data_.insert(data_.end(), row.begin(), row.end());
}

std::string History::to_csv() const {
  std::string out;
  for (std::size_t c = 0; c < columns_.size(); ++c) {
    if (c) out += ',';
    out += columns_[c];
  }
  out += '\n';
  char buf[32];
  for (std::size_t r = 0; r < rows(); ++r) {
    for (std::size_t c = 0; c < columns_.size(); ++c) {
      if (c) out += ',';
      std::snprintf(buf, sizeof buf, "%.10g", at(r, c));
      out += buf;
    }
    out += '\n';
  }
  return out;
}

}  // namespace gearsph
