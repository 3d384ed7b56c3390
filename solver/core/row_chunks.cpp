#include "solver/core/row_chunks.hpp"

#include <algorithm>

namespace gearsph {

void RowChunks::plan(const std::vector<std::uint32_t>& rows, const std::vector<std::uint32_t>& j,
                     int threads, int components, RowCost row_cost) {
  const std::size_t n = rows.empty() ? 0 : rows.size() - 1;
  const int t_count = std::max(1, threads);
  components_ = components;
  // Equal shares of the cost: pairs, per-particle work, the weighted extra.
  auto cost = [&](std::size_t r) {
    return double(rows[r + 1] - rows[r]) + row_cost.per_row +
           (row_cost.extra ? row_cost.per_extra * row_cost.extra[r] : 0.0);
  };
  double total = 0.0;
  for (std::size_t r = 0; r < n; ++r) total += cost(r);
  first_.assign(t_count + 1, n);
  first_[0] = 0;
  std::size_t i = 0;
  double before = 0.0;  // cost of the rows before row i
  for (int c = 1; c < t_count; ++c) {
    const double target = total * c / t_count;
    while (i < n && before < target) before += cost(i++);
    // On a boundary of kRowAlign rows: the per-particle passes are vector
    // loops over a chunk's rows, and a chunk that starts mid-line loads
    // every vector across two lines (50 % slower: the second chunk's
    // stress pass took 4.9 us a step of the gear against 2.4 us). Only for
    // chunks long enough that the shift of up to half a line costs at most
    // 1.6 % of a chunk.
    const std::size_t aligned = (i + kRowAlign / 2) / kRowAlign * kRowAlign;
    first_[c] = n >= kAlignedChunkRows * t_count ? std::clamp(aligned, first_[c - 1], n) : i;
  }
  cross_.resize(n);
  reach_.assign(t_count, 0);
  spill_at_.assign(t_count + 1, 0);
  for (int c = 0; c < t_count; ++c) {
    const std::size_t stop = first_[c + 1];
    reach_[c] = stop;
    for (std::size_t r = first_[c]; r < stop; ++r) {
      const auto row_end = j.begin() + rows[r + 1];
      const auto at = std::lower_bound(j.begin() + rows[r], row_end, stop);
      cross_[r] = static_cast<std::uint32_t>(at - j.begin());
      if (at != row_end) reach_[c] = std::max<std::size_t>(reach_[c], *(row_end - 1) + 1);
    }
    spill_at_[c + 1] = spill_at_[c] + components * window(c);
  }
  spill_.assign(spill_at_[t_count], 0.0);
}

void RowChunks::add_spills(int c, double* const* dst, int count, int first) {
  const std::size_t lo = begin(c), hi = end(c);
  for (int t = 0; t < c; ++t) {
    const std::size_t w0 = end(t), w1 = reach_[t];
    const std::size_t from = std::max(lo, w0), to = std::min(hi, w1);
    if (from >= to) continue;
    for (int q = 0; q < count; ++q) {
      double* s = spill(t, first + q);
      for (std::size_t i = from; i < to; ++i) {
        dst[q][i] += s[i - w0];
        s[i - w0] = 0.0;
      }
    }
  }
}

void RowChunks::add_spills_grouped(int c, double* dst, int group) {
  const std::size_t lo = begin(c), hi = end(c);
  const std::size_t g = static_cast<std::size_t>(group);
  for (int t = 0; t < c; ++t) {
    const std::size_t w0 = end(t), w1 = reach_[t];
    const std::size_t from = std::max(lo, w0), to = std::min(hi, w1);
    if (from >= to) continue;
    double* s = spill_grouped(t);
    for (std::size_t i = from; i < to; ++i) {
      for (std::size_t q = 0; q < g; ++q) {
        dst[g * i + q] += s[g * (i - w0) + q];
        s[g * (i - w0) + q] = 0.0;
      }
    }
  }
}

}  // namespace gearsph
