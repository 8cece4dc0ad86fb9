#include "contact/normal_solver.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "common/error.hpp"

namespace fretwear {

std::string NormalSolverOptions::validate() const {
  if (!(tolerance > 0.0 && tolerance <= 1e-2))
    return fmt::format("tolerance = {} is outside (0, 1e-2]", tolerance);
  if (max_iterations < 1) return fmt::format("max_iterations = {} must be at least 1", max_iterations);
  if (!(proportioning >= 0.0 && proportioning < 1e3))
    return fmt::format("proportioning = {} is outside [0, 1e3)", proportioning);
  return {};
}

std::string to_string(NormalSolverOptions::Preconditioner p) {
  switch (p) {
    case NormalSolverOptions::Preconditioner::none: return "none";
    case NormalSolverOptions::Preconditioner::symbol: return "symbol";
  }
  return "?";
}

std::string to_string(Termination t) {
  switch (t) {
    case Termination::converged: return "converged";
    case Termination::max_iterations: return "max_iterations";
    case Termination::non_finite: return "non_finite";
    case Termination::no_admissible_cell: return "no_admissible_cell";
  }
  return "?";
}

std::string SolveSummary::brief() const {
  return fmt::format("{} after {} iterations, residual {:.3g}, {:.3g} ms", to_string(termination), iterations,
                     residual, 1e3 * seconds);
}

NormalSolver::NormalSolver(const HalfPlaneKernel& kernel, NormalSolverOptions options)
    : kernel_(kernel), options_(options) {
  if (auto msg = options_.validate(); !msg.empty()) throw InputError("normal solver options: " + msg);
  if (options_.preconditioner == NormalSolverOptions::Preconditioner::symbol)
    preconditioned_ = !kernel_.inverse_spectrum().empty();
}

namespace {

// u += c K e_j for the Toeplitz K with first column col.
void add_column(std::span<const double> col, int j, double c, std::span<double> u) {
  const int n = int(u.size());
  for (int i = 0; i < j; ++i) u[i] += c * col[j - i];
  for (int i = j; i < n; ++i) u[i] += c * col[i - j];
}

}  // namespace

SolveSummary NormalSolver::solve(std::span<const double> g0, double P, ContactState& state) const {
  return solve(g0, P, state, {});
}

SolveSummary NormalSolver::solve(std::span<const double> g0, double P, ContactState& state,
                                 std::span<const double> shift) const {
  if (!preconditioned_) return iterate(g0, P, state, shift, false);
  const SolveSummary first = iterate(g0, P, state, shift, true);
  if (first.converged() || first.termination == Termination::no_admissible_cell) return first;
  // The preconditioned iteration can stall where long stretches sit at zero gap and zero pressure (a worn
  // profile near its asymptote); plain constrained CG, warm-started from where it stopped, does not.
  SolveSummary second = iterate(g0, P, state, shift, false);
  second.iterations += first.iterations;
  second.seconds += first.seconds;
  return second;
}

SolveSummary NormalSolver::iterate(std::span<const double> g0, double P, ContactState& state,
                                   std::span<const double> shift, bool use_preconditioner) const {
  const auto t_start = std::chrono::steady_clock::now();
  const int n = kernel_.grid().n;
  const double h = kernel_.grid().h();
  SolveSummary summary;
  auto finish = [&](Termination t) {
    summary.termination = t;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return summary;
  };

  std::vector<char> admissible(n);
  int n_admissible = 0;
  for (int i = 0; i < n; ++i) n_admissible += admissible[i] = std::isfinite(g0[i]);
  if (n_admissible == 0) return finish(Termination::no_admissible_cell);

  auto& p = state.p;
  double load = 0.0;
  if (int(p.size()) == n) {
    for (int i = 0; i < n; ++i) {
      if (!admissible[i] || !(p[i] > 0.0)) p[i] = 0.0;
      load += h * p[i];
    }
  }
  if (!(load > 0.0)) {
    // Cold start: uniform pressure where the gap is within A P / 2 of its minimum (the cells that may touch, as the
    // default window reckons them: the exact contact of a wedge, 1.25 a for Hertz).
    double g0_min = std::numeric_limits<double>::infinity();
    for (int i = 0; i < n; ++i)
      if (admissible[i]) g0_min = std::min(g0_min, g0[i]);
    const double reach = g0_min + 0.5 * kernel_.A() * P;
    p.assign(n, 0.0);
    for (int i = 0; i < n; ++i) {
      p[i] = admissible[i] && (!options_.cold_start_near || g0[i] <= reach) ? 1.0 : 0.0;
      load += h * p[i];
    }
  }
  for (double& pi : p) pi *= P / load;

  const bool shifted = !shift.empty();
  // y = (K + diag(shift)) x
  auto apply = [&](std::span<const double> x, std::span<double> y) {
    kernel_.apply(x, y);
    if (shifted)
      for (int i = 0; i < n; ++i) y[i] += shift[i] * x[i];
  };
  // With a shift, a block preconditioner: the symbol (K's circulant inverse) on the cells where K dominates, Jacobi
  // 1/(K_00 + shift_i) where the shift does. A circulant shifted by the mean shift fits neither block and stalled
  // (20 000 iterations on the Hertz wear run).
  const bool preconditioned = use_preconditioner && preconditioned_;
  // A preconditioned run that has not halved its best residual for this many iterations has stalled.
  constexpr int kStallIterations = 200;
  double best_residual = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  const double k00 = kernel_.column()[0];
  const auto& inverse = kernel_.inverse_spectrum();
  // A sparse correction of s columns costs s n; a product about as much as 2 log2(2n) columns (BM_ToeplitzProduct).
  const int max_columns = std::max(4, 2 * int(std::bit_width(unsigned(2 * n))));
  const std::span<const double> column = kernel_.column();

  auto& g = state.gap;
  g.assign(n, 0.0);
  std::vector<double> u(n), t(n, 0.0), v(n), z(preconditioned ? n : 0), e(preconditioned ? n : 0);
  std::vector<char> work(n), e_work;
  std::vector<int> changed;  // cells where projection or re-entry changed p − τ t
  std::vector<double> change;
  apply(p, u);
  bool u_exact = true;
  double rz_old = 1.0;
  bool conjugate = false;
  constexpr double kInf = std::numeric_limits<double>::infinity();

  for (int it = 0;; ++it) {
    summary.iterations = it;
    double g_mean = 0.0;
    double G = 0.0, overlap_sq = 0.0;
    for (bool evaluated = false; !evaluated;) {
      double g_sum = 0.0;
      int n_active = 0;
      for (int i = 0; i < n; ++i) {
        g[i] = admissible[i] ? u[i] + g0[i] : kInf;
        if (p[i] > 0.0) g_sum += g[i], ++n_active;
      }
      g_mean = g_sum / n_active;
      double g_max = 0.0, comp = 0.0, overlap = 0.0;
      G = 0.0;
      overlap_sq = 0.0;
      for (int i = 0; i < n; ++i) {
        if (!admissible[i]) continue;
        g[i] -= g_mean;
        g_max = std::max(g_max, g[i]);
        if (p[i] > 0.0) {
          comp += p[i] * std::abs(g[i]);
          G += g[i] * g[i];
        } else {
          overlap = std::max(overlap, -g[i]);
          if (g[i] < 0.0) overlap_sq += g[i] * g[i];
        }
      }
      // A complete contact loads every admissible cell and leaves no open gap to measure against; A P, the 2D
      // approach scale, keeps the residual meaningful there (regression_complete_contact_residual.cpp).
      g_max = std::max(g_max, kernel_.A() * P);
      summary.residual = std::max(h * comp / (P * g_max), overlap / g_max);
      // Stop only on an exact u: recompute K p once the carried one says converged (or at the last iteration).
      evaluated = u_exact || !(summary.residual <= options_.tolerance || it >= options_.max_iterations);
      if (!evaluated) {
        apply(p, u);
        u_exact = true;
      }
    }
    state.approach = g_mean;
    if (!std::isfinite(summary.residual)) return finish(Termination::non_finite);
    if (summary.residual <= options_.tolerance) return finish(Termination::converged);
    if (it >= options_.max_iterations) return finish(Termination::max_iterations);
    if (summary.residual < 0.5 * best_residual) best_residual = summary.residual, best_iteration = it;
    if (preconditioned && it - best_iteration > kStallIterations) return finish(Termination::max_iterations);

    // The working set: the contact set; with the preconditioner also every overlapping cell, which then enters
    // through a preconditioned steepest-descent step on the enlarged set (re-entry at −τ g, as without it, scales
    // with the cell and overshoots on fine grids).
    // Overlapping cells are let in only when their violation is large against the gradient on the contact set
    // (Dostál's proportioning): cells at zero gap and zero pressure, which a worn profile has by the hundred, would
    // otherwise enter and leave at every iteration and restart CG each time.
    const double gamma = options_.proportioning;
    const bool admit = overlap_sq > gamma * gamma * G;
    bool enlarge = false;
    for (int i = 0; i < n; ++i) {
      const bool overlapping = p[i] == 0.0 && g[i] < 0.0;  // inadmissible cells have g = +∞
      enlarge = enlarge || (preconditioned && overlapping && admit);
    }
    for (int i = 0; i < n; ++i) work[i] = p[i] > 0.0 || (enlarge && g[i] < 0.0);

    // Conjugate direction on the working set: t = z + β t, z = g or its preconditioned form.
    double rz = G;
    if (preconditioned) {
      for (int i = 0; i < n; ++i) z[i] = work[i] && !(shifted && shift[i] > k00) ? g[i] : 0.0;
      kernel_.fft().apply_spectrum(inverse, z, z);
      if (shifted)
        for (int i = 0; i < n; ++i)
          if (work[i] && shift[i] > k00) z[i] = g[i] / (k00 + shift[i]);
      // Keep the direction load-neutral (Σ z = 0 on the working set). Unshifted, the plain mean is subtracted (the
      // symbol preconditioner is nearly uniform there). Shifted, the Jacobi block scales cells by up to 1e6
      // against the symbol block, and only the projection in the preconditioner's metric keeps CG consistent:
      // z = M⁻¹ g − λ M⁻¹ 1 with λ = Σ M⁻¹g / Σ M⁻¹1 (a plain mean stalled every wear-sized shift).
      if (shifted) {
        // M⁻¹ 1 depends on the working set alone: recomputed only when the set changed.
        if (work != e_work) {
          for (int i = 0; i < n; ++i) e[i] = work[i] && !(shift[i] > k00) ? 1.0 : 0.0;
          kernel_.fft().apply_spectrum(inverse, e, e);
          for (int i = 0; i < n; ++i)
            if (work[i] && shift[i] > k00) e[i] = 1.0 / (k00 + shift[i]);
          e_work = work;
        }
      } else {
        for (int i = 0; i < n; ++i) e[i] = work[i] ? 1.0 : 0.0;
      }
      double z_sum = 0.0, e_sum = 0.0;
      for (int i = 0; i < n; ++i)
        if (work[i]) z_sum += z[i], e_sum += e[i];
      const double lambda = z_sum / e_sum;
      rz = 0.0;
      for (int i = 0; i < n; ++i) {
        z[i] = work[i] ? z[i] - lambda * e[i] : 0.0;
        if (work[i]) rz += g[i] * z[i];
      }
    }
    const std::span<const double> dir = preconditioned ? std::span<const double>(z) : std::span<const double>(g);
    const double beta = conjugate && !enlarge ? rz / rz_old : 0.0;
    for (int i = 0; i < n; ++i) t[i] = work[i] ? dir[i] + beta * t[i] : 0.0;
    rz_old = rz;
    apply(t, v);
    double v_sum = 0.0;
    int n_work = 0;
    for (int i = 0; i < n; ++i)
      if (work[i]) v_sum += v[i], ++n_work;
    const double v_mean = v_sum / n_work;
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i) {
      if (work[i]) {
        num += g[i] * t[i];
        den += (v[i] - v_mean) * t[i];
      }
    }
    const double tau = num / den;
    if (!std::isfinite(tau)) return finish(Termination::non_finite);

    // Step, project onto p ≥ 0, let overlapping cells back in (then restart CG), rescale to the load.
    bool reentered = enlarge;
    changed.clear();
    change.clear();
    load = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!admissible[i]) continue;
      if (work[i]) {
        const double stepped = p[i] - tau * t[i];
        if (stepped < 0.0) changed.push_back(i), change.push_back(-stepped);
        p[i] = std::max(stepped, 0.0);
      } else if (g[i] < 0.0 && admit) {
        p[i] = -tau * g[i];
        changed.push_back(i), change.push_back(p[i]);
        reentered = true;
      }
      load += h * p[i];
    }
    conjugate = !reentered;
    if (!(load > 0.0)) return finish(Termination::non_finite);
    const double scale = P / load;
    for (double& pi : p) pi *= scale;
    if (options_.incremental_gap && int(changed.size()) <= max_columns && tau != 0.0) {
      // u ← scale (u − τ (v − (K + diag(shift)) c / τ))
      for (std::size_t k = 0; k < changed.size(); ++k) {
        add_column(column, changed[k], -change[k] / tau, v);
        if (shifted) v[changed[k]] -= shift[changed[k]] * change[k] / tau;
      }
      for (int i = 0; i < n; ++i) u[i] = scale * (u[i] - tau * v[i]);
      u_exact = false;
    } else {
      apply(p, u);
      u_exact = true;
    }
  }
}

}  // namespace fretwear
