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
    case Termination::not_run: return "not_run";
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

constexpr double kInf = std::numeric_limits<double>::infinity();
// A preconditioned run that has not halved its best residual for this many iterations has stalled.
constexpr int kStallIterations = 200;
// A plain run from where a preconditioned one stalled: stalled when it has not halved its best residual for this
// many (such runs converge in a few hundred iterations, 4096 cells included).
constexpr int kPlainStallIterations = 5000;
// The active-set fallback (ActiveSetSolve): sets tried, CG iterations for each set's equalities, and their gap error
// as a share of the solver's tolerance times the gap scale (a tenth: the residual that accepts the result is then
// the constrained CG's own, met at its first iteration).
constexpr int kMaxActiveSets = 50;
constexpr int kMaxActiveSetIterations = 2000;
constexpr double kActiveSetGapError = 0.1;

// u += c K e_j for the Toeplitz K with first column col.
void add_column(std::span<const double> col, int j, double c, std::span<double> u) {
  const int n = int(u.size());
  for (int i = 0; i < j; ++i) u[i] += c * col[j - i];
  for (int i = j; i < n; ++i) u[i] += c * col[i - j];
}

// The preconditioner on the cells of `set` (ConstrainedCg's working set, ActiveSetSolve's set): z = M⁻¹ x, M the
// kernel's circulant on the cells K dominates and Jacobi K_00 + shift_i on those a shift dominates (shift_i > K_00),
// made load-neutral on the set, z − λ e with λ = Σ z / Σ e over it: e = M⁻¹ 1 with a shift (recomputed only when
// `set` is not `e_set`), e = 1 without one (the plain mean). z is zero off the set, and x is read only on it.
void block_precondition(const HalfPlaneKernel& kernel, std::span<const double> shift, std::span<const char> set,
                        std::span<const double> x, std::span<double> z, std::vector<double>& e,
                        std::vector<char>& e_set) {
  const int n = int(set.size());
  const double k00 = kernel.column()[0];
  const bool shifted = !shift.empty();
  const auto& inverse = kernel.inverse_spectrum();
  for (int i = 0; i < n; ++i) z[i] = set[i] && !(shifted && shift[i] > k00) ? x[i] : 0.0;
  kernel.fft().apply_spectrum(inverse, z, z);
  if (shifted)
    for (int i = 0; i < n; ++i)
      if (set[i] && shift[i] > k00) z[i] = x[i] / (k00 + shift[i]);
  if (shifted) {
    // M⁻¹ 1 depends on the set alone: recomputed only when the set changed.
    if (!std::equal(set.begin(), set.end(), e_set.begin(), e_set.end())) {
      for (int i = 0; i < n; ++i) e[i] = set[i] && !(shift[i] > k00) ? 1.0 : 0.0;
      kernel.fft().apply_spectrum(inverse, e, e);
      for (int i = 0; i < n; ++i)
        if (set[i] && shift[i] > k00) e[i] = 1.0 / (k00 + shift[i]);
      e_set.assign(set.begin(), set.end());
    }
  } else {
    for (int i = 0; i < n; ++i) e[i] = set[i] ? 1.0 : 0.0;
  }
  double z_sum = 0.0, e_sum = 0.0;
  for (int i = 0; i < n; ++i)
    if (set[i]) z_sum += z[i], e_sum += e[i];
  const double lambda = z_sum / e_sum;
  for (int i = 0; i < n; ++i) z[i] = set[i] ? z[i] - lambda * e[i] : 0.0;
}

// One run of the header's constrained CG (Polonsky and Keer 1999) on the operator K + diag(shift): the pressure p
// (state.p) with its displacement u = (K + diag(shift)) p carried from iterate to iterate, the gap g = g0 + u − δ
// (state.gap, δ its mean over the contact set) and the conjugate direction t on the working set.
class ConstrainedCg {
 public:
  ConstrainedCg(const HalfPlaneKernel& kernel, const NormalSolverOptions& options, std::span<const double> g0,
                double P, ContactState& state, std::span<const double> shift, bool preconditioned);

  bool preconditioned() const { return preconditioned_; }
  // Some cell has pad material above it (a finite g0).
  bool has_admissible_cell() const { return n_admissible_ > 0; }
  // p on the load P: the caller's p where it carries load, else the cold start; u = (K + diag(shift)) p.
  void start();
  // r of the stopping criterion, on an exact u whenever r could stop the run (`last`: the iteration limit is reached).
  double residual(bool last);
  // The working set: the contact set, enlarged by the overlapping cells when the proportioning test admits them.
  void select_working_set();
  // t = z + β t on the working set, z = g or its preconditioned form; β = 0 after a restart or an enlarged set.
  void conjugate_direction();
  // τ = g·t / t·(K + diag(shift)) t on the load-balanced subspace, with v = (K + diag(shift)) t.
  double step_length();
  // p ← max(p − τ t, 0) on the working set, overlapping cells re-entered at −τ g, scaled to the load; u follows.
  // False when no load is left to scale.
  bool step(double tau);

 private:
  // y = (K + diag(shift)) x
  void apply(std::span<const double> x, std::span<double> y) const;
  // g = g0 + u − δ with δ the mean over the contact set, and r = max(h Σ p |g| / (P g_max), max_{p = 0} (−g) / g_max);
  // also Σ g² over the contact set (G) and over the overlapping cells, for the proportioning test.
  double gap_residual();
  // z = M⁻¹ g made load-neutral on the working set in M's metric; returns g·z.
  double precondition();
  // p − τ t projected onto p ≥ 0 on the working set, overlapping cells re-entered at −τ g (c: what both change);
  // returns the load h Σ p.
  double project(double tau);
  // p scaled by P / load, and u ← scale (u − τ (v − (K + diag(shift)) c / τ)) while c is sparse, else recomputed.
  void rescale(double tau, double load);

  const HalfPlaneKernel& kernel_;
  const NormalSolverOptions& options_;
  const std::span<const double> g0_, shift_;
  const double P_;
  ContactState& state_;
  std::vector<double>& p_;
  std::vector<double>& g_;
  const bool shifted_, preconditioned_;
  const int n_;
  const double h_, k00_;
  // A sparse correction of s columns costs s n; a product about as much as 2 log2(2n) columns (BM_ToeplitzProduct).
  const int max_columns_;
  std::vector<char> admissible_;  // finite g0: the pad has material above the cell
  int n_admissible_ = 0;
  std::vector<char> work_;        // the working set of the current iteration
  std::vector<char> e_work_;      // the working set e_ was computed for
  std::vector<double> u_;         // (K + diag(shift)) p, carried; exact when u_exact_
  std::vector<double> t_, v_;     // the conjugate direction and (K + diag(shift)) t
  std::vector<double> z_, e_;     // M⁻¹ g and M⁻¹ 1 on the working set (preconditioned only)
  std::vector<int> changed_;      // cells where projection or re-entry changed p − τ t
  std::vector<double> change_;    // by how much (Pa)
  bool u_exact_ = true;
  double rz_old_ = 1.0;           // g·z of the previous direction
  bool conjugate_ = false;        // the next direction is conjugate to the last (no restart)
  double g_mean_ = 0.0;           // δ: the mean gap over the contact set (m)
  double G_ = 0.0, overlap_sq_ = 0.0;  // Σ g² over the contact set and over the overlapping cells (m²)
  bool admit_ = false;            // the proportioning test lets the overlapping cells in
  bool enlarge_ = false;          // ... and, preconditioned, into the working set
};

ConstrainedCg::ConstrainedCg(const HalfPlaneKernel& kernel, const NormalSolverOptions& options,
                             std::span<const double> g0, double P, ContactState& state, std::span<const double> shift,
                             bool preconditioned)
    : kernel_(kernel),
      options_(options),
      g0_(g0),
      shift_(shift),
      P_(P),
      state_(state),
      p_(state.p),
      g_(state.gap),
      shifted_(!shift.empty()),
      preconditioned_(preconditioned),
      n_(kernel.grid().n),
      h_(kernel.grid().h()),
      k00_(kernel.column()[0]),
      max_columns_(std::max(4, 2 * int(std::bit_width(unsigned(2 * n_))))),
      admissible_(n_),
      work_(n_),
      u_(n_),
      t_(n_, 0.0),
      v_(n_),
      z_(preconditioned ? n_ : 0),
      e_(preconditioned ? n_ : 0) {
  for (int i = 0; i < n_; ++i) n_admissible_ += admissible_[i] = std::isfinite(g0_[i]);
}

void ConstrainedCg::apply(std::span<const double> x, std::span<double> y) const {
  kernel_.apply(x, y);
  if (shifted_)
    for (int i = 0; i < n_; ++i) y[i] += shift_[i] * x[i];
}

void ConstrainedCg::start() {
  double load = 0.0;
  if (int(p_.size()) == n_) {
    for (int i = 0; i < n_; ++i) {
      if (!admissible_[i] || !(p_[i] > 0.0)) p_[i] = 0.0;
      load += h_ * p_[i];
    }
  }
  if (!(load > 0.0)) {
    // Cold start: uniform pressure where the gap is within A P / 2 of its minimum (the cells that may touch, as the
    // default window reckons them: the exact contact of a wedge, 1.25 a for Hertz).
    double g0_min = kInf;
    for (int i = 0; i < n_; ++i)
      if (admissible_[i]) g0_min = std::min(g0_min, g0_[i]);
    const double reach = g0_min + 0.5 * kernel_.A() * P_;
    p_.assign(n_, 0.0);
    for (int i = 0; i < n_; ++i) {
      p_[i] = admissible_[i] && (!options_.cold_start_near || g0_[i] <= reach) ? 1.0 : 0.0;
      load += h_ * p_[i];
    }
  }
  for (double& pi : p_) pi *= P_ / load;
  g_.assign(n_, 0.0);
  apply(p_, u_);
}

double ConstrainedCg::residual(bool last) {
  double r = gap_residual();
  // Stop only on an exact u: recompute K p once the carried one says converged (or at the last iteration).
  while (!u_exact_ && (r <= options_.tolerance || last)) {
    apply(p_, u_);
    u_exact_ = true;
    r = gap_residual();
  }
  state_.approach = g_mean_;
  return r;
}

double ConstrainedCg::gap_residual() {
  double g_sum = 0.0;
  int n_active = 0;
  for (int i = 0; i < n_; ++i) {
    g_[i] = admissible_[i] ? u_[i] + g0_[i] : kInf;
    if (p_[i] > 0.0) g_sum += g_[i], ++n_active;
  }
  g_mean_ = g_sum / n_active;
  double g_max = 0.0, comp = 0.0, overlap = 0.0;
  G_ = 0.0;
  overlap_sq_ = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (!admissible_[i]) continue;
    g_[i] -= g_mean_;
    g_max = std::max(g_max, g_[i]);
    if (p_[i] > 0.0) {
      comp += p_[i] * std::abs(g_[i]);
      G_ += g_[i] * g_[i];
    } else {
      overlap = std::max(overlap, -g_[i]);
      if (g_[i] < 0.0) overlap_sq_ += g_[i] * g_[i];
    }
  }
  // A complete contact loads every admissible cell and leaves no open gap to measure against; A P, the 2D
  // approach scale, keeps the residual meaningful there (regression_complete_contact_residual.cpp).
  g_max = std::max(g_max, kernel_.A() * P_);
  return std::max(h_ * comp / (P_ * g_max), overlap / g_max);
}

// With the preconditioner every overlapping cell joins the working set, and then enters through a preconditioned
// steepest-descent step on the enlarged set (re-entry at −τ g, as without it, scales with the cell and overshoots on
// fine grids). Overlapping cells are let in only when their violation is large against the gradient on the contact
// set (Dostál's proportioning): cells at zero gap and zero pressure, which a worn profile has by the hundred, would
// otherwise enter and leave at every iteration and restart CG each time.
void ConstrainedCg::select_working_set() {
  const double gamma = options_.proportioning;
  admit_ = overlap_sq_ > gamma * gamma * G_;
  enlarge_ = false;
  for (int i = 0; i < n_; ++i) {
    const bool overlapping = p_[i] == 0.0 && g_[i] < 0.0;  // inadmissible cells have g = +∞
    enlarge_ = enlarge_ || (preconditioned_ && overlapping && admit_);
  }
  for (int i = 0; i < n_; ++i) work_[i] = p_[i] > 0.0 || (enlarge_ && g_[i] < 0.0);
}

void ConstrainedCg::conjugate_direction() {
  double rz = G_;
  if (preconditioned_) rz = precondition();
  const std::span<const double> dir = preconditioned_ ? std::span<const double>(z_) : std::span<const double>(g_);
  const double beta = conjugate_ && !enlarge_ ? rz / rz_old_ : 0.0;
  for (int i = 0; i < n_; ++i) t_[i] = work_[i] ? dir[i] + beta * t_[i] : 0.0;
  rz_old_ = rz;
}

// With a shift, a block preconditioner: the symbol (K's circulant inverse) on the cells where K dominates, Jacobi
// 1/(K_00 + shift_i) where the shift does. A circulant shifted by the mean shift fits neither block and stalled
// (20 000 iterations on the Hertz wear run).
// Keep the direction load-neutral (Σ z = 0 on the working set). Unshifted, the plain mean is subtracted (the symbol
// preconditioner is nearly uniform there). Shifted, the Jacobi block scales cells by up to 1e6 against the symbol
// block, and only the projection in the preconditioner's metric keeps CG consistent: z = M⁻¹ g − λ M⁻¹ 1 with
// λ = Σ M⁻¹g / Σ M⁻¹1 (a plain mean stalled every wear-sized shift).
double ConstrainedCg::precondition() {
  block_precondition(kernel_, shift_, work_, g_, z_, e_, e_work_);
  double rz = 0.0;
  for (int i = 0; i < n_; ++i)
    if (work_[i]) rz += g_[i] * z_[i];
  return rz;
}

double ConstrainedCg::step_length() {
  apply(t_, v_);
  double v_sum = 0.0;
  int n_work = 0;
  for (int i = 0; i < n_; ++i)
    if (work_[i]) v_sum += v_[i], ++n_work;
  const double v_mean = v_sum / n_work;
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (work_[i]) {
      num += g_[i] * t_[i];
      den += (v_[i] - v_mean) * t_[i];
    }
  }
  return num / den;
}

bool ConstrainedCg::step(double tau) {
  const double load = project(tau);
  if (!(load > 0.0)) return false;
  rescale(tau, load);
  return true;
}

double ConstrainedCg::project(double tau) {
  bool reentered = enlarge_;
  changed_.clear();
  change_.clear();
  double load = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (!admissible_[i]) continue;
    if (work_[i]) {
      const double stepped = p_[i] - tau * t_[i];
      if (stepped < 0.0) changed_.push_back(i), change_.push_back(-stepped);
      p_[i] = std::max(stepped, 0.0);
    } else if (g_[i] < 0.0 && admit_) {
      p_[i] = -tau * g_[i];
      changed_.push_back(i), change_.push_back(p_[i]);
      reentered = true;
    }
    load += h_ * p_[i];
  }
  conjugate_ = !reentered;  // a cell let back in restarts CG
  return load;
}

void ConstrainedCg::rescale(double tau, double load) {
  const double scale = P_ / load;
  for (double& pi : p_) pi *= scale;
  if (options_.incremental_gap && int(changed_.size()) <= max_columns_ && tau != 0.0) {
    const std::span<const double> column = kernel_.column();
    for (std::size_t k = 0; k < changed_.size(); ++k) {
      add_column(column, changed_[k], -change_[k] / tau, v_);
      if (shifted_) v_[changed_[k]] -= shift_[changed_[k]] * change_[k] / tau;
    }
    for (int i = 0; i < n_; ++i) u_[i] = scale * (u_[i] - tau * v_[i]);
    u_exact_ = false;
  } else {
    apply(p_, u_);
    u_exact_ = true;
  }
}

// The primal–dual active-set iteration (Hintermüller, Ito and Kunisch 2003, a semismooth Newton method), where the
// constrained CG's working sets cycle (NormalSolver::solve), on K or K + diag(shift). Each step solves the contact
// conditions as equalities on a set C, g_i = 0 on C and p_i = 0 off it with h Σ p = P, by preconditioned CG on C
// with the mean gap removed (no projection, so nothing restarts it), then takes as the next set the cells of C whose
// pressure stayed non-negative and the cells off C that overlap by more than the equality solve resolves,
//     C ← {i ∈ C : p_i ≥ 0} ∪ {i ∉ C : g_i < −e},
// e (`inner`, m) the bound on each equality solve's gap error. A worn contact near its limit has cells at zero gap
// and zero pressure by the hundred, which a set that dropped them at p = 0 and took them back at an overlap of
// round-off (1e-15 m) moved in and out for ever (either rule alone settles the captured case). A set that repeats
// stops it (the iteration is not guaranteed to settle for a kernel that is not an M-matrix). Returns whether the set
// settled; p then holds its pressure, which the caller accepts only by its own residual. `iterations` counts the CG
// iterations.
class ActiveSetSolve {
 public:
  // shift: empty, or the contact-implicit step's diag(shift) added to K (m/Pa per cell).
  ActiveSetSolve(const HalfPlaneKernel& kernel, std::span<const double> g0, double P, std::span<const double> shift)
      : kernel_(kernel), g0_(g0), shift_(shift), P_(P), n_(kernel.grid().n), h_(kernel.grid().h()),
        u_(n_), g_(n_), r_(n_), z_(n_), t_(n_), v_(n_), e_(n_), set_(n_, 0) {}

  // max_cg bounds each set's CG iterations, max_total all of them (iterations counts them).
  bool run(std::vector<double>& p, double inner, int max_sets, int max_cg, int max_total, int& iterations) {
    max_total_ = max_total;
    p.resize(n_, 0.0);
    for (int i = 0; i < n_; ++i) {
      set_[i] = std::isfinite(g0_[i]) && p[i] > 0.0;
      if (!set_[i]) p[i] = 0.0;
    }
    std::vector<std::vector<char>> seen;
    for (int k = 0; k < max_sets; ++k) {
      if (!equalities(p, inner, max_cg, iterations)) return false;
      std::vector<char> next(n_, 0);
      bool settled = true;
      for (int i = 0; i < n_; ++i) {
        if (!std::isfinite(g0_[i])) continue;
        next[i] = set_[i] ? p[i] >= 0.0 : g_[i] < -inner;
        settled = settled && next[i] == set_[i];
      }
      if (settled) return true;
      if (std::find(seen.begin(), seen.end(), next) != seen.end()) return false;  // the sets cycle
      seen.push_back(set_);
      set_ = std::move(next);
      for (int i = 0; i < n_; ++i)
        if (!set_[i]) p[i] = 0.0;
    }
    return false;
  }

 private:
  // y = (K + diag(shift)) x
  void apply(std::span<const double> x, std::span<double> y) const {
    kernel_.apply(x, y);
    if (!shift_.empty())
      for (int i = 0; i < n_; ++i) y[i] += shift_[i] * x[i];
  }

  // (K + diag(shift)) p on the cells, and the gap g = (K + diag(shift)) p + g0 − δ with δ its mean over the set.
  void gap(std::span<const double> p) {
    apply(p, u_);
    double sum = 0.0;
    int m = 0;
    for (int i = 0; i < n_; ++i)
      if (set_[i]) sum += u_[i] + g0_[i], ++m;
    const double delta = sum / m;
    for (int i = 0; i < n_; ++i) g_[i] = std::isfinite(g0_[i]) ? u_[i] + g0_[i] - delta : kInf;
  }

  // z = M⁻¹ x made load-neutral on the set (block_precondition).
  void precondition(std::span<const double> x, std::span<double> z) {
    block_precondition(kernel_, shift_, set_, x, z, e_, e_set_);
  }

  // The equalities on the set: p on it with h Σ p = P and g = 0 there, by CG from the given p (rescaled to the load,
  // or uniform where it carries none); g_ is then the gap everywhere.
  bool equalities(std::vector<double>& p, double inner, int max_cg, int& iterations) {
    double load = 0.0;
    int m = 0;
    for (int i = 0; i < n_; ++i)
      if (set_[i]) load += h_ * p[i], ++m;
    if (m == 0) return false;
    for (int i = 0; i < n_; ++i) p[i] = set_[i] ? (load > 0.0 ? p[i] * P_ / load : P_ / (h_ * m)) : 0.0;
    gap(p);
    for (int i = 0; i < n_; ++i) r_[i] = set_[i] ? -g_[i] : 0.0;
    precondition(r_, z_);
    double rz = 0.0;
    for (int i = 0; i < n_; ++i) rz += r_[i] * z_[i];
    t_ = z_;
    for (int it = 0;; ++it) {
      double worst = 0.0;
      for (int i = 0; i < n_; ++i)
        if (set_[i]) worst = std::max(worst, std::abs(r_[i]));
      if (worst <= inner) break;
      if (it >= max_cg || iterations >= max_total_ || !(rz > 0.0)) return false;
      apply(t_, v_);
      double v_mean = 0.0;
      for (int i = 0; i < n_; ++i)
        if (set_[i]) v_mean += v_[i];
      v_mean /= m;
      double tv = 0.0;
      for (int i = 0; i < n_; ++i)
        if (set_[i]) tv += t_[i] * (v_[i] - v_mean);
      const double alpha = rz / tv;
      for (int i = 0; i < n_; ++i)
        if (set_[i]) p[i] += alpha * t_[i], r_[i] -= alpha * (v_[i] - v_mean);
      precondition(r_, z_);
      double rz_new = 0.0;
      for (int i = 0; i < n_; ++i) rz_new += r_[i] * z_[i];
      for (int i = 0; i < n_; ++i) t_[i] = set_[i] ? z_[i] + rz_new / rz * t_[i] : 0.0;
      rz = rz_new;
      ++iterations;
      if (it % 50 == 49) {  // the recurrence drifts: the residual afresh from p
        gap(p);
        for (int i = 0; i < n_; ++i) r_[i] = set_[i] ? -g_[i] : 0.0;
      }
    }
    gap(p);
    return true;
  }

  const HalfPlaneKernel& kernel_;
  const std::span<const double> g0_, shift_;
  const double P_;
  const int n_;
  const double h_;
  std::vector<double> u_, g_, r_, z_, t_, v_, e_;  // e_: block_precondition's e, for the set e_set_
  std::vector<char> set_, e_set_;
  int max_total_ = 0;
};

}  // namespace

SolveSummary NormalSolver::solve(std::span<const double> g0, double P, ContactState& state) const {
  return solve(g0, P, state, {});
}

SolveSummary NormalSolver::solve(std::span<const double> g0, double P, ContactState& state,
                                 std::span<const double> shift) const {
  if (!preconditioned_) return iterate(g0, P, state, shift, false);
  const std::vector<double> start = state.p;  // the caller's warm start (empty, or without load: cold)
  SolveSummary total = iterate(g0, P, state, shift, true);
  if (total.converged() || total.termination == Termination::no_admissible_cell) return total;
  const auto then = [&total](const SolveSummary& next) {
    const int iterations = total.iterations + next.iterations;
    const double seconds = total.seconds + next.seconds;
    total = next;
    total.iterations = iterations, total.seconds = seconds;
  };
  // After a stalled preconditioned run: the active set, then plain constrained CG, then both from the cold start.
  //
  // A stick zone standing proud of worn zones in light contact, its edges one-cell steps of 0.1 µm that carry
  // several GPa like a flat punch's corners (a contact worn near the stick limit, 512 cells and up), defeats the
  // constrained CG from any start: the preconditioned run reaches a residual of a few 1e-3 within a few iterations,
  // and then the working set takes in the worn zones at once (the proportioning test's sum of their small overlaps),
  // sheds them a few cells an iteration, and takes them in again; the plain run cycles likewise, to its stall test
  // or its iteration limit. The active-set iteration has no such restarts and settles in a few sets
  // (regression_normal_solve_worn_punch_corners.cpp): from the caller's start, or where the preconditioned run
  // stopped when it gave none. Its pressure is accepted only if the constrained CG, started there, stops on its own
  // residual. It goes first: where it settles it costs tens of CG iterations, where the plain run spends the
  // thousands of its stall test first (a set that repeats, or 50 sets, stops it where it does not settle). With a
  // shift too: the contact-implicit step's solves, whose plain run mostly reaches their iteration limit and hands
  // the step back to the stepper for a smaller one (wear/implicit_stepper.hpp), which on such contacts shrank the
  // jump without end (docs/PERFORMANCE.md, "Wear near the stick limit").
  const std::vector<double> stalled = state.p;
  {
    const bool warm = std::any_of(start.begin(), start.end(), [](double p) { return p > 0.0; });
    std::vector<double> p = warm && int(start.size()) == kernel_.grid().n ? start : state.p;
    double g_min = kInf, g_max = -kInf;
    for (double g : g0)
      if (std::isfinite(g)) g_min = std::min(g_min, g), g_max = std::max(g_max, g);
    const double inner = kActiveSetGapError * options_.tolerance * std::max(g_max - g_min, kernel_.A() * P);
    int iterations = 0;
    if (ActiveSetSolve(kernel_, g0, P, shift)
            .run(p, inner, kMaxActiveSets, std::min(kMaxActiveSetIterations, options_.max_iterations),
                 options_.max_iterations, iterations)) {
      state.p = std::move(p);
      SolveSummary checked = iterate(g0, P, state, shift, true);
      checked.iterations += iterations;
      then(checked);
      if (checked.converged()) return total;
    } else {
      total.iterations += iterations;
    }
  }
  // The preconditioned iteration can stall where long stretches sit at zero gap and zero pressure (a worn
  // profile near its asymptote); plain constrained CG, warm-started from where it stopped, does not.
  state.p = stalled;
  const SolveSummary plain = iterate(g0, P, state, shift, false, kPlainStallIterations);
  then(plain);
  if (plain.converged() || plain.termination != Termination::max_iterations ||
      plain.iterations >= options_.max_iterations)  // converged, failed otherwise, or used every iteration
    return total;
  // A start far from the solution can defeat both: a stick zone a few cells wide standing proud of worn zones in
  // light contact, warm-started from a pressure spread over them. The preconditioned run moves the load onto the
  // stick zone too slowly and stalls, and the plain one re-enters the worn cells at −τ g, far past their share, and
  // cycles between two sets (regression_normal_solve_narrow_worn_contact.cpp). Then both run again from the cold
  // start, plain CG to the iteration limit.
  state.p.clear();
  then(iterate(g0, P, state, shift, true));
  if (total.converged()) return total;
  then(iterate(g0, P, state, shift, false));
  return total;
}

SolveSummary NormalSolver::iterate(std::span<const double> g0, double P, ContactState& state,
                                   std::span<const double> shift, bool use_preconditioner, int plain_stall) const {
  const auto t_start = std::chrono::steady_clock::now();
  SolveSummary summary;
  auto finish = [&](Termination t) {
    summary.termination = t;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return summary;
  };

  ConstrainedCg cg(kernel_, options_, g0, P, state, shift, use_preconditioner && preconditioned_);
  if (!cg.has_admissible_cell()) return finish(Termination::no_admissible_cell);
  cg.start();
  double best_residual = kInf;
  int best_iteration = 0;
  for (int it = 0;; ++it) {
    // The stopping test; a preconditioned run that stalls stops too, and solve() goes on without the preconditioner.
    summary.iterations = it;
    summary.residual = cg.residual(it >= options_.max_iterations);
    if (!std::isfinite(summary.residual)) return finish(Termination::non_finite);
    if (summary.residual <= options_.tolerance) return finish(Termination::converged);
    if (it >= options_.max_iterations) return finish(Termination::max_iterations);
    if (summary.residual < 0.5 * best_residual) best_residual = summary.residual, best_iteration = it;
    if (cg.preconditioned() && it - best_iteration > kStallIterations) return finish(Termination::max_iterations);
    if (!cg.preconditioned() && plain_stall > 0 && it - best_iteration > plain_stall)
      return finish(Termination::max_iterations);

    // One iteration: a CG step on the working set, then back onto p ≥ 0 and the load.
    cg.select_working_set();
    cg.conjugate_direction();
    const double tau = cg.step_length();
    if (!std::isfinite(tau)) return finish(Termination::non_finite);
    if (!cg.step(tau)) return finish(Termination::non_finite);
  }
}

}  // namespace fretwear
