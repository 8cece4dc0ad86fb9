#include "contact/normal_solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "contact/error.hpp"

namespace fretwear {

std::string NormalSolverOptions::validate() const {
  if (!(tolerance > 0.0 && tolerance <= 1e-2))
    return fmt::format("tolerance = {} is outside (0, 1e-2]", tolerance);
  if (max_iterations < 1) return fmt::format("max_iterations = {} must be at least 1", max_iterations);
  return {};
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
}

SolveSummary NormalSolver::solve(std::span<const double> g0, double P, ContactState& state) const {
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
  if (!(load > 0.0)) {  // cold start: uniform pressure on every admissible cell
    p.assign(n, 0.0);
    for (int i = 0; i < n; ++i) p[i] = admissible[i] ? 1.0 : 0.0;
    load = h * n_admissible;
  }
  for (double& pi : p) pi *= P / load;

  auto& g = state.gap;
  g.assign(n, 0.0);
  std::vector<double> t(n, 0.0), r(n);
  double G_old = 1.0;
  bool conjugate = false;
  constexpr double kInf = std::numeric_limits<double>::infinity();

  for (int it = 0;; ++it) {
    summary.iterations = it;
    kernel_.apply(p, g);
    double g_sum = 0.0;
    int n_active = 0;
    for (int i = 0; i < n; ++i) {
      g[i] = admissible[i] ? g[i] + g0[i] : kInf;
      if (p[i] > 0.0) g_sum += g[i], ++n_active;
    }
    const double g_mean = g_sum / n_active;
    state.approach = g_mean;
    double g_max = 0.0, comp = 0.0, overlap = 0.0, G = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!admissible[i]) continue;
      g[i] -= g_mean;
      g_max = std::max(g_max, g[i]);
      if (p[i] > 0.0) {
        comp += p[i] * std::abs(g[i]);
        G += g[i] * g[i];
      } else {
        overlap = std::max(overlap, -g[i]);
      }
    }
    if (!(g_max > 0.0)) g_max = std::max(std::abs(g_mean), std::numeric_limits<double>::min());
    summary.residual = std::max(h * comp / (P * g_max), overlap / g_max);
    if (!std::isfinite(summary.residual)) return finish(Termination::non_finite);
    if (summary.residual <= options_.tolerance) return finish(Termination::converged);
    if (it >= options_.max_iterations) return finish(Termination::max_iterations);

    // Conjugate direction on the contact set.
    const double beta = conjugate ? G / G_old : 0.0;
    for (int i = 0; i < n; ++i) t[i] = p[i] > 0.0 ? g[i] + beta * t[i] : 0.0;
    G_old = G;
    kernel_.apply(t, r);
    double r_sum = 0.0;
    for (int i = 0; i < n; ++i)
      if (p[i] > 0.0) r_sum += r[i];
    const double r_mean = r_sum / n_active;
    double num = 0.0, den = 0.0;
    for (int i = 0; i < n; ++i) {
      if (p[i] > 0.0) {
        num += g[i] * t[i];
        den += (r[i] - r_mean) * t[i];
      }
    }
    const double tau = num / den;
    if (!std::isfinite(tau)) return finish(Termination::non_finite);

    // Step, project onto p ≥ 0, let overlapping cells back in (then restart CG), rescale to the load.
    bool reentered = false;
    load = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!admissible[i]) continue;
      if (p[i] > 0.0) {
        p[i] = std::max(p[i] - tau * t[i], 0.0);
      } else if (g[i] < 0.0) {
        p[i] = -tau * g[i];
        reentered = true;
      }
      load += h * p[i];
    }
    conjugate = !reentered;
    if (!(load > 0.0)) return finish(Termination::non_finite);
    for (double& pi : p) pi *= P / load;
  }
}

}  // namespace fretwear
