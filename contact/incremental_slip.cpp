#include "contact/incremental_slip.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "contact/contact_zones.hpp"
#include "contact/error.hpp"

namespace fretwear {

std::string IncrementalSlipOptions::validate() const {
  if (increments_per_cycle < 4 || increments_per_cycle % 4 != 0)
    return fmt::format("increments_per_cycle = {} must be a positive multiple of 4", increments_per_cycle);
  if (cycles < 1) return fmt::format("cycles = {} must be at least 1", cycles);
  if (!(tolerance > 0.0 && tolerance <= 1e-2))
    return fmt::format("tolerance = {} is outside (0, 1e-2]", tolerance);
  if (max_iterations < 1) return fmt::format("max_iterations = {} must be at least 1", max_iterations);
  return {};
}

IncrementalSlipSolver::IncrementalSlipSolver(const HalfPlaneKernel& kernel, IncrementalSlipOptions options)
    : kernel_(kernel), options_(options) {
  if (auto msg = options_.validate(); !msg.empty()) throw InputError("incremental slip options: " + msg);
  if (options_.preconditioner == NormalSolverOptions::Preconditioner::symbol) {
    // As NormalSolver: spectrum() is C's half spectrum over m = 2n; apply_spectrum wants C⁻¹'s over m.
    const auto spec = kernel_.fft().spectrum();
    const double m = 2.0 * kernel_.grid().n;
    inverse_spectrum_.resize(spec.size());
    for (std::size_t k = 0; k < spec.size(); ++k) {
      const double lambda = spec[k].real() * m;
      if (!(lambda > 0.0)) {  // C not positive definite: solve without the preconditioner
        inverse_spectrum_.clear();
        break;
      }
      inverse_spectrum_[k] = 1.0 / (lambda * m);
    }
  }
}

namespace {

// The Euclidean projection of y onto {lo ≤ q ≤ hi, Σ q = target} over the cells in `mask`: q = clamp(y + μ) with
// the μ that meets the sum (Σ clamp(y + μ) is piecewise linear and non-decreasing in μ: safeguarded Newton, which
// ends in a few steps once the clamped set settles). Returns whether any q differs from y.
bool project(std::span<const double> y, std::span<const double> lo, std::span<const double> hi,
             std::span<const char> mask, double target, std::span<double> q) {
  const int n = int(y.size());
  double mu_lo = std::numeric_limits<double>::infinity(), mu_hi = -mu_lo, scale = std::abs(target);
  for (int i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    mu_lo = std::min(mu_lo, lo[i] - y[i]);
    mu_hi = std::max(mu_hi, hi[i] - y[i]);
    scale += hi[i] - lo[i];
  }
  if (!(mu_lo <= mu_hi)) return false;  // an empty mask
  double mu = std::clamp(0.0, mu_lo, mu_hi);
  for (int it = 0; it < 200; ++it) {
    double sum = 0.0;
    int n_free = 0;
    for (int i = 0; i < n; ++i) {
      if (!mask[i]) continue;
      const double v = y[i] + mu;
      if (v <= lo[i]) {
        sum += lo[i];
      } else if (v >= hi[i]) {
        sum += hi[i];
      } else {
        sum += v;
        ++n_free;
      }
    }
    const double excess = sum - target;
    if (std::abs(excess) <= 4.0 * std::numeric_limits<double>::epsilon() * scale) break;
    (excess > 0.0 ? mu_hi : mu_lo) = mu;
    double next = n_free > 0 ? mu - excess / n_free : 0.5 * (mu_lo + mu_hi);
    if (!(next > mu_lo && next < mu_hi)) next = 0.5 * (mu_lo + mu_hi);
    if (next == mu) break;
    mu = next;
  }
  bool changed = false;
  for (int i = 0; i < n; ++i) {
    if (!mask[i]) continue;
    q[i] = std::clamp(y[i] + mu, lo[i], hi[i]);
    changed = changed || q[i] != y[i];
  }
  return changed;
}

}  // namespace

SolveSummary IncrementalSlipSolver::solve_increment(std::span<const double> p, double f, const SlipIncrement& inc,
                                                    IncrementState& state) const {
  const int n = kernel_.grid().n;
  std::vector<double> lo(n), hi(n);
  for (int i = 0; i < n; ++i) {
    hi[i] = p[i] > 0.0 ? f * p[i] : 0.0;
    lo[i] = -hi[i];
  }
  if (int(state.q.size()) != n || int(state.u.size()) != n) {
    state.q.assign(n, 0.0);
    state.u.assign(n, 0.0);
  }
  const std::vector<double> u_prev = state.u;
  if (inverse_spectrum_.empty()) return iterate(lo, hi, inc, u_prev, state, false);
  const SolveSummary first = iterate(lo, hi, inc, u_prev, state, true);
  if (first.converged() || first.termination == Termination::no_admissible_cell) return first;
  // As in NormalSolver: plain constrained CG, warm-started from where the preconditioned run stalled.
  SolveSummary second = iterate(lo, hi, inc, u_prev, state, false);
  second.iterations += first.iterations;
  second.seconds += first.seconds;
  return second;
}

SolveSummary IncrementalSlipSolver::iterate(std::span<const double> lo, std::span<const double> hi,
                                            const SlipIncrement& inc, std::span<const double> u_prev,
                                            IncrementState& state, bool use_preconditioner) const {
  const auto t_start = std::chrono::steady_clock::now();
  const Grid& grid = kernel_.grid();
  const int n = grid.n;
  const double h = grid.h();
  SolveSummary summary;
  auto finish = [&](Termination t) {
    summary.termination = t;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return summary;
  };

  std::vector<char> contact(n), work(n, 0), work_old(n, 0);
  int first = n, last = -1;
  double capacity = 0.0;
  for (int i = 0; i < n; ++i) {
    contact[i] = hi[i] > 0.0;
    if (contact[i]) first = std::min(first, i), last = i, capacity += h * hi[i];
  }
  state.dw.assign(n, 0.0);
  if (last < 0) return finish(Termination::no_admissible_cell);
  if (std::abs(inc.Q) > capacity) return finish(Termination::no_admissible_cell);  // beyond f P: no feasible q

  const double d_eps = inc.bulk_strain - inc.bulk_strain_prev;
  const double half_span = 0.5 * (grid.x(last) - grid.x(first) + h);
  double d = kernel_.A() * std::abs(inc.Q - inc.Q_prev) + std::abs(d_eps) * half_span;
  if (!(d > 0.0)) d = kernel_.A() * capacity;  // nothing changes: measure against the contact's own scale
  const double target = inc.Q / h;

  auto& q = state.q;
  auto& u = state.u;
  // A feasible start: the previous traction shifted uniformly (and clamped) to the new load.
  {
    const std::vector<double> y = q;
    if (project(y, lo, hi, contact, target, q)) kernel_.apply(q, u);
  }
  bool u_exact = true;

  const bool preconditioned = use_preconditioner && !inverse_spectrum_.empty();
  constexpr int kStallIterations = 200;  // a preconditioned run that has not halved its residual for this long
  double best_residual = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  std::vector<double> r(n, 0.0), g(n, 0.0), t(n, 0.0), v(n), z(n), y(n);
  double rz_old = 1.0, lambda = 0.0;
  bool restart = true;

  for (int it = 0;; ++it) {
    summary.iterations = it;
    for (bool evaluated = false; !evaluated;) {
      // r = K (q − q_prev) + Δε x; λ its mean over the free cells (the multiplier of the load).
      double r_free = 0.0, r_upper = -std::numeric_limits<double>::infinity(), r_lower = -r_upper;
      int n_free = 0;
      for (int i = 0; i < n; ++i) {
        if (!contact[i]) continue;
        r[i] = u[i] - u_prev[i] + d_eps * grid.x(i);
        if (q[i] >= hi[i]) {
          r_upper = std::max(r_upper, r[i]);
        } else if (q[i] <= lo[i]) {
          r_lower = std::min(r_lower, r[i]);
        } else {
          r_free += r[i];
          ++n_free;
        }
      }
      if (n_free > 0) {
        lambda = r_free / n_free;
      } else {  // every cell at a bound: any λ in [max over q = +fp, min over q = −fp] satisfies the KKT conditions
        lambda = std::isfinite(r_upper) && std::isfinite(r_lower) ? 0.5 * (r_upper + r_lower)
                 : std::isfinite(r_upper)                         ? r_upper
                                                                  : r_lower;
      }
      double violation = 0.0;
      for (int i = 0; i < n; ++i) {
        if (!contact[i]) continue;
        g[i] = r[i] - lambda;
        const double vi = q[i] >= hi[i] ? std::max(g[i], 0.0) : q[i] <= lo[i] ? std::max(-g[i], 0.0) : std::abs(g[i]);
        violation = std::max(violation, vi);
      }
      summary.residual = violation / d;
      evaluated = u_exact || !(summary.residual <= options_.tolerance || it >= options_.max_iterations);
      if (!evaluated) {
        kernel_.apply(q, u);
        u_exact = true;
      }
    }
    if (!std::isfinite(summary.residual)) return finish(Termination::non_finite);
    if (summary.residual <= options_.tolerance) {
      // Δw = −Δs on the cells at a bound; the cells that stick do not slip, nor does a bound cell whose residual
      // points inward by less than the tolerance (it is taken as sticking, so that q Δw ≥ 0 holds exactly).
      for (int i = 0; i < n; ++i) {
        if (!contact[i]) continue;
        if (q[i] >= hi[i]) state.dw[i] = std::max(-g[i], 0.0);
        else if (q[i] <= lo[i]) state.dw[i] = std::min(-g[i], 0.0);
      }
      return finish(Termination::converged);
    }
    if (it >= options_.max_iterations) return finish(Termination::max_iterations);
    if (summary.residual < 0.5 * best_residual) best_residual = summary.residual, best_iteration = it;
    if (preconditioned && it - best_iteration > kStallIterations) return finish(Termination::max_iterations);

    // The working set: the free cells and the bound cells the residual pulls inward; a new set restarts CG.
    int n_work = 0;
    double g_sum = 0.0;
    for (int i = 0; i < n; ++i) {
      work[i] = contact[i] && ((q[i] < hi[i] && q[i] > lo[i]) || (q[i] >= hi[i] && g[i] > 0.0) ||
                               (q[i] <= lo[i] && g[i] < 0.0));
      if (work[i]) g_sum += g[i], ++n_work;
      restart = restart || work[i] != work_old[i];
    }
    work_old = work;
    // The gradient on the load-neutral subspace of the working set, and its preconditioned form.
    const double g_mean = g_sum / n_work;
    for (int i = 0; i < n; ++i) g[i] = work[i] ? g[i] - g_mean : 0.0;
    if (preconditioned) {
      kernel_.fft().apply_spectrum(inverse_spectrum_, g, z);
      double z_sum = 0.0;
      for (int i = 0; i < n; ++i)
        if (work[i]) z_sum += z[i];
      for (int i = 0; i < n; ++i) z[i] = work[i] ? z[i] - z_sum / n_work : 0.0;
    } else {
      z = g;
    }
    double rz = 0.0;
    for (int i = 0; i < n; ++i)
      if (work[i]) rz += g[i] * z[i];
    const double beta = restart ? 0.0 : rz / rz_old;
    for (int i = 0; i < n; ++i) t[i] = work[i] ? z[i] + beta * t[i] : 0.0;
    rz_old = rz;
    kernel_.apply(t, v);
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i) {
      if (work[i]) {
        num += g[i] * t[i];
        den += v[i] * t[i];  // Σ t = 0 on the working set: no mean of v to remove
      }
    }
    const double tau = num / den;
    if (!std::isfinite(tau) || !(den > 0.0)) return finish(Termination::non_finite);

    // Step on the working set, then project back onto the box and the load over it.
    double fixed = 0.0;
    for (int i = 0; i < n; ++i) {
      y[i] = work[i] ? q[i] - tau * t[i] : q[i];
      if (contact[i] && !work[i]) fixed += q[i];
    }
    const bool clamped = project(y, lo, hi, work, target - fixed, q);
    if (clamped) {
      kernel_.apply(q, u);
      u_exact = true;
    } else {
      for (int i = 0; i < n; ++i) u[i] -= tau * v[i];
      u_exact = false;
    }
    restart = clamped;
  }
}

namespace {

// f p − |q|: positive where a cell sticks, zero where it slips; near a stick edge it falls like the pressure of the
// corrective contact (f p* of the analogy), so locate_zones fits the edges as the analogy route does.
std::vector<double> stick_margin(std::span<const double> hi, std::span<const double> q) {
  std::vector<double> m(hi.size(), 0.0);
  for (std::size_t i = 0; i < hi.size(); ++i)
    if (hi[i] > 0.0) m[i] = std::max(hi[i] - std::abs(q[i]), 0.0);
  return m;
}

}  // namespace

IncrementalResult IncrementalSlipSolver::solve(const ContactState& contact, const CyclicLoad& load) const {
  const Grid& grid = kernel_.grid();
  const int n = grid.n;
  const double h = grid.h();
  const double f = load.f, P = load.P, Q = load.Q_max;
  IncrementalResult result;
  if (Q >= f * P) {
    CycleResult r;
    r.regime = Regime::gross_slip;
    r.message = fmt::format("Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and under force control the "
                            "slip is not determined",
                            Q, f * P);
    result.cycles.push_back(std::move(r));
    return result;
  }

  const std::vector<double>& p = contact.p;
  std::vector<double> hi(n);
  for (int i = 0; i < n; ++i) hi[i] = p[i] > 0.0 ? f * p[i] : 0.0;
  const std::vector<double> no_corners(n, 0.0);  // a stick zone never ends at a corner of the pad
  const int m = options_.increments_per_cycle;
  auto strain_at = [&](double Qt) { return Q > 0.0 ? load.bulk_strain * Qt / Q : 0.0; };

  IncrementState state;
  double Q_prev = 0.0;
  auto step = [&](double Qt, int cycle, int k) {
    const SlipIncrement inc{Qt, Q_prev, strain_at(Qt), strain_at(Q_prev)};
    const SolveSummary s = solve_increment(p, f, inc, state);
    ++result.n_increments;
    result.n_iterations += s.iterations;
    if (!(s.residual <= result.worst.residual) || result.n_increments == 1) result.worst = s;
    if (!s.converged())
      throw ConvergenceError(fmt::format(
          "incremental slip: {} increment {} (Q from {:.6g} to {:.6g} N/m) stopped ({}) after {} iterations with "
          "residual {:.3g} above the tolerance {:.3g}",
          cycle == 0 ? std::string("the first loading,") : fmt::format("cycle {},", cycle), k, Q_prev, Qt,
          to_string(s.termination), s.iterations, s.residual, options_.tolerance));
    Q_prev = Qt;
    return s;
  };

  // The first loading, 0 → Q, in a quarter of a cycle's increments.
  for (int k = 1; k <= m / 4; ++k) step(Q * (4.0 * k / m), 0, k);

  for (int cycle = 1; cycle <= options_.cycles; ++cycle) {
    CycleResult r;
    std::vector<double> w(n, 0.0), w_min(n, 0.0), w_max(n, 0.0);
    r.slip_travelled.assign(n, 0.0);
    r.energy_density.assign(n, 0.0);
    for (int j = 1; j <= m; ++j) {
      // +Q → −Q over the first half, −Q → +Q over the second; 0, −Q, 0 and +Q fall exactly on increment ends.
      const double Qt = 2 * j <= m ? Q * (1.0 - 4.0 * j / m) : Q * (-1.0 + 4.0 * (j - m / 2) / m);
      r.solves.push_back(step(Qt, cycle, j));
      for (int i = 0; i < n; ++i) {
        const double dw = state.dw[i];
        if (dw == 0.0) continue;
        w[i] += dw;
        w_min[i] = std::min(w_min[i], w[i]);
        w_max[i] = std::max(w_max[i], w[i]);
        r.slip_travelled[i] += std::abs(dw);
        r.energy_density[i] += state.q[i] * dw;
      }
      if (4 * j == m) r.q_unloaded = state.q;
      if (2 * j == m) r.q_bottom = state.q;
      if (4 * j == 3 * m) r.q_reloaded = state.q;
    }
    r.q_top = state.q;
    r.slip_range.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
      r.slip_range[i] = w_max[i] - w_min[i];
      r.slip_max = std::max(r.slip_max, r.slip_range[i]);
      r.dissipated_energy += h * r.energy_density[i];
    }

    const auto stick = locate_zones(grid, stick_margin(hi, r.q_top), no_corners);
    for (const Zone& z : stick) r.stick_zones.emplace_back(z.left.x, z.right.x);
    if (!stick.empty()) r.stick_zone = Interval{stick.front().left.x, stick.back().right.x};
    const auto stick_unloaded = locate_zones(grid, stick_margin(hi, r.q_unloaded), no_corners);
    if (!stick_unloaded.empty())
      r.stick_zone_unloaded = Interval{stick_unloaded.front().left.x, stick_unloaded.back().right.x};

    // Reverse slip: at the top some cell is held at q = −f p (the leading edge has slipped backwards).
    int n_backward = 0;
    double x_backward = 0.0;
    for (int i = 0; i < n; ++i)
      if (hi[i] > 0.0 && r.q_top[i] <= -hi[i]) x_backward = n_backward++ == 0 ? grid.x(i) : x_backward;
    if (n_backward > 0) {
      r.regime = Regime::reverse_slip;
      r.message = fmt::format("at the top of the cycle {} cells from x = {:.6g} m sit at q = -f p: the leading edge "
                              "slips backwards (reverse slip)",
                              n_backward, x_backward);
    }
    result.cycles.push_back(std::move(r));
  }
  return result;
}

}  // namespace fretwear
