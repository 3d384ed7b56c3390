#include "solver/neighbours/neighbour_list.hpp"

#include <algorithm>

#include "solver/core/particles.hpp"
#include "solver/core/passes.hpp"

namespace gearsph {

namespace {

bool selected(PairSelection s, int body_i, int body_j) {
  switch (s) {
    case PairSelection::SameBody:
      return body_i == body_j;
    case PairSelection::AnyBody:
      return true;
    case PairSelection::OtherBody:
      break;
  }
  return body_i != body_j;
}

}  // namespace

void NeighbourList::build(const Particles& p, double cutoff, PairSelection selection,
                          bool reference, int threads, const std::uint8_t* eligible) {
  const std::size_t n = p.n;
  const double* px = reference ? p.x0.data() : p.x.data();
  const double* py = reference ? p.y0.data() : p.y.data();
  cutoff_ = cutoff;
  grid_.build(px, py, n, cutoff);
  const double c2 = cutoff * cutoff;

  auto scan = [&](std::size_t i, auto&& emit) {
    if (eligible && !eligible[i]) return;
    const double xi = px[i], yi = py[i];
    const int bi = p.body[i];
    grid_.for_each_near(xi, yi, [&](std::uint32_t k) {
      if (k == i || (reference && k < i) || !selected(selection, bi, p.body[k])) return;
      if (eligible && !eligible[k]) return;
      const double dx = xi - px[k], dy = yi - py[k];
      if (dx * dx + dy * dy < c2) emit(k);
    });
  };

  count_.assign(n, 0);
  over_shares<int>("neighbour counts", n, threads, [&](std::size_t lo, std::size_t hi, int&) {
    for (std::size_t i = lo; i < hi; ++i) {
      std::uint32_t c = 0;
      scan(i, [&](std::uint32_t) { ++c; });
      count_[i] = c;
    }
  });
  rows.resize(n + 1);
  rows[0] = 0;
  for (std::size_t i = 0; i < n; ++i) rows[i + 1] = rows[i] + count_[i];
  j.resize(rows[n]);
  over_shares<int>("neighbour rows", n, threads, [&](std::size_t lo, std::size_t hi, int&) {
    for (std::size_t i = lo; i < hi; ++i) {
      std::uint32_t at = rows[i];
      scan(i, [&](std::uint32_t k) { j[at++] = k; });
      // Sorted rows: deterministic order and forward memory access.
      std::sort(j.begin() + rows[i], j.begin() + rows[i + 1]);
    }
  });
  dw_r.assign(reference ? 0 : j.size(), 0.0);
  if (!w.empty()) w.assign(j.size(), 0.0);
  x_built_.assign(p.x.begin(), p.x.end());
  y_built_.assign(p.y.begin(), p.y.end());
  ++builds_;
}

std::size_t NeighbourList::moved_too_far(std::size_t lo, std::size_t hi, const double* x,
                                         const double* y) const {
  const double *xb = x_built_.data(), *yb = y_built_.data();
  const double limit = 0.25 * skin_ * skin_;
  std::size_t moved = 0;
#pragma omp simd reduction(+ : moved)
  for (std::size_t i = lo; i < hi; ++i) {
    const double dx = x[i] - xb[i], dy = y[i] - yb[i];
    moved += dx * dx + dy * dy > limit ? 1 : 0;
  }
  return moved;
}

bool NeighbourList::needs_rebuild(const Particles& p) const {
  if (x_built_.size() != p.n) return true;
  return moved_too_far(0, p.n, p.x.data(), p.y.data()) > 0;
}

}  // namespace gearsph
