#pragma once
// Verlet neighbour lists with a skin, stored as compressed rows: row i holds
// every j within `cutoff = support + skin` of i (both directions are stored,
// so each particle only ever writes to itself: no races, results independent
// of the thread count; reference lists hold each pair once, see build()).
// The list is rebuilt only when some particle has moved more than half the
// skin since the last build (particles move ~1e-8 m per step, so a rebuild
// every few thousand steps).
//
// Per entry W'(r_ij)/r_ij is cached at the current positions, computed once
// per step and used by every pair loop: grad_i W_ij = dw_r (x_i - x_j), so
// one number per pair instead of two (12 bytes an entry with the index).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"

namespace gearsph {

struct Particles;

// Which pairs go into a list.
enum class PairSelection {
  SameBody,   // kernel interactions inside one body
  AnyBody,    // kernel interactions across bodies too (contact model "kernel")
  OtherBody,  // contact candidates: pairs from different bodies only
};

class NeighbourList {
 public:
  // rows[i] .. rows[i+1] index the entries of particle i.
  std::vector<std::uint32_t> rows;
  std::vector<std::uint32_t> j;
  // Cached per entry, refreshed each step by the velocity-gradient loop
  // (current-configuration lists only).
  std::vector<double> dw_r;  // W'(r_ij) / r_ij
  std::vector<double> w;     // W_ij, sized only when a term needs it

  // Builds from the current positions, or from the reference positions when
  // `reference` is set: total-Lagrangian lists, which never change, hold each
  // unordered pair once (row i only j > i) and no W' cache. With `eligible`,
  // particles flagged 0 there get an empty row and appear in no other row
  // (contact candidates: interior particles, which never touch).
  void build(const Particles& p, double cutoff, PairSelection selection, bool reference,
             int threads, const std::uint8_t* eligible = nullptr);
  bool needs_rebuild(const Particles& p) const;
  // needs_rebuild for particles lo .. hi at (x, y), for a pass that has the
  // positions at hand: how many moved beyond half the skin. Only for lists
  // built for the present particles (built_for).
  std::size_t moved_too_far(std::size_t lo, std::size_t hi, const double* x, const double* y) const;
  bool built_for(std::size_t n) const { return builds_ > 0 && x_built_.size() == n; }
  std::size_t entries() const { return j.size(); }
  std::size_t builds() const { return builds_; }
  double cutoff() const { return cutoff_; }
  double skin() const { return skin_; }
  void set_skin(double skin) { skin_ = skin; }

 private:
  CellGrid grid_;
  std::vector<double> x_built_, y_built_;
  std::vector<std::uint32_t> count_;
  double cutoff_ = 0.0;
  double skin_ = 0.0;
  std::size_t builds_ = 0;
};

}  // namespace gearsph
