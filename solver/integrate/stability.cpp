#include "solver/integrate/stability.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "solver/core/passes.hpp"
#include "solver/core/row_chunks.hpp"
#include "solver/core/setup_progress.hpp"
#include "solver/physics/artificial_viscosity.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph {

namespace {

// Power iterations: enough for the largest eigenvalue to within a few
// percent on the scenes we run (it converges from below; see kSafety).
constexpr int kIterations = 80;
// Power iteration underestimates the largest eigenvalue; keep a margin.
constexpr double kSafety = 0.95;
// Chunks of the damping operator's pair loop, run by however many threads.
constexpr int kDampingChunks = 16;
// Entries per partial sum of a norm.
constexpr std::size_t kNormBlock = 4096;

bool integrated(const Simulation& sim, std::size_t i, int component) {
  const Motion& m = sim.motions[sim.particles.motion[i]];
  return component == 0 ? m.integrates_x() : m.integrates_y();
}

// Sum of squares of (ux, uy) in fixed blocks added in order: the same
// bits on any number of threads.
double squared_norm(const std::vector<double>& ux, const std::vector<double>& uy,
                    std::vector<double>& block_sums, int threads) {
  const std::size_t n = ux.size();
  const std::size_t blocks = block_sums.size();
  over_shares<int>("norm", blocks, threads, [&](std::size_t lo, std::size_t hi, int&) {
    for (std::size_t b = lo; b < hi; ++b) {
      double s = 0.0;
      for (std::size_t i = b * kNormBlock; i < std::min(n, (b + 1) * kNormBlock); ++i) {
        s += ux[i] * ux[i] + uy[i] * uy[i];
      }
      block_sums[b] = s;
    }
  });
  double sum = 0.0;
  for (double s : block_sums) sum += s;
  return sum;
}

// Largest eigenvalue of a linear operator on the integrated velocity or
// displacement components, by power iteration from a fixed random start.
// apply(u) leaves A u in the particles' accelerations, which the passes
// write anyway: one vector pair of set-up memory, not two.
template <class Apply>
double largest_eigenvalue(Simulation& sim, Apply&& apply) {
  const std::size_t n = sim.particles.n;
  std::vector<double> ux(n), uy(n);
  // Which components are integrated (not prescribed).
  std::vector<std::uint8_t> free_x(n), free_y(n);
  std::vector<double> block_sums((n + kNormBlock - 1) / kNormBlock);
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    free_x[i] = integrated(sim, i, 0);
    free_y[i] = integrated(sim, i, 1);
    ux[i] = free_x[i] ? uni(rng) : 0.0;
    uy[i] = free_y[i] ? uni(rng) : 0.0;
  }
  const double* ax = sim.particles.ax.data();
  const double* ay = sim.particles.ay.data();
  double lambda = 0.0;
  for (int it = 0; it < kIterations; ++it) {
    setup_progress("finding the stable time step", double(it) / kIterations);
    const double norm_u = std::sqrt(squared_norm(ux, uy, block_sums, sim.threads));
    if (norm_u == 0.0) return 0.0;
    over_shares<int>("normalise", n, sim.threads, [&](std::size_t lo, std::size_t hi, int&) {
      for (std::size_t i = lo; i < hi; ++i) {
        ux[i] /= norm_u;
        uy[i] /= norm_u;
      }
    });
    apply(ux, uy);
    over_shares<int>("free components", n, sim.threads, [&](std::size_t lo, std::size_t hi, int&) {
      for (std::size_t i = lo; i < hi; ++i) {
        ux[i] = free_x[i] ? ax[i] : 0.0;
        uy[i] = free_y[i] ? ay[i] : 0.0;
      }
    });
    lambda = std::sqrt(squared_norm(ux, uy, block_sums, sim.threads));
  }
  return lambda;
}

// What the estimate changes in the scene it runs on, and puts back: the
// method (total-Lagrangian, no viscosity), the positions and accelerations,
// and in an updated-Lagrangian scene the stress, density and deformation
// that the total-Lagrangian passes overwrite, and the reference pairs they
// need. On an exception, the destructor puts back all but the per-step
// state of a total-Lagrangian scene, which its set-up starts afresh anyway.
class Borrowed {
 public:
  explicit Borrowed(Simulation& sim) : sim_(sim), method_(sim.method), j2_(sim.largest_j2) {
    const Particles& p = sim.particles;
    updated_ = sim.method.formulation != Formulation::TotalLagrangian;
    if (!std::equal(p.x.begin(), p.x.end(), p.x0.begin()) ||
        !std::equal(p.y.begin(), p.y.end(), p.y0.begin())) {
      x_ = p.x;  // a scene that starts deformed (none does yet)
      y_ = p.y;
    }
    if (updated_) {
      for (const Column<double>* v : state(sim.particles)) saved_.push_back(*v);
    }
    // The stress pass turns the contact normals, which is the run's business.
    normal_x_.swap(sim.contact_state.normal_x);
  }
  Borrowed(const Borrowed&) = delete;
  Borrowed& operator=(const Borrowed&) = delete;
  ~Borrowed() {
    if (!returned_) put_back();
  }
  // The normal way out: a total-Lagrangian scene keeps its reference pairs
  // (total_lagrangian_setup starts their per-step state afresh), and its
  // stress and density are those of its initial positions.
  void give_back() {
    put_back();
    returned_ = true;
    if (!updated_) {
      physics::total_lagrangian_setup(sim_);
      physics::total_lagrangian_stress(sim_);
      sim_.largest_j2 = j2_;
    }
  }

 private:
  static std::vector<Column<double>*> state(Particles& p) {
    return {&p.p, &p.sxx, &p.syy, &p.szz, &p.sxy, &p.rho, &p.fxx, &p.fxy, &p.fyx, &p.fyy};
  }
  void put_back() noexcept {
    Particles& p = sim_.particles;
    sim_.method = method_;
    std::copy(x_.empty() ? p.x0.begin() : x_.begin(), x_.empty() ? p.x0.end() : x_.end(),
              p.x.begin());
    std::copy(y_.empty() ? p.y0.begin() : y_.begin(), y_.empty() ? p.y0.end() : y_.end(),
              p.y.begin());
    std::fill(p.ax.begin(), p.ax.end(), 0.0);
    std::fill(p.ay.begin(), p.ay.end(), 0.0);
    normal_x_.swap(sim_.contact_state.normal_x);
    if (updated_) {
      const std::vector<Column<double>*> to = state(p);
      for (std::size_t k = 0; k < saved_.size(); ++k) to[k]->swap(saved_[k]);
      sim_.reference = ReferencePairs();
    }
    sim_.largest_j2 = j2_;
  }
  Simulation& sim_;
  const MethodConfig method_;
  const LargestJ2 j2_;
  bool updated_ = false, returned_ = false;
  Column<double> x_, y_, normal_x_;
  std::vector<Column<double>> saved_;
};

// The largest angular frequency of the undamped elastic operator: power
// iteration on K u = -(a(X + eps u) - a(X)) / eps, the total-Lagrangian
// stress and momentum passes at the reference positions (set up by the
// caller, without viscosity).
double elastic_omega_max(Simulation& sim) {
  Particles& p = sim.particles;
  const std::size_t n = p.n;
  physics::total_lagrangian_stress(sim);
  physics::total_lagrangian_momentum(sim, 0.0);
  // The forces of the undeformed scene, subtracted from those of each
  // perturbed one. They vanish to the bit where x = X (u = 0, so F = I and
  // P = 0 exactly), and are then not stored.
  const bool a0_zero = std::all_of(p.ax.begin(), p.ax.end(), [](double a) { return a == 0.0; }) &&
                       std::all_of(p.ay.begin(), p.ay.end(), [](double a) { return a == 0.0; });
  const Column<double> ax0 = a0_zero ? Column<double>() : p.ax;
  const Column<double> ay0 = a0_zero ? Column<double>() : p.ay;
  const double eps = 1e-6 * sim.discretization.dx;
  const double lambda_k =
      largest_eigenvalue(sim, [&](const std::vector<double>& ux, const std::vector<double>& uy) {
        for (std::size_t i = 0; i < n; ++i) {
          p.x[i] = p.x0[i] + eps * ux[i];
          p.y[i] = p.y0[i] + eps * uy[i];
        }
        physics::total_lagrangian_stress(sim);
        physics::total_lagrangian_momentum(sim, 0.0);
        for (std::size_t i = 0; i < n; ++i) {
          p.ax[i] = -(p.ax[i] - (a0_zero ? 0.0 : ax0[i])) / eps;
          p.ay[i] = -(p.ay[i] - (a0_zero ? 0.0 : ay0[i])) / eps;
        }
      });
  return std::sqrt(std::max(lambda_k, 0.0));
}

// The largest rate of the artificial viscosity's linear part, every pair
// taken as approaching (Monaghan 1992, eq. 4.1, the alpha term):
//   a_i = sum_j m_j alpha c_ij h (v_ij . x_ij) / ((r^2 + eta^2) rho_ij) grad_i W_ij.
double viscous_damping_rate(Simulation& sim, const ArtificialViscosity& av) {
  Particles& p = sim.particles;
  const double h = sim.h(), eta2 = std::pow(av.eta_over_h * h, 2);
  const ReferencePairs& rp = sim.reference;
  // Each pair once, to both ends, in a fixed number of chunks whatever the
  // threads (RowChunks): the estimate, and so the step, does not depend on
  // the thread count. Serial, this loop took 7.5 s of a 1e6-particle
  // plate's set-up.
  RowChunks chunks;
  chunks.plan(rp.rows, rp.j, kDampingChunks, 2);
  // Pairs of rows lo .. hi of one chunk, into ax, ay and the chunk's spill.
  auto chunk_pairs = [&](int chunk, const std::vector<double>& vx, const std::vector<double>& vy) {
    double* const ax = p.ax.data();
    double* const ay = p.ay.data();
    const std::size_t lo = chunks.begin(chunk), hi = chunks.end(chunk);
    std::fill(ax + lo, ax + hi, 0.0);
    std::fill(ay + lo, ay + hi, 0.0);
    double* const spill[2] = {chunks.spill(chunk, 0), chunks.spill(chunk, 1)};
    for (std::size_t i = lo; i < hi; ++i) {
      for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
        const std::uint32_t j = rp.j[k];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r2 = dx * dx + dy * dy, r = std::sqrt(r2);
        const double vr = (vx[i] - vx[j]) * dx + (vy[i] - vy[j]) * dy;
        // Graded particles: the pair's h_ij (total_lagrangian.hpp).
        const double hij = rp.hp.empty() ? h : 0.5 * (rp.hp[i] + rp.hp[j]);
        const double e2 = rp.hp.empty() ? eta2 : std::pow(av.eta_over_h * hij, 2);
        const double coef = physics::monaghan_linear(av.alpha, 0.5 * (p.cs[i] + p.cs[j]), hij,
                                                     r2 + e2, 0.5 * (p.rho0[i] + p.rho0[j]));
        const double g = rp.dw0[k] / r;  // grad_i W_ij = g (dx, dy)
        const double sx = coef * vr * g * dx, sy = coef * vr * g * dy;
        ax[i] -= p.mass[j] * sx;  // a = -D v with D positive semi-definite
        ay[i] -= p.mass[j] * sy;
        if (k < chunks.cross(i)) {
          ax[j] += p.mass[i] * sx;
          ay[j] += p.mass[i] * sy;
        } else {
          spill[0][j - hi] += p.mass[i] * sx;
          spill[1][j - hi] += p.mass[i] * sy;
        }
      }
    }
  };
  return largest_eigenvalue(sim, [&](const std::vector<double>& vx, const std::vector<double>& vy) {
    auto pairs = [&](int c, int, int&) { chunk_pairs(c, vx, vy); };
    auto spills = [&](int c, int, int&) {
      double* const sums[2] = {p.ax.data(), p.ay.data()};
      chunks.add_spills(c, sums, 2);
    };
    const Pass<int> passes[] = {
        {"damping pairs", Runs::OverChunks, &chunks, pairs, Sync::Barrier, true},
        {"damping spills", Runs::OverChunks, &chunks, spills, Sync::Barrier, true},
    };
    constexpr std::size_t kNeverStop = 0;
    run_passes<int>(passes, sim.threads, kNeverStop);
  });
}

// The stable step of leapfrog for the oscillator u'' + g u' + w^2 u = 0,
// 2 (sqrt(w^2 + g^2/4) - g/2) / w^2, shortened by the Courant condition's
// |v| (moving particles carry signals faster) and kept below by kSafety.
double stable_step(const Simulation& sim, double w, double g) {
  const Particles& p = sim.particles;
  double dt = w > 0 ? 2.0 * (std::sqrt(w * w + 0.25 * g * g) - 0.5 * g) / (w * w) : 1e300;
  double c_max = 0.0, cv_max = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    c_max = std::max(c_max, p.cs[i]);
    cv_max = std::max(cv_max, p.cs[i] + std::hypot(p.vx[i], p.vy[i]));
  }
  if (cv_max > 0) dt *= c_max / cv_max;
  return kSafety * dt;
}

}  // namespace

StabilityLimit estimate_stability_limit(Simulation& sim) {
  // On the scene itself, not a copy (the copy was the set-up's peak of
  // memory: docs/speed-accuracy-history.md), in the total-Lagrangian form: at the
  // initial configuration its linearisation is the updated-Lagrangian one
  // too. In a total-Lagrangian scene the reference pairs built here are the
  // run's own.
  Borrowed borrowed(sim);
  const bool updated = sim.method.formulation != Formulation::TotalLagrangian;
  const ArtificialViscosity av = sim.method.viscosity;
  sim.method.formulation = Formulation::TotalLagrangian;
  sim.method.viscosity.alpha = sim.method.viscosity.beta = 0.0;
  if (updated) sim.method.hourglass.coefficient = 0.0;  // a damping in UL, not a stiffness
  sim.particles.x = sim.particles.x0;
  sim.particles.y = sim.particles.y0;
  physics::total_lagrangian_setup(sim);

  StabilityLimit out;
  out.omega_max = elastic_omega_max(sim);
  if (av.alpha > 0.0) out.damping_rate = viscous_damping_rate(sim, av);
  out.iterations = kIterations;
  out.dt_limit = stable_step(sim, out.omega_max, out.damping_rate);
  borrowed.give_back();
  return out;
}

}  // namespace gearsph
