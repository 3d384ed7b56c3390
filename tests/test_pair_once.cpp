// The total-Lagrangian pair list stores each unordered pair once and its
// loops write to both ends (RowChunks): the same forces as full rows, for
// any number of threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <set>
#include <vector>

#include "solver/core/row_chunks.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/neighbours/neighbour_list.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "tests/support/steel_block.hpp"

namespace gearsph {
namespace {

// A deformed, moving block: random displacements of 2 % of the spacing and
// random velocities, so that F, P, viscosity and hourglass are all non-zero.
Simulation deformed_block(int n, int threads, double hourglass) {
  Simulation sim = testing_support::steel_block(n, Formulation::TotalLagrangian,
                                                GradientCorrection::Quadratic, 1.2, threads);
  sim.method.hourglass.coefficient = hourglass;
  const double dx = sim.discretization.dx;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    p.x[i] += 0.02 * dx * uni(rng);
    p.y[i] += 0.02 * dx * uni(rng);
    p.vx[i] = uni(rng);
    p.vy[i] = uni(rng);
  }
  return sim;
}

void forces(Simulation& sim) {
  physics::total_lagrangian_setup(sim);
  physics::total_lagrangian_stress(sim);
  physics::total_lagrangian_momentum(sim, 1e-9);
}

double max_abs(const Column<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

TEST(PairOnce, EachUnorderedPairIsStoredOnceInSortedRows) {
  Simulation sim = deformed_block(20, 1, 0.0);
  physics::total_lagrangian_setup(sim);
  const ReferencePairs& rp = sim.reference;
  for (std::size_t i = 0; i < sim.particles.n; ++i) {
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      ASSERT_GT(rp.j[k], i);
      if (k > rp.rows[i]) {
        ASSERT_GT(rp.j[k], rp.j[k - 1]);
      }
    }
  }
  // A full list at the reference positions holds every pair twice.
  Particles at_rest = sim.particles;
  at_rest.x = at_rest.x0;
  at_rest.y = at_rest.y0;
  NeighbourList full;
  full.build(at_rest, 3.0 * sim.h(), PairSelection::SameBody, /*reference=*/false, 1);
  EXPECT_EQ(rp.entries(), full.entries());
  EXPECT_GT(rp.pairs(), 10u * sim.particles.n);
}

TEST(PairOnce, ForcesEqualFullRowSums) {
  // Written out over full rows, with G_ji taken from the pair's other end:
  //   F_i = I + sum_j V0_j (u_j - u_i) (x) G_ij
  //   a_i = 1/rho0_i sum_j V0_j (P_i G_ij - P_j G_ji)   (no viscosity here)
  Simulation sim = deformed_block(24, 3, 0.0);
  sim.method.viscosity.alpha = sim.method.viscosity.beta = 0.0;
  forces(sim);
  const Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  const std::size_t n = p.n;
  struct Entry {
    std::uint32_t j;
    double gx, gy;  // G_ij seen from i
  };
  std::vector<std::vector<Entry>> rows(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      rows[i].push_back({rp.j[k], rp.g[4 * k], rp.g[4 * k + 1]});
      rows[rp.j[k]].push_back({static_cast<std::uint32_t>(i), rp.g[4 * k + 2], rp.g[4 * k + 3]});
    }
  }
  auto g_of = [&](std::size_t a, std::size_t b, double& gx, double& gy) {
    for (const Entry& e : rows[a]) {
      if (e.j == b) {
        gx = e.gx;
        gy = e.gy;
        return;
      }
    }
    FAIL() << "missing pair";
  };
  double worst_f = 0.0, worst_a = 0.0;
  const double a_scale = std::max(max_abs(p.ax), max_abs(p.ay));
  for (std::size_t i = 0; i < n; ++i) {
    double f[4] = {1, 0, 0, 1}, a[2] = {0, 0};
    for (const Entry& e : rows[i]) {
      const double vj = rp.vol0[e.j];
      const double dux = (p.x[e.j] - p.x0[e.j]) - (p.x[i] - p.x0[i]);
      const double duy = (p.y[e.j] - p.y0[e.j]) - (p.y[i] - p.y0[i]);
      f[0] += vj * dux * e.gx;
      f[1] += vj * dux * e.gy;
      f[2] += vj * duy * e.gx;
      f[3] += vj * duy * e.gy;
      double gjx = 0, gjy = 0;
      g_of(e.j, i, gjx, gjy);
      // The step keeps V0 P (ReferencePairs::pv: xx, xy, yx, yy).
      const double vi = rp.vol0[i];
      const double* pi = &rp.pv[4 * i];
      const double* pj = &rp.pv[4 * e.j];
      a[0] += vj * ((pi[0] * e.gx + pi[1] * e.gy) / vi - (pj[0] * gjx + pj[1] * gjy) / vj);
      a[1] += vj * ((pi[2] * e.gx + pi[3] * e.gy) / vi - (pj[2] * gjx + pj[3] * gjy) / vj);
    }
    worst_f = std::max({worst_f, std::abs(f[0] - p.fxx[i]), std::abs(f[1] - p.fxy[i]),
                        std::abs(f[2] - p.fyx[i]), std::abs(f[3] - p.fyy[i])});
    worst_a = std::max(
        {worst_a, std::abs(a[0] / p.rho0[i] - p.ax[i]), std::abs(a[1] / p.rho0[i] - p.ay[i])});
  }
  EXPECT_LT(worst_f, 1e-14);  // F - I ~ 2e-2: round-off
  EXPECT_LT(worst_a, 1e-12 * a_scale) << "largest |a| " << a_scale;
  EXPECT_GT(a_scale, 1e3);  // the block is deformed: the check is not trivial
}

TEST(PairOnce, AnyThreadCountGivesTheSameForcesToRoundOff) {
  // Viscosity and hourglass control on: every sum a pair writes to both ends.
  Simulation one = deformed_block(30, 1, 0.5);
  forces(one);
  const double a_scale = std::max(max_abs(one.particles.ax), max_abs(one.particles.ay));
  for (int threads : {2, 3, 4, 7}) {
    Simulation many = deformed_block(30, threads, 0.5);
    forces(many);
    double da = 0.0, df = 0.0;
    for (std::size_t i = 0; i < one.particles.n; ++i) {
      da = std::max({da, std::abs(one.particles.ax[i] - many.particles.ax[i]),
                     std::abs(one.particles.ay[i] - many.particles.ay[i])});
      df = std::max({df, std::abs(one.particles.fxx[i] - many.particles.fxx[i]),
                     std::abs(one.particles.fxy[i] - many.particles.fxy[i])});
    }
    EXPECT_LT(da, 1e-12 * a_scale) << threads << " threads";
    EXPECT_LT(df, 1e-15) << threads << " threads";
    EXPECT_NEAR(many.energy.dissipated, one.energy.dissipated,
                1e-12 * std::abs(one.energy.dissipated));
  }
  EXPECT_GT(one.energy.dissipated, 0.0);
}

// Every array a thread writes by rows starts on a cache line and owns whole
// lines (cache_aligned.hpp): no other array, and no small object written by
// another thread, shares its first or last line.
TEST(PairOnce, ArraysWrittenByRowsOwnWholeCacheLines) {
  Simulation sim = deformed_block(21, 2, 0.5);  // 441 doubles: 55 lines and one more

  forces(sim);
  const Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  const Column<double>* arrays[] = {&p.x,   &p.y,      &p.vx,      &p.vy,     &p.ax,     &p.ay,
                                    &p.rho, &p.p,      &p.sxx,     &p.syy,    &p.sxy,    &p.szz,
                                    &p.fxx, &p.fxy,    &p.fyx,     &p.fyy,    &p.ext_ax, &p.ext_ay,
                                    &rp.pv, &rp.state, &rp.u,      &rp.sums,  &rp.hg_ax, &rp.hg_ay,
                                    &rp.g,  &rp.dw0,   &rp.visc_a, &rp.visc_b};
  std::vector<std::pair<std::uintptr_t, std::uintptr_t>> lines;
  for (const Column<double>* a : arrays) {
    ASSERT_FALSE(a->empty());
    const auto first = reinterpret_cast<std::uintptr_t>(a->data());
    EXPECT_EQ(first % kCacheLine, 0u);
    lines.emplace_back(first / kCacheLine, (first + a->size() * sizeof(double) - 1) / kCacheLine);
  }
  std::sort(lines.begin(), lines.end());
  for (std::size_t k = 1; k < lines.size(); ++k) {
    EXPECT_GT(lines[k].first, lines[k - 1].second) << "two arrays share a cache line";
  }
  EXPECT_EQ(CacheAligned<double>::bytes(1), kCacheLine);
  EXPECT_EQ(CacheAligned<double>::bytes(8), kCacheLine);
  EXPECT_EQ(CacheAligned<double>::bytes(9), 2 * kCacheLine);
  // Each chunk's largest J2 is written by its own thread every step.
  ASSERT_EQ(rp.chunk_peaks.size(), 2u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(&rp.chunk_peaks[1]) -
                reinterpret_cast<std::uintptr_t>(&rp.chunk_peaks[0]),
            kCacheLine);
}

// Arrays mapped on their own (page-aligned) are shifted by a different
// number of cache lines each (cache_aligned.hpp): 64 successive arrays take
// 64 different L1 sets, and the shift stays within 1/16 of the array and
// 64 KiB.
TEST(PairOnce, LargeArraysStartInDifferentCacheSets) {
  for (std::size_t bytes : {kStaggerFrom, std::size_t{1} << 24}) {
    std::set<std::size_t> sets;
    for (int k = 0; k < 64; ++k) {
      const std::size_t shift = stagger(bytes);
      EXPECT_EQ(shift % kCacheLine, 0u);
      EXPECT_GT(shift, 0u);
      EXPECT_LE(shift, std::min<std::size_t>(bytes / 16, std::size_t{64} << 10));
      sets.insert(shift % 4096 / kCacheLine);
    }
    EXPECT_EQ(sets.size(), 64u) << bytes << " bytes";
  }
  // The shifted arrays are whole and apart: each keeps its values.
  std::vector<Column<double>> arrays;
  for (int k = 0; k < 16; ++k) {
    arrays.emplace_back(kStaggerFrom / sizeof(double) + k, double(k));
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(arrays.back().data()) % kCacheLine, 0u);
  }
  for (int k = 0; k < 16; ++k) {
    EXPECT_TRUE(std::all_of(arrays[k].begin(), arrays[k].end(), [&](double v) { return v == k; }));
  }
}

// Chunks are cut at equal cost: pairs plus one per row, plus the weighted
// extra. Eight rows of three pairs each (cost 4 a row, 32 in all): the cut
// falls after row 3. With an extra of 4 on the last four rows at weight 0.5
// (costs 4, 4, 4, 4, 6, 6, 6, 6; 40 in all) the first chunk takes rows until
// it holds at least half: 4 + 4 + 4 + 4 + 6 = 22, so through row 4.
TEST(PairOnce, ChunksAreCutAtEqualCost) {
  std::vector<std::uint32_t> rows = {0}, j;
  const std::uint32_t n = 8;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t k = 1; k <= 3; ++k) j.push_back(i + k);
    rows.push_back(static_cast<std::uint32_t>(j.size()));
  }
  RowChunks chunks;
  chunks.plan(rows, j, 2, 1);
  EXPECT_EQ(chunks.end(0), 4u);
  const std::vector<std::uint32_t> extra = {0, 0, 0, 0, 4, 4, 4, 4};
  chunks.plan(rows, j, 2, 1, {1.0, extra.data(), 0.5});
  EXPECT_EQ(chunks.end(0), 5u);
  chunks.plan(rows, j, 2, 1, {1.0, extra.data(), 0.0});
  EXPECT_EQ(chunks.end(0), 4u);
  // Rows 0-3 with 3 pairs, rows 4-7 with 1: per-row work moves the cut.
  std::vector<std::uint32_t> uneven_rows = {0}, uneven_j;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t k = 1; k <= (i < 4 ? 3u : 1u); ++k) uneven_j.push_back(i + k);
    uneven_rows.push_back(static_cast<std::uint32_t>(uneven_j.size()));
  }
  chunks.plan(uneven_rows, uneven_j, 2, 1, {1.0});  // rows cost 4 4 4 4 2 2 2 2
  EXPECT_EQ(chunks.end(0), 3u);
  chunks.plan(uneven_rows, uneven_j, 2, 1, {5.0});  // 8 8 8 8 6 6 6 6
  EXPECT_EQ(chunks.end(0), 4u);
  // Chunks of kAlignedChunkRows rows or more start on a cache line: 1,000
  // rows of equal cost on 3 threads are cut at 336 and 664, not 333 and 666.
  std::vector<std::uint32_t> long_rows = {0}, long_j;
  for (std::uint32_t i = 0; i < 1000; ++i) {
    for (std::uint32_t k = i + 1; k <= std::min(i + 3, 999u); ++k) long_j.push_back(k);
    long_rows.push_back(static_cast<std::uint32_t>(long_j.size()));
  }
  chunks.plan(long_rows, long_j, 3, 1, {3.0});
  EXPECT_EQ(chunks.end(0), 336u);
  EXPECT_EQ(chunks.end(1), 664u);
  EXPECT_EQ(chunks.end(2), 1000u);
}

// A pass may keep four sums of a row side by side (4 i + q) and spill them
// as one group: each row gets the sums, in the same order, that four
// separate arrays get. Rows 0-11 of a strip, each with neighbours i+1 ..
// i+4, cut for 3 threads, so that every window is used.
TEST(PairOnce, GroupedSpillsEqualSeparateOnes) {
  std::vector<std::uint32_t> rows = {0}, j;
  const std::uint32_t n = 12;
  for (std::uint32_t i = 0; i < n; ++i) {
    for (std::uint32_t k = i + 1; k <= std::min(i + 4, n - 1); ++k) j.push_back(k);
    rows.push_back(static_cast<std::uint32_t>(j.size()));
  }
  RowChunks apart, grouped;
  apart.plan(rows, j, 3, 4);
  grouped.plan(rows, j, 3, 4);
  ASSERT_LT(apart.cross(apart.end(0) - 1), rows[apart.end(0)]);  // chunk 0 spills
  std::vector<double> sums[4], together(4 * n, 0.0);
  for (auto& s : sums) s.assign(n, 0.0);
  double* to[4] = {sums[0].data(), sums[1].data(), sums[2].data(), sums[3].data()};
  // Pair (i, j) adds 1 / (1 + i + 10 j + 100 q) to j's sum q: a sum whose
  // order of terms shows in its last bits.
  auto value = [](std::size_t i, std::size_t k, int q) {
    return 1.0 / (1.0 + i + 10.0 * k + 100.0 * q);
  };
  for (int c = 0; c < 3; ++c) {
    const std::size_t hi = apart.end(c);
    for (std::size_t i = apart.begin(c); i < hi; ++i) {
      for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
        const bool cross = k >= apart.cross(i);
        for (int q = 0; q < 4; ++q) {
          const double v = value(i, j[k], q);
          (cross ? apart.spill(c, q)[j[k] - hi] : to[q][j[k]]) += v;
          (cross ? grouped.spill_grouped(c)[4 * (j[k] - hi) + q] : together[4 * j[k] + q]) += v;
        }
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    apart.add_spills(c, to, 4);
    grouped.add_spills_grouped(c, together.data(), 4);
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (int q = 0; q < 4; ++q) {
      EXPECT_EQ(together[4 * i + q], sums[q][i]) << "row " << i << ", sum " << q;
    }
  }
  // The first row of a later chunk received spilled sums.
  EXPECT_GT(sums[0][apart.begin(1)], 0.0);
}

// A scene of one material and one spacing (the seed paper's gear) takes the
// pairs' masses and sound speeds as constants; the step must give
// the same bits as with them gathered per pair. A scene of two materials
// (the Hertz cylinder on its block) keeps the gathers.
TEST(PairOnce, UniformScenesTakeConstantsAndGiveTheSameBits) {
  auto gear = [](bool constants) {
    // The seed paper's lattice: one mass and one sound speed for every particle.
    PreparedJob prepared = prepare_job(
        {{"scene", {{"type", "rack_pinion"}}}, {"discretization", {{"particles", "lattice"}}}}, 2);
    Simulation sim = prepared.scene.sim;
    integrate::initialise(sim);
    EXPECT_TRUE(sim.reference.uniform.all);
    sim.reference.uniform.all = constants;
    for (int s = 0; s < 600; ++s) integrate::step(sim);
    return sim;
  };
  const Simulation a = gear(true), b = gear(false);
  double moved = 0.0;
  for (std::size_t i = 0; i < a.particles.n; ++i) {
    ASSERT_EQ(a.particles.x[i], b.particles.x[i]) << i;
    ASSERT_EQ(a.particles.vx[i], b.particles.vx[i]) << i;
    ASSERT_EQ(a.particles.sxx[i], b.particles.sxx[i]) << i;
    ASSERT_EQ(a.particles.ax[i], b.particles.ax[i]) << i;
    moved = std::max(moved, std::abs(a.particles.vx[i]));
  }
  EXPECT_GT(moved, 0.0);
  EXPECT_GT(a.energy.dissipated, 0.0) << "the viscosity never acted";

  PreparedJob hertz = prepare_job({{"scene", {{"type", "hertz"}}}}, 1);
  Simulation two = hertz.scene.sim;
  integrate::initialise(two);
  EXPECT_FALSE(two.reference.uniform.all);
}

}  // namespace
}  // namespace gearsph
