#pragma once
// Threads for loops over a pair list that stores each unordered pair once
// (row i holds only neighbours j > i) and writes every pair's result to both
// ends.
//
// The rows are cut into contiguous chunks, one per thread, of about equal
// cost (pairs, optionally weighted per row: plan). A pair whose j lies in
// its row's own chunk writes to j directly: only the chunk's thread touches
// those rows. The other pairs ("cross" pairs, the tail of each sorted row)
// write to the chunk's spill window, a buffer for rows past the chunk's end
// that its pairs reach; after a barrier each thread adds the windows that
// land on its rows (add_spills). Particles are spatially ordered, so the
// windows are short: the pairs that straddle a chunk boundary. One thread
// spills nothing.
//
// No locks, no atomics, and with one thread every sum is formed in the same
// order as a loop over full rows would form it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/core/cache_aligned.hpp"

namespace gearsph {

// What a row costs, in units of one pair of the pass: its pairs, plus
// `per_row` for the per-particle work of the passes the cut also serves,
// plus `per_extra` times extra[row] when `extra` is given (per-row work that
// varies, such as the pairs whose viscosity acts).
struct RowCost {
  double per_row = 1.0;
  const std::uint32_t* extra = nullptr;
  double per_extra = 0.0;
};

// Chunks start on a multiple of this many rows (a cache line of doubles)
// when each holds at least kAlignedChunkRows rows.
inline constexpr std::size_t kRowAlign = kCacheLine / sizeof(double);
inline constexpr std::size_t kAlignedChunkRows = 256;

class RowChunks {
 public:
  // Cuts rows[0..n] into `threads` chunks of about equal cost (starting on
  // a multiple of kRowAlign rows if long enough), and sizes the
  // spill windows for `components` values per row (the most any loop writes
  // per pair end).
  void plan(const std::vector<std::uint32_t>& rows, const std::vector<std::uint32_t>& j,
            int threads, int components, RowCost cost = {});
  int chunks() const { return static_cast<int>(first_.size()) - 1; }
  bool planned_for(int threads, int components) const {
    return chunks() == threads && components_ == components;
  }
  // Chunk c owns rows begin(c) .. end(c).
  std::size_t begin(int c) const { return first_[c]; }
  std::size_t end(int c) const { return first_[c + 1]; }
  // Entries cross(i) .. rows[i+1] of row i have j >= end(chunk of i).
  std::uint32_t cross(std::size_t i) const { return cross_[i]; }
  // Component q of chunk c's window: index it with j - end(c).
  double* spill(int c, int q) { return spill_.data() + spill_at_[c] + q * window(c); }
  // Components 0 .. group-1 of chunk c's window kept together, as a loop
  // that writes them as one vector wants them: value q for row j at
  // group * (j - end(c)) + q. The same memory as spill(c, 0 .. group-1).
  double* spill_grouped(int c) { return spill_.data() + spill_at_[c]; }
  // Adds to dst[q][i] every value of components first .. first+count-1
  // that lands on a row of chunk c and zeroes it; call after a barrier that
  // follows the pair loop.
  void add_spills(int c, double* const* dst, int count, int first = 0);
  // The same for components 0 .. group-1 of spill_grouped, into
  // dst[group * i + q].
  void add_spills_grouped(int c, double* dst, int group);

 private:
  std::size_t window(int c) const { return reach_[c] - first_[c + 1]; }
  std::vector<std::size_t> first_;     // chunk boundaries, chunks + 1 rows
  std::vector<std::uint32_t> cross_;   // per row
  std::vector<std::size_t> reach_;     // per chunk: one past the highest j it spills to
  std::vector<std::size_t> spill_at_;  // per chunk: offset of its window
  Column<double> spill_;               // written by one thread, added by another
  int components_ = 0;
};

}  // namespace gearsph
