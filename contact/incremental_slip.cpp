#include "contact/incremental_slip.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <utility>

#include <fmt/format.h>

#include "contact/contact_zones.hpp"
#include "contact/coupling_kernel.hpp"
#include "common/error.hpp"

namespace fretwear {

namespace {
constexpr int kMaxEvaluations = 200;  // force-control solves per displacement-controlled increment
constexpr double kMirrorTolerance = 1e-6;  // the odd part of a gap taken as even, relative to its largest value
constexpr double kSteadyTolerance = 1e-6;  // a cycle repeats the one before (Run::repeated), relative to the traction
}  // namespace

std::string IncrementalSlipOptions::validate() const {
  if (increments_per_cycle < 4 || increments_per_cycle % 4 != 0)
    return fmt::format("increments_per_cycle = {} must be a positive multiple of 4", increments_per_cycle);
  if (cycles < 1) return fmt::format("cycles = {} must be at least 1", cycles);
  if (!(tolerance > 0.0 && tolerance <= 1e-2))
    return fmt::format("tolerance = {} is outside (0, 1e-2]", tolerance);
  if (max_iterations < 1) return fmt::format("max_iterations = {} must be at least 1", max_iterations);
  if (!(coupling_tolerance > 0.0 && coupling_tolerance <= 1e-2))
    return fmt::format("coupling_tolerance = {} is outside (0, 1e-2]", coupling_tolerance);
  if (settling_increments < 0 || settling_increments % 4 != 0)
    return fmt::format("settling_increments = {} must be 0 or a positive multiple of 4", settling_increments);
  if (steady_cycles_max < 0) return fmt::format("steady_cycles_max = {} must be 0 or more", steady_cycles_max);
  if (max_coupling_sweeps < 1)
    return fmt::format("max_coupling_sweeps = {} must be at least 1", max_coupling_sweeps);
  if (auto msg = normal.validate(); !msg.empty()) return "normal." + msg;
  return {};
}

IncrementalSlipSolver::IncrementalSlipSolver(const HalfPlaneKernel& kernel, IncrementalSlipOptions options)
    : kernel_(kernel), options_(options) {
  if (auto msg = options_.validate(); !msg.empty()) throw InputError("incremental slip options: " + msg);
  if (options_.preconditioner == NormalSolverOptions::Preconditioner::symbol)
    preconditioned_ = !kernel_.inverse_spectrum().empty();
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

// The traction bounds ±f p of the pressure p: zero off the contact.
void traction_bounds(std::span<const double> p, double f, std::span<double> lo, std::span<double> hi) {
  for (std::size_t i = 0; i < hi.size(); ++i) {
    hi[i] = p[i] > 0.0 ? f * p[i] : 0.0;
    lo[i] = -hi[i];
  }
}

// The cells whose bound has closed (they left the contact) drop their traction, and u = K q follows.
void drop_separated(const HalfPlaneKernel& kernel, std::span<const double> hi, IncrementState& state) {
  bool dropped = false;
  for (std::size_t i = 0; i < hi.size(); ++i)
    if (hi[i] == 0.0 && state.q[i] != 0.0) state.q[i] = 0.0, dropped = true;
  if (dropped) kernel.apply(state.q, state.u);
}

}  // namespace

SolveSummary IncrementalSlipSolver::solve_increment(std::span<const double> p, double f, const SlipIncrement& inc,
                                                    IncrementState& state) const {
  const int n = kernel_.grid().n;
  std::vector<double> lo(n), hi(n);
  traction_bounds(p, f, lo, hi);
  if (int(state.q.size()) != n || int(state.u.size()) != n) {
    state.q.assign(n, 0.0);
    state.u.assign(n, 0.0);
  }
  const std::vector<double> u_prev = state.u;
  return solve_bounded(lo, hi, inc, u_prev, state);
}

SolveSummary IncrementalSlipSolver::solve_bounded(std::span<const double> lo, std::span<const double> hi,
                                                  const SlipIncrement& inc, std::span<const double> u_prev,
                                                  IncrementState& state) const {
  if (!preconditioned_) return iterate(lo, hi, inc, u_prev, state, false);
  const SolveSummary first = iterate(lo, hi, inc, u_prev, state, true);
  if (first.converged() || first.termination == Termination::no_admissible_cell) return first;
  // As in NormalSolver: plain constrained CG, warm-started from where the preconditioned run stalled.
  SolveSummary second = iterate(lo, hi, inc, u_prev, state, false);
  second.iterations += first.iterations;
  second.seconds += first.seconds;
  return second;
}

namespace {

// Relative: how far |Q| may exceed h Σ hi by round-off and still be carried (BoxConstrainedCg::feasible).
constexpr double kCapacityRoundOff = 1e-12;

// A preconditioned run that has not halved its best residual for this many iterations has stalled.
constexpr int kStallIterations = 200;

// One run of the header's constrained CG with two-sided bounds (after Polonsky and Keer 1999) for one increment: the
// traction q with u = K q (state, u carried from iterate to iterate), the KKT gradient g = Δs − λ and the conjugate
// direction t on the working set.
class BoxConstrainedCg {
 public:
  // Zeroes state.dw: no slip unless the increment converges.
  BoxConstrainedCg(const HalfPlaneKernel& kernel, std::span<const double> lo, std::span<const double> hi,
                   const SlipIncrement& inc, std::span<const double> u_prev, IncrementState& state,
                   bool preconditioned);

  bool preconditioned() const { return preconditioned_; }
  // Some cell can carry traction, and the bounds can carry |Q|: h Σ hi ≥ |Q|, but for round-off. At Q = ±f P (the
  // stick limit, where displacement control's search ends) the bounds f p of a coupled increment's pressure, which
  // its normal solve balances to P in floating point, may sum to f P less a few ulps; |Q| is then taken as h Σ hi.
  bool feasible() const { return last_ >= 0 && !(std::abs(inc_.Q) > capacity_ * (1.0 + kCapacityRoundOff)); }
  // The slip scale d, and a feasible start: the previous traction shifted uniformly (and clamped) to the new load.
  void start();
  // r of the stopping criterion, on an exact u whenever r could stop the run (`last`: the iteration limit is reached).
  double residual(double tolerance, bool last);
  // What a converged increment leaves: the slip Δw on the cells at a bound and the rigid shift λ.
  void record_slip();
  // The working set: the free cells and the bound cells the residual pulls inward; g on its load-neutral subspace.
  void select_working_set();
  // t = z + β t on the working set, z = g or its preconditioned form; β = 0 after a restart.
  void conjugate_direction();
  // τ = g·t / t·K t, with v = K t; NaN unless t·K t > 0.
  double step_length();
  // q ← the projection of q − τ t onto the box and the load over the working set; u follows.
  void step(double tau);

 private:
  // r = K (q − q_prev) + Δε x, λ its mean over the free cells, g = r − λ; returns the largest KKT violation over d.
  double kkt_residual();

  const HalfPlaneKernel& kernel_;
  const Grid& grid_;
  const std::span<const double> lo_, hi_, u_prev_;
  const SlipIncrement& inc_;
  IncrementState& state_;
  std::vector<double>& q_;
  std::vector<double>& u_;
  const bool preconditioned_;
  const int n_;
  const double h_;
  std::vector<char> contact_;     // hi > 0: the cells that can carry traction
  int first_ = 0, last_ = -1;     // the first and the last of them
  double capacity_ = 0.0;         // h Σ hi (N/m)
  double d_eps_ = 0.0;            // ε − ε_prev
  double d_ = 0.0;                // the slip scale of the stopping criterion (m)
  double target_ = 0.0;           // Σ q = Q / h
  std::vector<char> work_, work_old_;  // the working set, now and at the last iteration
  std::vector<double> r_, g_, t_, v_, z_, y_;
  bool u_exact_ = true;
  double rz_old_ = 1.0;           // g·z of the previous direction
  double lambda_ = 0.0;           // λ: the multiplier of the load (m)
  bool restart_ = true;           // the next direction is a steepest-descent one
  int n_work_ = 0;
};

BoxConstrainedCg::BoxConstrainedCg(const HalfPlaneKernel& kernel, std::span<const double> lo,
                                   std::span<const double> hi, const SlipIncrement& inc,
                                   std::span<const double> u_prev, IncrementState& state, bool preconditioned)
    : kernel_(kernel),
      grid_(kernel.grid()),
      lo_(lo),
      hi_(hi),
      u_prev_(u_prev),
      inc_(inc),
      state_(state),
      q_(state.q),
      u_(state.u),
      preconditioned_(preconditioned),
      n_(grid_.n),
      h_(grid_.h()),
      contact_(n_),
      work_(n_, 0),
      work_old_(n_, 0),
      r_(n_, 0.0),
      g_(n_, 0.0),
      t_(n_, 0.0),
      v_(n_),
      z_(n_),
      y_(n_) {
  first_ = n_;
  for (int i = 0; i < n_; ++i) {
    contact_[i] = hi_[i] > 0.0;
    if (contact_[i]) first_ = std::min(first_, i), last_ = i, capacity_ += h_ * hi_[i];
  }
  state_.dw.assign(n_, 0.0);
  state_.dw_touching.assign(n_, 0.0);
}

void BoxConstrainedCg::start() {
  d_eps_ = inc_.bulk_strain - inc_.bulk_strain_prev;
  const double half_span = 0.5 * (grid_.x(last_) - grid_.x(first_) + h_);
  d_ = kernel_.A() * std::abs(inc_.Q - inc_.Q_prev) + std::abs(d_eps_) * half_span;
  if (!(d_ > 0.0)) d_ = kernel_.A() * capacity_;  // nothing changes: measure against the contact's own scale
  target_ = std::clamp(inc_.Q, -capacity_, capacity_) / h_;
  const std::vector<double> y = q_;
  if (project(y, lo_, hi_, contact_, target_, q_)) kernel_.apply(q_, u_);
  u_exact_ = true;
}

double BoxConstrainedCg::residual(double tolerance, bool last) {
  double r = kkt_residual();
  // Stop only on an exact u: recompute K q once the carried one says converged (or at the last iteration).
  while (!u_exact_ && (r <= tolerance || last)) {
    kernel_.apply(q_, u_);
    u_exact_ = true;
    r = kkt_residual();
  }
  return r;
}

double BoxConstrainedCg::kkt_residual() {
  double r_free = 0.0, r_upper = -std::numeric_limits<double>::infinity(), r_lower = -r_upper;
  int n_free = 0;
  for (int i = 0; i < n_; ++i) {
    if (!contact_[i]) continue;
    r_[i] = u_[i] - u_prev_[i] + d_eps_ * grid_.x(i);
    if (q_[i] >= hi_[i]) {
      r_upper = std::max(r_upper, r_[i]);
    } else if (q_[i] <= lo_[i]) {
      r_lower = std::min(r_lower, r_[i]);
    } else {
      r_free += r_[i];
      ++n_free;
    }
  }
  if (n_free > 0) {
    lambda_ = r_free / n_free;
  } else {  // every cell at a bound: any λ in [max over q = +fp, min over q = −fp] satisfies the KKT conditions
    lambda_ = std::isfinite(r_upper) && std::isfinite(r_lower) ? 0.5 * (r_upper + r_lower)
              : std::isfinite(r_upper)                         ? r_upper
                                                               : r_lower;
  }
  double violation = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (!contact_[i]) continue;
    g_[i] = r_[i] - lambda_;
    const double vi = q_[i] >= hi_[i]   ? std::max(g_[i], 0.0)
                      : q_[i] <= lo_[i] ? std::max(-g_[i], 0.0)
                                        : std::abs(g_[i]);
    violation = std::max(violation, vi);
  }
  return violation / d_;
}

// Δw = −Δs on the cells at a bound; the cells that stick do not slip, nor does a bound cell whose residual points
// inward by less than the tolerance (it is taken as sticking, so that q Δw ≥ 0 holds exactly).
// Off the contact u = K q is exact on every cell (residual() stops on an exact u), so −(Δs − λ) is that cell's
// relative tangential displacement over the increment.
void BoxConstrainedCg::record_slip() {
  for (int i = 0; i < n_; ++i) {
    if (!contact_[i]) {
      state_.dw_touching[i] = -(u_[i] - u_prev_[i] + d_eps_ * grid_.x(i) - lambda_);
      continue;
    }
    if (q_[i] >= hi_[i]) state_.dw[i] = std::max(-g_[i], 0.0);
    else if (q_[i] <= lo_[i]) state_.dw[i] = std::min(-g_[i], 0.0);
    state_.dw_touching[i] = state_.dw[i];
  }
  state_.shift = lambda_;
}

void BoxConstrainedCg::select_working_set() {
  n_work_ = 0;
  double g_sum = 0.0;
  for (int i = 0; i < n_; ++i) {
    work_[i] = contact_[i] && ((q_[i] < hi_[i] && q_[i] > lo_[i]) || (q_[i] >= hi_[i] && g_[i] > 0.0) ||
                               (q_[i] <= lo_[i] && g_[i] < 0.0));
    if (work_[i]) g_sum += g_[i], ++n_work_;
    restart_ = restart_ || work_[i] != work_old_[i];  // a new set restarts CG
  }
  work_old_ = work_;
  const double g_mean = g_sum / n_work_;
  for (int i = 0; i < n_; ++i) g_[i] = work_[i] ? g_[i] - g_mean : 0.0;
}

void BoxConstrainedCg::conjugate_direction() {
  if (preconditioned_) {
    kernel_.fft().apply_spectrum(kernel_.inverse_spectrum(), g_, z_);
    double z_sum = 0.0;
    for (int i = 0; i < n_; ++i)
      if (work_[i]) z_sum += z_[i];
    for (int i = 0; i < n_; ++i) z_[i] = work_[i] ? z_[i] - z_sum / n_work_ : 0.0;
  } else {
    z_ = g_;
  }
  double rz = 0.0;
  for (int i = 0; i < n_; ++i)
    if (work_[i]) rz += g_[i] * z_[i];
  const double beta = restart_ ? 0.0 : rz / rz_old_;
  for (int i = 0; i < n_; ++i) t_[i] = work_[i] ? z_[i] + beta * t_[i] : 0.0;
  rz_old_ = rz;
}

double BoxConstrainedCg::step_length() {
  kernel_.apply(t_, v_);
  double num = 0.0, den = 0.0;
  for (int i = 0; i < n_; ++i) {
    if (work_[i]) {
      num += g_[i] * t_[i];
      den += v_[i] * t_[i];  // Σ t = 0 on the working set: no mean of v to remove
    }
  }
  return den > 0.0 ? num / den : std::numeric_limits<double>::quiet_NaN();
}

void BoxConstrainedCg::step(double tau) {
  double fixed = 0.0;
  for (int i = 0; i < n_; ++i) {
    y_[i] = work_[i] ? q_[i] - tau * t_[i] : q_[i];
    if (contact_[i] && !work_[i]) fixed += q_[i];
  }
  const bool clamped = project(y_, lo_, hi_, work_, target_ - fixed, q_);
  if (clamped) {
    kernel_.apply(q_, u_);
    u_exact_ = true;
  } else {
    for (int i = 0; i < n_; ++i) u_[i] -= tau * v_[i];
    u_exact_ = false;
  }
  restart_ = clamped;  // a cell that hit a bound restarts CG
}

}  // namespace

SolveSummary IncrementalSlipSolver::iterate(std::span<const double> lo, std::span<const double> hi,
                                            const SlipIncrement& inc, std::span<const double> u_prev,
                                            IncrementState& state, bool use_preconditioner) const {
  const auto t_start = std::chrono::steady_clock::now();
  SolveSummary summary;
  auto finish = [&](Termination t) {
    summary.termination = t;
    summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_start).count();
    return summary;
  };

  BoxConstrainedCg cg(kernel_, lo, hi, inc, u_prev, state, use_preconditioner && preconditioned_);
  if (!cg.feasible()) return finish(Termination::no_admissible_cell);  // no cell, or beyond f P: no feasible q
  cg.start();
  double best_residual = std::numeric_limits<double>::infinity();
  int best_iteration = 0;
  for (int it = 0;; ++it) {
    // The stopping test; a preconditioned run that stalls stops too, and solve_bounded() goes on without it.
    summary.iterations = it;
    summary.residual = cg.residual(options_.tolerance, it >= options_.max_iterations);
    if (!std::isfinite(summary.residual)) return finish(Termination::non_finite);
    if (summary.residual <= options_.tolerance) {
      cg.record_slip();
      return finish(Termination::converged);
    }
    if (it >= options_.max_iterations) return finish(Termination::max_iterations);
    if (summary.residual < 0.5 * best_residual) best_residual = summary.residual, best_iteration = it;
    if (cg.preconditioned() && it - best_iteration > kStallIterations) return finish(Termination::max_iterations);

    // One iteration: a CG step on the working set, then the projection onto the box and the load over it.
    cg.select_working_set();
    cg.conjugate_direction();
    const double tau = cg.step_length();
    if (!std::isfinite(tau)) return finish(Termination::non_finite);
    cg.step(tau);
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

// One increment's slip Δw added to the cycle's bookkeeping: the slip w per cell, its extremes, the slip travelled
// and the energy density q Δw (q at the end of the increment).
void accumulate_slip(const IncrementState& state, std::vector<double>& w, std::vector<double>& w_min,
                     std::vector<double>& w_max, CycleResult& r) {
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double dw = state.dw[i];
    if (dw == 0.0) continue;
    w[i] += dw;
    w_min[i] = std::min(w_min[i], w[i]);
    w_max[i] = std::max(w_max[i], w[i]);
    r.slip_travelled[i] += std::abs(dw);
    r.energy_density[i] += state.q[i] * dw;
  }
  for (std::size_t i = 0; i < w.size(); ++i) r.slip_if_touching[i] += std::abs(state.dw_touching[i]);
}

// What a marched cycle leaves besides its tractions: per cell the slip range (w_max − w_min over the cycle), the
// largest of them and the energy ∫ energy_density dx; the stick zones at the top of the cycle (bounds hi_top) and
// at the unloaded phase (bounds hi_unloaded).
void close_cycle(const Grid& grid, std::span<const double> w_max, std::span<const double> w_min,
                 std::span<const double> hi_top, std::span<const double> hi_unloaded, CycleResult& r) {
  const int n = grid.n;
  const std::vector<double> no_corners(n, 0.0);  // a stick zone never ends at a corner of the pad
  r.slip_range.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    r.slip_range[i] = w_max[i] - w_min[i];
    r.slip_max = std::max(r.slip_max, r.slip_range[i]);
    r.dissipated_energy += grid.h() * r.energy_density[i];
  }
  const auto stick = locate_zones(grid, stick_margin(hi_top, r.q_top), no_corners);
  for (const Zone& z : stick) r.stick_zones.emplace_back(z.left.x, z.right.x);
  if (!stick.empty()) r.stick_zone = Interval{stick.front().left.x, stick.back().right.x};
  const auto stick_unloaded = locate_zones(grid, stick_margin(hi_unloaded, r.q_unloaded), no_corners);
  if (!stick_unloaded.empty())
    r.stick_zone_unloaded = Interval{stick_unloaded.front().left.x, stick_unloaded.back().right.x};
}

// The run's one cycle when the load reaches |Q| ≥ f P under force control: gross slip, without fields.
IncrementalResult gross_slip(std::string message) {
  IncrementalResult result;
  CycleResult r;
  r.regime = Regime::gross_slip;
  r.message = std::move(message);
  result.cycles.push_back(std::move(r));
  return result;
}

// Where an increment sits in the run, for messages: "the first loading, increment k" or "cycle c, increment k".
std::string where(int cycle, int k) {
  const std::string when = cycle == 0 ? std::string("the first loading,") : fmt::format("cycle {},", cycle);
  return fmt::format("{} increment {}", when, k);
}

}  // namespace

// What solve() and solve_history() share: the traction carried from increment to increment, the rigid shift λ summed
// over the increments with the fretting loop δ = λ + D(q, p) − D(0, p) − ε x_c it gives (with a datum), the slip of
// the cycle being marched, and the result's counts.
class IncrementalSlipSolver::Run {
 public:
  IncrementalResult result() { return std::move(result_); }
  // True when the last cycle's traction at its top and its bottom repeats the cycle's before it, each cell within
  // kSteadyTolerance of the larger top traction: the march has reached its steady cycle.
  bool repeated() const {
    const auto& c = result_.cycles;
    if (c.size() < 2) return false;
    const CycleResult &a = c[c.size() - 2], &b = c.back();
    if (a.q_top.size() != b.q_top.size() || a.q_bottom.size() != b.q_bottom.size()) return false;
    double scale = 0.0, change = 0.0;
    for (std::size_t i = 0; i < b.q_top.size(); ++i)
      scale = std::max({scale, std::abs(a.q_top[i]), std::abs(b.q_top[i])});
    for (std::size_t i = 0; i < b.q_top.size(); ++i) change = std::max(change, std::abs(b.q_top[i] - a.q_top[i]));
    for (std::size_t i = 0; i < b.q_bottom.size(); ++i)
      change = std::max(change, std::abs(b.q_bottom[i] - a.q_bottom[i]));
    return change <= kSteadyTolerance * scale;
  }
  // True when the last cycle ended in the state it began in: its traction at the end within kSteadyTolerance of the
  // larger top traction of the one at its start. The next cycle, marched from that state through the same loads,
  // would then repeat it: the march has reached its steady cycle a cycle before repeated() can tell. (The traction is
  // the state: u = K q, and the pressure follows from q and the load.)
  bool closed() const {
    const auto& c = result_.cycles;
    if (c.empty() || cycle_start_q_.size() != state_.q.size()) return false;
    double scale = 0.0, change = 0.0;
    for (double v : c.back().q_top) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < state_.q.size(); ++i)
      change = std::max(change, std::abs(state_.q[i] - cycle_start_q_[i]));
    return change <= kSteadyTolerance * scale;
  }

 protected:
  Run(const IncrementalSlipSolver& solver, const ContactState& contact, const ReferenceDatum* datum,
      const NormalCoupling* coupling);
  virtual ~Run() = default;

  // The loads at the end of the last increment, and δ there (needs the datum).
  virtual LoopPoint loop_point() const = 0;
  // δ at the end of the last increment under the pressure p and the bulk strain eps.
  double delta(std::span<const double> p, double eps) const;
  // An increment's solve counted into the result: increments, CG iterations and the worst residual.
  void count(const SolveSummary& s);
  // A cycle before its first increment: no slip yet; with a datum the first loading and the loop's first point.
  CycleResult begin_cycle();
  // The end of an increment within the cycle: the largest |Q|, the loop point and the slip.
  void end_increment(CycleResult& r, double Q);
  // β ≠ 0: the increment by block Gauss–Seidel sweeps between the normal problem under the load P and the tangential
  // one with the bounds ±f p, from the pressure p and state_ (the increment's start); p, lo, hi and state_ end as
  // the increment's end. Returns the tangential solves' summary (not converged: the caller throws).
  SolveSummary coupled_increment(double P, double f, const SlipIncrement& inc, std::vector<double>& p,
                                 std::vector<double>& lo, std::vector<double>& hi, int cycle, int k);

  const IncrementalSlipSolver& solver_;
  const HalfPlaneKernel& kernel_;
  const IncrementalSlipOptions& options_;
  const Grid& grid_;
  const int n_;
  const double h_;
  const ReferenceDatum* datum_;
  const double D0_;             // D(0, p) under the contact's pressure (m)
  IncrementState state_;        // q and u = K q at the end of the last increment, zero before the first
  double shift_ = 0.0;          // λ summed over the increments (m)
  std::vector<LoopPoint> first_loading_;
  std::vector<double> w_, w_min_, w_max_;  // the slip per cell over the cycle being marched, and its extremes (m)
  std::vector<double> cycle_start_q_;      // the traction the cycle being marched began from (Pa)
  IncrementalResult result_;
  const NormalCoupling* coupling_;
  const bool coupled_;          // β ≠ 0
  const CouplingKernel S_;
  const NormalSolver coupled_normal_;  // the normal solves of the coupled increments
  const double A_beta_;
  ContactState normal_state_;   // the last coupled normal solve: the next one's warm start
  // The last coupled increment's changes of q and p (Pa) and its load steps: the next one's predicted start.
  std::vector<double> dq_last_, dp_last_;
  double dQ_last_ = 0.0, P_last_ = 0.0, d_eps_last_ = 0.0;

 private:
  // A sweep's normal half: p for the gap g0 − A β S q under the load P, warm-started from the last p.
  void coupled_pressure(std::span<const double> q, double P, const SlipIncrement& inc, std::vector<double>& p,
                        int cycle, int k);
  // A sweep's tangential half: q with the bounds ±f p and the coupling slip A β S (p − p_prev) of the pressure.
  SolveSummary coupled_traction(double f, const SlipIncrement& inc, std::span<const double> p,
                                std::span<const double> p_prev, std::span<const double> u_prev,
                                std::vector<double>& lo, std::vector<double>& hi, IncrementState& trial);
};

// solve(): under constant P the controlled quantity x (Q, or δ under displacement control) cycles 0 → +X → −X → +X
// and the bulk strain follows it; with β ≠ 0 the pressure moves with the shear.
class IncrementalSlipSolver::AmplitudeRun : public Run {
 public:
  AmplitudeRun(const IncrementalSlipSolver& solver, const ContactState& contact, const CyclicLoad& load,
               const ReferenceDatum* datum, const NormalCoupling* coupling);
  // The first loading, 0 → X, in a quarter of a cycle's increments.
  void first_loading();
  // One steady cycle, top to top, into the result.
  void cycle(int c);

 private:
  // The search for the Q of one displacement-controlled increment.
  struct DeltaSearch {
    DeltaSearch(double target, double strain, double strain_prev, int in_cycle, int increment,
                const IncrementState& from, const std::vector<double>& p_from)
        : x_t(target),
          eps_t(strain),
          eps_0(strain_prev),
          cycle(in_cycle),
          k(increment),
          start(from),
          trial(from),
          p_start(p_from) {}
    double x_t, eps_t, eps_0;     // the target δ (m); the bulk strain at the increment's end and at its start
    int cycle, k;
    IncrementState start, trial;  // the increment's start; the solve of the last evaluation
    std::vector<double> p_start;  // the pressure at the increment's start (it moves only when β ≠ 0)
    SolveSummary total;           // the solves so far, summed
    int evaluations = 0;
    double last = 0.0;            // Q of the last evaluation (N/m)
  };

  LoopPoint loop_point() const override { return {P_, Q_prev_, delta_now()}; }
  double strain_at(double x) const { return X_ > 0.0 ? bulk_strain_ * x / X_ : 0.0; }
  double delta_now() const { return delta(p_, strain_at(x_prev_)); }
  // The increment to x_t, solved and recorded.
  SolveSummary step(double x_t, int cycle, int k);
  // Throws ConvergenceError naming the increment if s did not converge.
  void check(const SolveSummary& s, int cycle, int k, double Qt) const;
  // Displacement control: the Q whose force-controlled increment gives δ(Q) = x_t, and its solves.
  std::pair<double, SolveSummary> displacement_increment(double x_t, int cycle, int k);
  // δ(Q) − x_t: the force-controlled increment to Q from the increment's start, warm-started from the last evaluation.
  double delta_miss(DeltaSearch& search, double Q);
  // Q accepted: the state holds its solve (an end of the bracket is solved again if another was evaluated since).
  std::pair<double, SolveSummary> accept(DeltaSearch& search, double Q);
  // Q = ±f P with δ still short of the target by −miss: the bodies slide rigidly by the rest (extra_).
  double slide(double Q_bound, double miss);
  // The Illinois false position on the bracket [a, b] of δ(Q) − x_t, to |δ(Q) − x_t| ≤ tol.
  std::pair<double, SolveSummary> false_position(DeltaSearch& search, double a, double fa, double b, double fb,
                                                 double tol);
  // Gross slip where the bodies slid rigidly beyond the stick limit, reverse slip where some cell is held at −f p at
  // the top of the cycle.
  void classify(CycleResult& r, double sliding) const;
  // Whether the last cycle may take its reloading half as the mirror image of its unloading half (the header).
  bool mirrors() const;
  // After the unloading half of cycle r from the state top and the pressure p_top: the reloading half as its mirror
  // image, back at that top.
  void mirror_reloading(CycleResult& r, std::size_t first_loop_point, IncrementState top, std::vector<double> p_top);

  const double f_, P_, bulk_strain_;
  const bool displacement_;
  const double X_;              // the amplitude of x: Q (N/m) or δ (m)
  const int m_;
  const int m_settle_;          // increments per cycle before the last (settling_increments)
  std::vector<double> p_;       // the pressure (Pa); it moves over the cycle only when β ≠ 0
  std::vector<double> lo_, hi_;
  bool mirror_ = false;         // the last cycle's reloading half mirrored (mirrors())
  double capacity_ = 0.0;       // f P on the grid, summed as iterate() sums it (N/m)
  double Q_prev_ = 0.0, x_prev_ = 0.0;  // at the end of the last increment
  double extra_ = 0.0;          // the rigid sliding of the last increment beyond the stick limit (m)
  double compliance_;           // dδ/dQ of the last increment (m²/N): the first guess of the next one's Q
};

// solve_history(): force control through the points of a load history, the pressure that of the normal problem at
// each increment's P.
class IncrementalSlipSolver::HistoryRun : public Run {
 public:
  HistoryRun(const IncrementalSlipSolver& solver, const ContactState& contact, const CyclicLoad& load,
             std::span<const double> g0, const ReferenceDatum* datum, const NormalCoupling* coupling);
  // The first loading, from Q = 0, ε = 0 under the contact's P to the first point, in m/4 increments.
  void first_loading();
  // One steady cycle through the points into the result.
  void cycle(int c);

 private:
  struct Target {  // the loads at the end of an increment
    double P, Q, eps;
  };

  friend class IncrementalSlipSolver;  // history_increments_at_most() splits a history as the march does

  LoopPoint loop_point() const override { return {prev_.P, prev_.Q, delta(p_now_, prev_.eps)}; }
  // The increments of one cycle and its phases, as indices into them.
  struct Cycle {
    std::vector<Target> targets;
    int top = 0, bottom = 0, unloaded = 0, reloaded = 0;
  };
  // The first loading's increments: m/4 equal steps to the first point.
  void split_first_loading(const HistoryPoint& first, int m);
  // Each segment of the history split into ⌈m Δt / T⌉ equal steps; the phases: top and bottom at the largest and the
  // smallest Q, unloaded and reloaded where Q first crosses their mean after each.
  static Cycle split(const std::vector<HistoryPoint>& H, int m);
  // The pressure under P: one normal solve per distinct P, warm-started from the nearest P solved.
  const std::vector<double>& pressure_at(double P);
  // The increment to t, solved and recorded.
  SolveSummary step(const Target& t, int cycle, int k);

  const double f_;
  const int m_;
  const std::span<const double> g0_;
  const NormalSolver normal_;
  double P0_ = 0.0;             // h Σ p of the contact (N/m)
  std::map<double, std::vector<double>> pressures_;
  std::vector<Target> first_;
  Cycle settling_, steady_;     // the cycles before the last (settling_increments), and the last
  std::vector<double> lo_, hi_, p_now_;
  Target prev_;                 // the loads at the end of the last increment
};

IncrementalResult IncrementalSlipSolver::solve(const ContactState& contact, const CyclicLoad& load,
                                               const ReferenceDatum* datum, const NormalCoupling* coupling) const {
  const int n = kernel_.grid().n;
  const double f = load.f, P = load.P, Q = load.Q_max;
  const bool displacement = load.delta > 0.0;
  if (!load.history.empty()) throw InputError("incremental slip: a load history is solved by solve_history()");
  if (displacement && !datum)
    throw InputError("incremental slip: displacement control needs a reference datum (the δ it prescribes)");
  const bool coupled = coupling && coupling->beta != 0.0;
  if (coupled && int(coupling->g0.size()) != n)
    throw InputError("incremental slip: the coupled solve needs the initial gap on the grid");
  if (!displacement && Q >= f * P)
    return gross_slip(fmt::format("Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and under force "
                                  "control the slip is not determined",
                                  Q, f * P));

  AmplitudeRun run(*this, contact, load, datum, coupling);
  run.first_loading();
  for (int cycle = 1; cycle <= options_.cycles; ++cycle) run.cycle(cycle);
  return run.result();
}

IncrementalResult IncrementalSlipSolver::solve_history(const ContactState& contact, const CyclicLoad& load,
                                                       std::span<const double> g0, const ReferenceDatum* datum,
                                                       const NormalCoupling* coupling) const {
  const auto& H = load.history;
  if (H.size() < 2 || int(g0.size()) != kernel_.grid().n)
    throw InputError("incremental slip: a load history needs two points or more and the initial gap on the grid");
  // Gross slip anywhere in the history: as under force control, the slip is not determined.
  for (const HistoryPoint& pt : H)
    if (std::abs(pt.Q) >= load.f * pt.P)
      return gross_slip(fmt::format("the load history reaches |Q| = {:.6g} N/m >= f P = {:.6g} N/m at t = {:.6g}: "
                                    "the bodies slide, and under force control the slip is not determined",
                                    std::abs(pt.Q), load.f * pt.P, pt.t));

  if (coupling && coupling->beta != 0.0 && int(coupling->g0.size()) != kernel_.grid().n)
    throw InputError("incremental slip: the coupled solve needs the initial gap on the grid");
  HistoryRun run(*this, contact, load, g0, datum, coupling);
  run.first_loading();
  int cycle = 1;
  for (; cycle <= options_.cycles; ++cycle) run.cycle(cycle);
  // A history may reach its steady cycle only after several (one that shakes down slips in its first cycle alone):
  // cycles are marched until one repeats the cycle before it, at most steady_cycles_max in all. A cycle marched at
  // settling_increments is not compared with one at increments_per_cycle.
  const bool settles_coarser = options_.cycles > 1 && options_.settling_increments > 0 &&
                               options_.settling_increments != options_.increments_per_cycle;
  // The last cycle of the loop above was marched at increments_per_cycle, as every later one is: one that ended
  // where it began is steady (Run::closed) whatever came before it.
  const auto comparable = [&] { return !settles_coarser || cycle - 2 >= options_.cycles; };
  bool repeated = true;
  if (options_.steady_cycles_max > 0)
    while (!(repeated = run.closed() || (comparable() && run.repeated())) && cycle <= options_.steady_cycles_max)
      run.cycle(cycle++);
  IncrementalResult result = run.result();
  result.repeated = repeated;
  result.cycles_marched = cycle - 1;
  return result;
}

int IncrementalSlipSolver::history_increments_at_most(const IncrementalSlipOptions& options,
                                                      const std::vector<HistoryPoint>& history) {
  if (history.size() < 2) return 0;
  const int m = options.increments_per_cycle;
  const int m_settle = options.cycles > 1 && options.settling_increments > 0 ? options.settling_increments : m;
  const int cycles = std::max(options.cycles, options.steady_cycles_max);
  const int settling = int(HistoryRun::split(history, m_settle).targets.size());
  const int steady = int(HistoryRun::split(history, m).targets.size());
  return m_settle / 4 + (options.cycles - 1) * settling + (cycles - options.cycles + 1) * steady;
}

IncrementalSlipSolver::Run::Run(const IncrementalSlipSolver& solver, const ContactState& contact,
                                const ReferenceDatum* datum, const NormalCoupling* coupling)
    : solver_(solver),
      kernel_(solver.kernel_),
      options_(solver.options_),
      grid_(kernel_.grid()),
      n_(grid_.n),
      h_(grid_.h()),
      datum_(datum),
      D0_(datum ? datum->relative_displacement(std::vector<double>(n_, 0.0), contact.p) : 0.0),
      coupling_(coupling),
      coupled_(coupling && coupling->beta != 0.0),
      S_(grid_),
      coupled_normal_(kernel_, options_.normal),
      A_beta_(coupled_ ? kernel_.A() * coupling->beta : 0.0) {
  state_.q.assign(n_, 0.0);
  state_.u.assign(n_, 0.0);
  normal_state_.p = contact.p;
}

double IncrementalSlipSolver::Run::delta(std::span<const double> p, double eps) const {
  return shift_ + datum_->relative_displacement(state_.q, p) - D0_ - eps * datum_->x_c();
}

void IncrementalSlipSolver::Run::count(const SolveSummary& s) {
  ++result_.n_increments;
  result_.n_iterations += s.iterations;
  if (!(s.residual <= result_.worst.residual) || result_.n_increments == 1) result_.worst = s;
  if (options_.after_increment) options_.after_increment(result_.n_increments);
}

CycleResult IncrementalSlipSolver::Run::begin_cycle() {
  CycleResult r;
  cycle_start_q_ = state_.q;
  w_.assign(n_, 0.0);
  w_min_.assign(n_, 0.0);
  w_max_.assign(n_, 0.0);
  r.slip_travelled.assign(n_, 0.0);
  r.slip_if_touching.assign(n_, 0.0);
  r.energy_density.assign(n_, 0.0);
  if (datum_) {
    r.first_loading = first_loading_;
    r.loop.push_back(loop_point());
  }
  return r;
}

void IncrementalSlipSolver::Run::end_increment(CycleResult& r, double Q) {
  r.Q_peak = std::max(r.Q_peak, std::abs(Q));
  if (datum_) {
    r.loop.push_back(loop_point());
    r.delta_max = std::max(r.delta_max, std::abs(r.loop.back().delta));
  }
  accumulate_slip(state_, w_, w_min_, w_max_, r);
}

IncrementalSlipSolver::AmplitudeRun::AmplitudeRun(const IncrementalSlipSolver& solver, const ContactState& contact,
                                                  const CyclicLoad& load, const ReferenceDatum* datum,
                                                  const NormalCoupling* coupling)
    : Run(solver, contact, datum, coupling),
      f_(load.f),
      P_(load.P),
      bulk_strain_(load.bulk_strain),
      displacement_(load.delta > 0.0),
      X_(displacement_ ? load.delta : load.Q_max),
      m_(options_.increments_per_cycle),
      m_settle_(options_.settling_increments > 0 ? options_.settling_increments : m_),
      p_(contact.p),
      lo_(n_),
      hi_(n_),
      compliance_(kernel_.A()) {
  traction_bounds(p_, f_, lo_, hi_);
  for (int i = 0; i < n_; ++i)
    if (hi_[i] > 0.0) capacity_ += h_ * hi_[i];
  mirror_ = mirrors();
}

// The equations are unchanged by x → −x with q → −q and Q → −Q (δ → −δ under displacement control) when the gap is
// even in x, no bulk strain (odd in Q, even in x) is applied and the datum's reference points lie on x = 0; the
// grid's cells then pair as i ↔ n − 1 − i. A worn gap is even only as far as the solves that wore it (their
// pressure is even to their tolerance, about 1e-6 of its peak): the gap is taken as even where its odd part is within
// kMirrorTolerance = 1e-6 of its largest value, and the cycle on it is then that of the even gap to within about as
// much, below the asymmetry the mirror neglects anyway (the header).
bool IncrementalSlipSolver::AmplitudeRun::mirrors() const {
  if (!options_.mirror_half_cycle || !coupled_ || bulk_strain_ != 0.0) return false;
  const double width = grid_.x_max - grid_.x_min;
  if (std::abs(grid_.x_min + grid_.x_max) > 1e-12 * width) return false;
  if (displacement_ && std::abs(datum_->x_c()) > 1e-12 * width) return false;
  const std::span<const double> g = coupling_->g0;
  double largest = 0.0, odd = 0.0;
  for (int i = 0; i < n_; ++i) {
    const double a = g[i], b = g[n_ - 1 - i];
    if (std::isfinite(a) != std::isfinite(b)) return false;
    if (!std::isfinite(a)) continue;
    largest = std::max(largest, std::abs(a));
    odd = std::max(odd, std::abs(a - b));
  }
  return odd <= kMirrorTolerance * largest;
}

void IncrementalSlipSolver::AmplitudeRun::first_loading() {
  if (datum_) first_loading_.push_back({P_, 0.0, 0.0});
  const int m = options_.cycles > 1 ? m_settle_ : m_;
  for (int k = 1; k <= m / 4; ++k) {
    step(X_ * (4.0 * k / m), 0, k);
    if (datum_) first_loading_.push_back(loop_point());
  }
}

void IncrementalSlipSolver::AmplitudeRun::cycle(int c) {
  CycleResult r = begin_cycle();
  r.Q_peak = std::abs(Q_prev_);  // the cycle starts at its top
  double sliding = 0.0;          // rigid sliding beyond the stick limit over the cycle (m)
  std::vector<double> hi_unloaded = hi_;
  bool sliding_unloaded = false;  // the bodies slide rigidly through the unloaded phase (δ = 0): no cell sticks
  const int m = c < options_.cycles ? m_settle_ : m_;
  const bool half = mirror_ && c == options_.cycles;
  const std::size_t loop_start = r.loop.size();
  IncrementState top = half ? state_ : IncrementState{};  // the steady top the half cycle starts from
  std::vector<double> p_top = half ? p_ : std::vector<double>{};
  for (int j = 1; j <= (half ? m / 2 : m); ++j) {
    // +X → −X over the first half, −X → +X over the second; 0, −X, 0 and +X fall exactly on increment ends.
    const double xt = 2 * j <= m ? X_ * (1.0 - 4.0 * j / m) : X_ * (-1.0 + 4.0 * (j - m / 2) / m);
    r.solves.push_back(step(xt, c, j));
    sliding += std::abs(extra_);
    end_increment(r, Q_prev_);
    if (4 * j == m) r.q_unloaded = state_.q, hi_unloaded = hi_, sliding_unloaded = extra_ != 0.0;
    if (2 * j == m) {
      r.q_bottom = state_.q;
      if (coupled_) result_.p_bottom = p_;
    }
    if (4 * j == 3 * m) r.q_reloaded = state_.q;
  }
  if (half) {
    mirror_reloading(r, loop_start, std::move(top), std::move(p_top));
    sliding *= 2.0;  // the reloading half slides as the unloading half did
  }
  if (coupled_) result_.p_top = p_;
  r.q_top = state_.q;
  close_cycle(grid_, w_max_, w_min_, hi_, hi_unloaded, r);
  // Sliding, every cell sits at |q| = f p; the margin f p − |q| is then zero but for round-off, which must not pass
  // for a stick zone.
  if (sliding_unloaded) r.stick_zone_unloaded.reset();
  classify(r, sliding);
  result_.cycles.push_back(std::move(r));
}

// The unloading half has left in w_ the slip W(x) at the bottom and in w_min_, w_max_ its extremes. The reloading
// half slips at x as the unloading half did at −x, reversed: w(x, t) = W(x) − w_u(−x, t), so over it w(x) reaches
// W(x) − w_min,u(−x) and W(x) − w_max,u(−x); its slip travelled and energy are those of −x; its loop points are the
// unloading's with Q and δ reversed. It ends at the bottom mirrored, q(x) = −q_bottom(−x), which is the top the half
// cycle started from but for what the first loading left locked in at the stick zone's edges (about 2e-3 p0 there;
// the header): the cycle reports that start, the steady top as a full march reaches it, as its top.
void IncrementalSlipSolver::AmplitudeRun::mirror_reloading(CycleResult& r, std::size_t first_loop_point,
                                                           IncrementState top, std::vector<double> p_top) {
  const auto mirror = [n = n_](int i) { return n - 1 - i; };
  const std::vector<double> e = r.energy_density, travelled = r.slip_travelled, w_min = w_min_, w_max = w_max_;
  const std::vector<double> touching = r.slip_if_touching;
  r.q_reloaded.resize(std::size_t(n_));
  for (int i = 0; i < n_; ++i) {
    r.energy_density[i] += e[mirror(i)];
    r.slip_travelled[i] += travelled[mirror(i)];
    r.slip_if_touching[i] += touching[mirror(i)];
    w_max_[i] = std::max(w_max[i], w_[i] - w_min[mirror(i)]);
    w_min_[i] = std::min(w_min[i], w_[i] - w_max[mirror(i)]);
    r.q_reloaded[i] = -r.q_unloaded[mirror(i)];
  }
  const std::size_t end = r.loop.size();
  for (std::size_t j = first_loop_point; j < end; ++j) {
    LoopPoint point = r.loop[j];
    point.Q = -point.Q;
    point.delta = -point.delta;
    r.loop.push_back(point);
  }
  state_ = std::move(top);
  p_ = std::move(p_top);
  traction_bounds(p_, f_, lo_, hi_);
  Q_prev_ = -Q_prev_;
  x_prev_ = -x_prev_;
  result_.mirrored = true;
}

SolveSummary IncrementalSlipSolver::AmplitudeRun::step(double x_t, int cycle, int k) {
  SolveSummary s;
  double Qt = x_t;
  extra_ = 0.0;
  if (displacement_) {
    const double delta_prev = delta_now();
    std::tie(Qt, s) = displacement_increment(x_t, cycle, k);
    const double dQ = Qt - Q_prev_;
    if (extra_ == 0.0 && dQ != 0.0 && (x_t - delta_prev) / dQ > 0.0) compliance_ = (x_t - delta_prev) / dQ;
  } else if (coupled_) {
    s = coupled_increment(P_, f_, {Qt, Q_prev_, strain_at(Qt), strain_at(Q_prev_)}, p_, lo_, hi_, cycle, k);
    check(s, cycle, k, Qt);
  } else {
    s = solver_.solve_increment(p_, f_, {Qt, Q_prev_, strain_at(Qt), strain_at(Q_prev_)}, state_);
    check(s, cycle, k, Qt);
  }
  count(s);
  double work = 0.0;
  for (int i = 0; i < n_; ++i) work += h_ * state_.q[i] * state_.dw[i];
  result_.increment_energy.push_back(work);
  result_.increment_Q.push_back(Qt);
  result_.increment_shift.push_back(state_.shift + extra_);
  Q_prev_ = Qt;
  x_prev_ = x_t;
  shift_ += state_.shift + extra_;
  return s;
}

void IncrementalSlipSolver::AmplitudeRun::check(const SolveSummary& s, int cycle, int k, double Qt) const {
  if (!s.converged())
    throw ConvergenceError(fmt::format(
        "incremental slip: {} (Q from {:.6g} to {:.6g} N/m) stopped ({}) after {} iterations with residual {:.3g} "
        "above the tolerance {:.3g}",
        where(cycle, k), Q_prev_, Qt, to_string(s.termination), s.iterations, s.residual, options_.tolerance));
}

// δ(Q) is continuous and increasing (the tangential compliance is positive), so a bracket grown from the secant guess
// and the Illinois false position find the Q whose δ is x_t; past ±f P (every cell at ±f p) the bodies slide.
std::pair<double, SolveSummary> IncrementalSlipSolver::AmplitudeRun::displacement_increment(double x_t, int cycle,
                                                                                             int k) {
  DeltaSearch search(x_t, strain_at(x_t), strain_at(x_prev_), cycle, k, state_, p_);
  const double tol = 10.0 * options_.tolerance * std::abs(x_t - x_prev_);
  const double Qt = std::clamp(Q_prev_ + (x_t - x_prev_) / compliance_, -capacity_, capacity_);
  const double ft = delta_miss(search, Qt);
  if (std::abs(ft) <= tol) return {Qt, search.total};
  // Bracket: a with δ(a) < x_t, b with δ(b) > x_t, in doubling steps from the guess up to ±f P.
  double a = Qt, fa = ft, b = Qt, fb = ft;
  double step = std::max(std::abs(ft) / compliance_, 1e-6 * capacity_);
  while (fa > 0.0) {
    if (a == -capacity_) return {slide(a, fa), search.total};
    b = a, fb = fa;
    a = std::max(a - step, -capacity_);
    fa = delta_miss(search, a);
    step *= 2.0;
  }
  while (fb < 0.0) {
    if (b == capacity_) return {slide(b, fb), search.total};
    a = b, fa = fb;
    b = std::min(b + step, capacity_);
    fb = delta_miss(search, b);
    step *= 2.0;
  }
  if (std::abs(fa) <= tol) return accept(search, a);
  if (std::abs(fb) <= tol) return accept(search, b);
  return false_position(search, a, fa, b, fb, tol);
}

double IncrementalSlipSolver::AmplitudeRun::delta_miss(DeltaSearch& search, double Q) {
  search.last = Q;
  SolveSummary s;
  if (coupled_) {
    // β ≠ 0: the coupled increment to Q from the increment's start (its traction and pressure); the normal solves
    // stay warm-started from the last evaluation's pressure.
    state_ = search.start;
    p_ = search.p_start;
    s = coupled_increment(P_, f_, {Q, Q_prev_, search.eps_t, search.eps_0}, p_, lo_, hi_, search.cycle, search.k);
    search.trial = state_;
  } else {
    search.trial.q = state_.q;  // warm start: the last evaluation (q and u = K q agree)
    search.trial.u = state_.u;
    s = solver_.solve_bounded(lo_, hi_, {Q, Q_prev_, search.eps_t, search.eps_0}, search.start.u, search.trial);
  }
  search.total.iterations += s.iterations;
  search.total.seconds += s.seconds;
  search.total.residual = std::max(search.total.residual, s.residual);
  search.total.termination = s.termination;
  check(s, search.cycle, search.k, Q);
  if (++search.evaluations > kMaxEvaluations)
    throw ConvergenceError(fmt::format("incremental slip: {} (δ from {:.6g} to {:.6g} m): no Q found in {} solves",
                                       where(search.cycle, search.k), x_prev_, search.x_t, kMaxEvaluations));
  state_ = search.trial;
  const IncrementState& trial = search.trial;
  return shift_ + trial.shift + datum_->relative_displacement(trial.q, p_) - D0_ - search.eps_t * datum_->x_c() -
         search.x_t;
}

std::pair<double, SolveSummary> IncrementalSlipSolver::AmplitudeRun::accept(DeltaSearch& search, double Q) {
  if (Q != search.last) delta_miss(search, Q);
  return {Q, search.total};
}

double IncrementalSlipSolver::AmplitudeRun::slide(double Q_bound, double miss) {
  extra_ = -miss;
  for (int i = 0; i < n_; ++i) {
    if (hi_[i] > 0.0) state_.dw[i] += extra_;
    state_.dw_touching[i] += extra_;  // the bodies slide past every x alike
  }
  return Q_bound;
}

std::pair<double, SolveSummary> IncrementalSlipSolver::AmplitudeRun::false_position(DeltaSearch& search, double a,
                                                                                     double fa, double b, double fb,
                                                                                     double tol) {
  int side = 0;  // Illinois: halve the retained end's value when the same end is kept twice
  for (;;) {
    double Qt = (a * fb - b * fa) / (fb - fa);
    if (!(Qt > a && Qt < b)) Qt = 0.5 * (a + b);
    const double ft = delta_miss(search, Qt);
    if (std::abs(ft) <= tol || b - a <= 1e-14 * capacity_) return {Qt, search.total};
    if (ft < 0.0) {
      a = Qt, fa = ft;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = Qt, fb = ft;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
}

// A sweep k: p_k from q_{k−1}, then q_k from p_k; the increment ends when a sweep changes neither traction by more
// than coupling_tolerance · max p_k. q_0 and p_0 are the increment's start; with predict_increments, where the last
// increment had the same P and the same strain per unit Q and loaded in the same direction, the first normal solve
// takes instead the start plus the last increment's change scaled to this load step, q_0 + r Δq_last (r = ΔQ/ΔQ_last),
// and p_0 + r Δp_last is its warm start and the pressure its change is measured from (header).
SolveSummary IncrementalSlipSolver::Run::coupled_increment(double P, double f, const SlipIncrement& inc,
                                                           std::vector<double>& p, std::vector<double>& lo,
                                                           std::vector<double>& hi, int cycle, int k) {
  const std::vector<double> p_prev = p, u_prev = state_.u, q_prev = state_.q;
  std::vector<double> p_last = p, q_last = state_.q;
  IncrementState trial = state_;
  const double dQ = inc.Q - inc.Q_prev, d_eps = inc.bulk_strain - inc.bulk_strain_prev;
  std::vector<double> q_predicted;  // the first sweep's normal solve takes it instead of the start's q
  const double same = 1e-12;       // relative: the same P, the same strain per unit Q (they are sums of rounded terms)
  const double strain_scale = std::abs(d_eps * dQ_last_) + std::abs(d_eps_last_ * dQ);
  if (options_.predict_increments && dQ_last_ != 0.0 && std::abs(P - P_last_) <= same * P && dQ / dQ_last_ > 0.0 &&
      std::abs(d_eps * dQ_last_ - d_eps_last_ * dQ) <= same * strain_scale) {
    const double r = dQ / dQ_last_;
    q_predicted = q_prev;
    for (int i = 0; i < n_; ++i) {
      q_predicted[i] += r * dq_last_[i];
      p_last[i] = std::max(0.0, p_last[i] + r * dp_last_[i]);
    }
    normal_state_.p = p_last;  // the first normal solve's warm start
  }
  SolveSummary total;
  double change = std::numeric_limits<double>::infinity();
  int sweeps = 0;
  while (change > options_.coupling_tolerance * *std::max_element(p.begin(), p.end())) {
    if (++sweeps > options_.max_coupling_sweeps)
      throw ConvergenceError(fmt::format(
          "incremental slip: {} (Q from {:.6g} to {:.6g} N/m): the coupled normal and tangential solves of "
          "dissimilar bodies (beta = {:.4g}) still change the traction by {:.3g} of the peak pressure after {} "
          "sweeps (coupling tolerance {:.3g}){}",
          where(cycle, k), inc.Q_prev, inc.Q, coupling_->beta, change / *std::max_element(p.begin(), p.end()),
          options_.max_coupling_sweeps, options_.coupling_tolerance,
          f * std::abs(coupling_->beta) >= kSweepsSlowBeyond
              ? fmt::format(": a sweep contracts the change by about f |beta| = {:.3g}, and near 1 or above the "
                            "sweeps do not settle (docs/METHODS.md, \"Known to fail\")",
                            f * std::abs(coupling_->beta))
              : ""));
    coupled_pressure(sweeps == 1 && !q_predicted.empty() ? q_predicted : trial.q, P, inc, p, cycle, k);
    const SolveSummary ts = coupled_traction(f, inc, p, p_prev, u_prev, lo, hi, trial);
    total.iterations += ts.iterations;
    total.seconds += ts.seconds;
    total.residual = ts.residual;
    total.termination = ts.termination;
    if (!ts.converged()) return total;
    change = 0.0;
    for (int i = 0; i < n_; ++i)
      change = std::max({change, std::abs(p[i] - p_last[i]), std::abs(trial.q[i] - q_last[i])});
    p_last = p;
    q_last = trial.q;
  }
  state_ = std::move(trial);
  dq_last_.resize(n_);
  dp_last_.resize(n_);
  for (int i = 0; i < n_; ++i) dq_last_[i] = state_.q[i] - q_prev[i], dp_last_[i] = p[i] - p_prev[i];
  dQ_last_ = dQ, P_last_ = P, d_eps_last_ = d_eps;
  result_.n_coupling_sweeps += sweeps;
  result_.max_coupling_sweeps = std::max(result_.max_coupling_sweeps, sweeps);
  return total;
}

void IncrementalSlipSolver::Run::coupled_pressure(std::span<const double> q, double P, const SlipIncrement& inc,
                                                  std::vector<double>& p, int cycle, int k) {
  std::vector<double> coupling_u(n_), gap(n_);
  S_.apply(q, coupling_u, A_beta_);
  for (int i = 0; i < n_; ++i) gap[i] = coupling_->g0[i] - coupling_u[i];
  const SolveSummary ns = coupled_normal_.solve(gap, P, normal_state_);
  if (!ns.converged())
    throw ConvergenceError(fmt::format("incremental slip: {} (P {:.6g}, Q from {:.6g} to {:.6g} N/m): the coupled "
                                       "normal solve stopped ({}) with residual {:.3g}",
                                       where(cycle, k), P, inc.Q_prev, inc.Q, to_string(ns.termination),
                                       ns.residual));
  p = normal_state_.p;
}

// Cells that left the contact drop their traction, as under a load history; the pressure's coupling slip enters
// through the previous displacement, u_prev − A β S (p − p_prev).
SolveSummary IncrementalSlipSolver::Run::coupled_traction(double f, const SlipIncrement& inc,
                                                          std::span<const double> p, std::span<const double> p_prev,
                                                          std::span<const double> u_prev, std::vector<double>& lo,
                                                          std::vector<double>& hi, IncrementState& trial) {
  traction_bounds(p, f, lo, hi);
  drop_separated(kernel_, hi, trial);
  std::vector<double> dp(n_), coupling_u(n_), u_eff(n_);
  for (int i = 0; i < n_; ++i) dp[i] = p[i] - p_prev[i];
  S_.apply(dp, coupling_u, A_beta_);
  for (int i = 0; i < n_; ++i) u_eff[i] = u_prev[i] - coupling_u[i];
  return solver_.solve_bounded(lo, hi, inc, u_eff, trial);
}

void IncrementalSlipSolver::AmplitudeRun::classify(CycleResult& r, double sliding) const {
  int n_backward = 0;
  double x_backward = 0.0;
  for (int i = 0; i < n_; ++i)
    if (hi_[i] > 0.0 && r.q_top[i] <= -hi_[i]) x_backward = n_backward++ == 0 ? grid_.x(i) : x_backward;
  if (sliding > 0.0) {
    // Displacement control past the stick limit: the bodies slide rigidly by sliding/2 each half cycle.
    r.regime = Regime::gross_slip;
    r.sliding_amplitude = 0.25 * sliding;
    r.message = fmt::format("Q reaches f P = {:.6g} N/m and the bodies slide {:.6g} m each way beyond the stick "
                            "limit (sliding amplitude {:.6g} m at delta = {:.6g} m)",
                            capacity_, 0.5 * sliding, r.sliding_amplitude, X_);
    r.stick_zone.reset();
    r.stick_zones.clear();  // a cell that never slips at the window's end is no stick zone when the bodies slide
  } else if (n_backward > 0) {
    // At the top some cell is held at q = −f p: the leading edge has slipped backwards.
    r.regime = Regime::reverse_slip;
    r.message = fmt::format("at the top of the cycle {} cells from x = {:.6g} m sit at q = -f p: the leading edge "
                            "slips backwards (reverse slip)",
                            n_backward, x_backward);
  }
}

IncrementalSlipSolver::HistoryRun::HistoryRun(const IncrementalSlipSolver& solver, const ContactState& contact,
                                              const CyclicLoad& load, std::span<const double> g0,
                                              const ReferenceDatum* datum, const NormalCoupling* coupling)
    : Run(solver, contact, datum, coupling),
      f_(load.f),
      m_(options_.increments_per_cycle),
      g0_(g0),
      normal_(kernel_),
      lo_(n_),
      hi_(n_),
      p_now_(contact.p) {
  for (double pi : contact.p) P0_ += h_ * pi;
  pressures_[P0_] = contact.p;
  prev_ = {P0_, 0.0, 0.0};
  // As solve()'s: with settling_increments the march before the last cycle takes that many a cycle (header).
  const int m_settle = options_.cycles > 1 && options_.settling_increments > 0 ? options_.settling_increments : m_;
  split_first_loading(load.history.front(), m_settle);
  settling_ = split(load.history, m_settle);
  steady_ = split(load.history, m_);
}

void IncrementalSlipSolver::HistoryRun::split_first_loading(const HistoryPoint& first, int m) {
  for (int k = 1; k <= m / 4; ++k) {
    const double s = 4.0 * k / m;
    first_.push_back({P0_ + s * (first.P - P0_), s * first.Q, s * first.bulk_strain});
  }
}

IncrementalSlipSolver::HistoryRun::Cycle IncrementalSlipSolver::HistoryRun::split(const std::vector<HistoryPoint>& H,
                                                                                  int m) {
  Cycle c;
  std::vector<Target>& targets = c.targets;
  const double T = H.back().t - H.front().t;
  for (std::size_t j = 1; j < H.size(); ++j) {
    const int steps = std::max(1, int(std::ceil(m * (H[j].t - H[j - 1].t) / T - 1e-9)));
    for (int k = 1; k <= steps; ++k) {
      const double s = double(k) / steps;
      targets.push_back({H[j - 1].P + s * (H[j].P - H[j - 1].P), H[j - 1].Q + s * (H[j].Q - H[j - 1].Q),
                         H[j - 1].bulk_strain + s * (H[j].bulk_strain - H[j - 1].bulk_strain)});
    }
  }
  for (std::size_t j = 0; j < targets.size(); ++j) {
    if (targets[j].Q > targets[c.top].Q) c.top = int(j);
    if (targets[j].Q < targets[c.bottom].Q) c.bottom = int(j);
  }
  const double Q_mid = 0.5 * (targets[c.top].Q + targets[c.bottom].Q);
  const int n_targets = int(targets.size());
  auto crossing = [&](int from, bool down) {
    for (int k = 1; k <= n_targets; ++k) {
      const int j = (from + k) % n_targets;
      if (down ? targets[j].Q <= Q_mid : targets[j].Q >= Q_mid) return j;
    }
    return from;
  };
  c.unloaded = crossing(c.top, true);
  c.reloaded = crossing(c.bottom, false);
  return c;
}

const std::vector<double>& IncrementalSlipSolver::HistoryRun::pressure_at(double P) {
  if (auto it = pressures_.find(P); it != pressures_.end()) return it->second;
  auto near = pressures_.lower_bound(P);
  if (near == pressures_.end() || (near != pressures_.begin() && P - std::prev(near)->first < near->first - P))
    near = std::prev(near);
  ContactState state;
  state.p = near->second;
  const SolveSummary s = normal_.solve(g0_, P, state);
  if (!s.converged())
    throw ConvergenceError(fmt::format("incremental slip: the normal solve at P = {:.6g} N/m of the load history "
                                       "stopped ({}) with residual {:.3g}",
                                       P, to_string(s.termination), s.residual));
  return pressures_[P] = std::move(state.p);
}

void IncrementalSlipSolver::HistoryRun::first_loading() {
  if (datum_) first_loading_.push_back({P0_, 0.0, 0.0});
  for (std::size_t k = 0; k < first_.size(); ++k) {
    step(first_[k], 0, int(k) + 1);
    if (datum_) first_loading_.push_back(loop_point());
  }
}

void IncrementalSlipSolver::HistoryRun::cycle(int c) {
  CycleResult r = begin_cycle();
  std::vector<double> hi_top, hi_unloaded;
  const Cycle& cy = c < options_.cycles ? settling_ : steady_;
  for (int j = 0; j < int(cy.targets.size()); ++j) {
    r.solves.push_back(step(cy.targets[j], c, j + 1));
    end_increment(r, prev_.Q);
    // The pressure and the bulk strain at the top and the bottom, at any β: P and ε vary along a history, so the
    // phases there are not the contact's pressure under load.P with ±ε.
    if (j == cy.top) {
      r.q_top = state_.q, hi_top = hi_;
      result_.p_top = p_now_, result_.bulk_strain_top = prev_.eps;
    }
    if (j == cy.bottom) {
      r.q_bottom = state_.q;
      result_.p_bottom = p_now_, result_.bulk_strain_bottom = prev_.eps;
    }
    if (j == cy.unloaded) r.q_unloaded = state_.q, hi_unloaded = hi_;
    if (j == cy.reloaded) r.q_reloaded = state_.q;
  }
  close_cycle(grid_, w_max_, w_min_, hi_top, hi_unloaded, r);
  int n_backward = 0;
  for (int i = 0; i < n_; ++i) n_backward += hi_top[i] > 0.0 && r.q_top[i] <= -hi_top[i];
  if (n_backward > 0) {
    r.regime = Regime::reverse_slip;
    r.message = fmt::format("at the top of the cycle {} cells sit at q = -f p (reverse slip)", n_backward);
  }
  result_.cycles.push_back(std::move(r));
}

// At a new P the bounds ±f p change: cells that separate drop their traction (the drop is part of the increment's
// Δq), and q above its new bound is clamped by the increment's projection.
SolveSummary IncrementalSlipSolver::HistoryRun::step(const Target& t, int cycle, int k) {
  const SlipIncrement inc{t.Q, prev_.Q, t.eps, prev_.eps};
  SolveSummary s;
  if (coupled_) {  // β ≠ 0: the pressure under t.P solved with the shear, sweep by sweep
    s = coupled_increment(t.P, f_, inc, p_now_, lo_, hi_, cycle, k);
  } else {
    const std::vector<double>& p = pressure_at(t.P);
    traction_bounds(p, f_, lo_, hi_);
    p_now_ = p;
    const std::vector<double> u_prev = state_.u;
    drop_separated(kernel_, hi_, state_);
    s = solver_.solve_bounded(lo_, hi_, inc, u_prev, state_);
  }
  count(s);
  if (!s.converged())
    throw ConvergenceError(fmt::format(
        "incremental slip: {} of the load history (P {:.6g}, Q from {:.6g} to {:.6g} N/m) stopped ({}) after {} "
        "iterations with residual {:.3g} above the tolerance {:.3g}",
        where(cycle, k), t.P, prev_.Q, t.Q, to_string(s.termination), s.iterations, s.residual, options_.tolerance));
  prev_ = t;
  shift_ += state_.shift;
  return s;
}

}  // namespace fretwear
