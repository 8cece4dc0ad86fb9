// Dissimilar Hertz under force control against an independent solution: the coupled cycle solved here by dense
// linear algebra and an active set, increment by increment, on the same grid and influence matrices, against the
// incremental route's block Gauss–Seidel sweeps of constrained conjugate gradients (contact/incremental_slip.hpp).
//
// The discrete problem (contact/coupling_kernel.hpp, fretwear's signs): with K the half-plane matrix, S the
// antisymmetric step matrix (h/2) sgn(i − j), A the compliance and β Dundurs' parameter,
//     gap:         g = g0 + K p − A β S q − δ,          g_i = 0 where p_i > 0,  g_i ≥ 0 and p_i = 0 elsewhere,
//     tangential:  Δs = K Δq + A β S Δp − Δλ over an increment,
//                  stick: Δs_i = 0, |q_i| ≤ f p_i;   slip: q_i = σ_i f p_i with σ_i Δs_i ≤ 0 (Coulomb),
//     loads:       h Σ p = P,   h Σ q = Q.
// Each increment is one linear system in (p on the contact set, q on the stick set, δ, Δλ), q = σ f p on the slip
// set: solved by Eigen's LU, and the sets corrected (a negative pressure leaves the contact, a negative gap joins
// it, a stick cell past f p slips, a slip cell whose slip points backwards sticks) until none changes. The load path
// is the engine's: 0 → Q in m/4 equal steps, then cycles Q → −Q → Q in m steps, the second of which is compared
// (for β ≠ 0 the first cycle after the first loading is not yet steady: test_cycle_dissimilar.cpp). The two methods
// share the model, not the algorithm: the comparison checks the coupled sweeps, their stopping rule, the increments'
// bookkeeping of slip and energy, and the stick zone the engine reports.
//
// Nowell, Hills and Sackfield (1988) solved this problem (a cylinder on a dissimilar half-plane under normal then
// tangential load) by quadrature of the coupled integral equations and found the stick zone's size and offset
// changed little by β at |β| ≈ 0.1; their tabulated values are not reproduced here, the dense solution stands in for
// them, on the same discretisation, so that the two must agree to the solvers' tolerances, not to a grid error.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <doctest/doctest.h>
#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/coupling_kernel.hpp"
#include "contact/incremental_slip.hpp"
#include "engine/simulation.hpp"
#include "scenes.hpp"

using namespace fretwear;

namespace {

constexpr double kP = 1e5, kRatio = 0.5;
constexpr int kIncrements = 80;  // per cycle (the first loading takes a quarter)
// Both solve the same discrete problem; the engine stops at a relative residual of 1e-8 per increment and its
// coupling sweeps at 1e-8 p_max: kSolverAgreement bounds what that leaves in the cycle's energy and slip.
constexpr double kSolverAgreement = 1e-5;

struct DenseCycle {
  std::vector<double> p_top, q_top, slip_range, energy_density;
  double energy = 0.0;
  std::vector<int> stick;  // cells that never slipped in the compared cycle
};

class DenseCoupled {
 public:
  DenseCoupled(const Model& m, double f) : m_(m), f_(f), n_(m.grid.n), K_(n_, n_), S_(n_, n_) {
    const CouplingKernel coupling(m.grid);
    for (int i = 0; i < n_; ++i)
      for (int j = 0; j < n_; ++j) {
        K_(i, j) = m.kernel->coefficient(double(i - j) * m.grid.h());
        S_(i, j) = coupling.matrix(i, j);
      }
    Ab_ = m.pair.A() * m.pair.beta();
  }

  // The frictionless start: p from the normal solve, q = 0, every contact cell stuck.
  void start(const std::vector<double>& p0) {
    p_ = Eigen::Map<const Eigen::VectorXd>(p0.data(), n_);
    q_ = Eigen::VectorXd::Zero(n_);
    w_ = Eigen::VectorXd::Zero(n_);
    e_ = Eigen::VectorXd::Zero(n_);
    state_.assign(std::size_t(n_), kOff);
    for (int i = 0; i < n_; ++i)
      if (p_(i) > 0.0) state_[std::size_t(i)] = kStick;
  }

  // One increment to the tangential load Q; returns false if the sets did not settle.
  bool increment(double Q) {
    const double h = m_.grid.h();
    const Eigen::VectorXd p0 = p_, q0 = q_;
    for (int round = 0; round < 200; ++round) {
      std::vector<int> C, St;
      for (int i = 0; i < n_; ++i) {
        if (state_[std::size_t(i)] != kOff) C.push_back(i);
        if (state_[std::size_t(i)] == kStick) St.push_back(i);
      }
      const int nc = int(C.size()), ns = int(St.size()), N = nc + ns + 2;
      // Unknowns: p on C, q on St, δ, Δλ. q_j = σ_j f p_j on the slip cells folds into the p columns.
      std::vector<int> col_q(std::size_t(n_), -1);
      for (int k = 0; k < ns; ++k) col_q[std::size_t(St[std::size_t(k)])] = nc + k;
      Eigen::MatrixXd M = Eigen::MatrixXd::Zero(N, N);
      Eigen::VectorXd b = Eigen::VectorXd::Zero(N);
      auto q_coefficient = [&](int j) { return sigma(j) * f_; };  // on a slip cell, q_j = this · p_j
      for (int r = 0; r < nc; ++r) {  // gap: K p − Aβ S q − δ = −g0
        const int i = C[std::size_t(r)];
        for (int c = 0; c < nc; ++c) {
          const int j = C[std::size_t(c)];
          M(r, c) += K_(i, j);
          if (state_[std::size_t(j)] != kStick) M(r, c) -= Ab_ * S_(i, j) * q_coefficient(j);
        }
        for (int k = 0; k < ns; ++k) M(r, nc + k) -= Ab_ * S_(i, St[std::size_t(k)]);
        M(r, N - 2) = -1.0;
        b(r) = -m_.g0[std::size_t(i)];
      }
      for (int r = 0; r < ns; ++r) {  // stick: K (q − q0) + Aβ S (p − p0) − Δλ = 0
        const int i = St[std::size_t(r)];
        double rhs = 0.0;
        for (int j = 0; j < n_; ++j) rhs += K_(i, j) * q0(j) + Ab_ * S_(i, j) * p0(j);
        for (int c = 0; c < nc; ++c) {
          const int j = C[std::size_t(c)];
          M(nc + r, c) += Ab_ * S_(i, j);
          if (state_[std::size_t(j)] != kStick) M(nc + r, c) += K_(i, j) * q_coefficient(j);
        }
        for (int k = 0; k < ns; ++k) M(nc + r, nc + k) += K_(i, St[std::size_t(k)]);
        M(nc + r, N - 1) = -1.0;
        b(nc + r) = rhs;
      }
      for (int c = 0; c < nc; ++c) {  // h Σ p = P, h Σ q = Q
        const int j = C[std::size_t(c)];
        M(N - 2 + 0, c) = h;
        if (state_[std::size_t(j)] != kStick) M(N - 1, c) = h * q_coefficient(j);
      }
      for (int k = 0; k < ns; ++k) M(N - 1, nc + k) = h;
      b(N - 2) = kP;
      b(N - 1) = Q;
      // The two load rows sit below the cells' rows; the unknowns δ and Δλ in the last two columns.
      const Eigen::VectorXd x = M.partialPivLu().solve(b);
      Eigen::VectorXd p = Eigen::VectorXd::Zero(n_), q = Eigen::VectorXd::Zero(n_);
      for (int c = 0; c < nc; ++c) p(C[std::size_t(c)]) = x(c);
      for (int c = 0; c < nc; ++c) {
        const int j = C[std::size_t(c)];
        q(j) = state_[std::size_t(j)] == kStick ? x(col_q[std::size_t(j)]) : q_coefficient(j) * p(j);
      }
      const double delta = x(N - 2), dlambda = x(N - 1);
      const Eigen::VectorXd gap = Eigen::Map<const Eigen::VectorXd>(m_.g0.data(), n_) + K_ * p - Ab_ * S_ * q -
                                  Eigen::VectorXd::Constant(n_, delta);
      const Eigen::VectorXd ds = K_ * (q - q0) + Ab_ * S_ * (p - p0) - Eigen::VectorXd::Constant(n_, dlambda);
      // Correct the sets, one kind of change at a time (the most violated first within it).
      const double p_scale = p.cwiseAbs().maxCoeff(), tol = 1e-12;
      bool changed = false;
      for (int i = 0; i < n_; ++i) {
        auto& st = state_[std::size_t(i)];
        if (st != kOff && p(i) < -tol * p_scale) st = kOff, changed = true;
        else if (st == kOff && gap(i) < -1e-10 * std::abs(delta)) st = kStick, changed = true;
      }
      if (!changed)
        for (int i = 0; i < n_; ++i) {
          auto& st = state_[std::size_t(i)];
          if (st == kStick && std::abs(q(i)) > f_ * p(i) * (1.0 + 1e-12)) st = q(i) > 0.0 ? kForward : kBackward, changed = true;
          else if ((st == kForward && ds(i) > tol * ds.cwiseAbs().maxCoeff()) ||
                   (st == kBackward && ds(i) < -tol * ds.cwiseAbs().maxCoeff()))
            st = kStick, changed = true;
        }
      if (changed) continue;
      for (int i = 0; i < n_; ++i) {
        if (state_[std::size_t(i)] == kForward || state_[std::size_t(i)] == kBackward) {
          w_(i) -= ds(i);  // Δw = −Δs
          e_(i) += q(i) * -ds(i);
          slipped_[std::size_t(i)] = 1;
        }
      }
      p_ = p;
      q_ = q;
      return true;
    }
    return false;
  }

  // Starts the bookkeeping of a cycle to compare.
  void begin_cycle() {
    e_ = Eigen::VectorXd::Zero(n_);
    w_ = Eigen::VectorXd::Zero(n_);
    w_min_ = w_max_ = std::vector<double>(std::size_t(n_), 0.0);
    slipped_.assign(std::size_t(n_), 0);
  }
  void observe() {
    for (int i = 0; i < n_; ++i) {
      w_min_[std::size_t(i)] = std::min(w_min_[std::size_t(i)], w_(i));
      w_max_[std::size_t(i)] = std::max(w_max_[std::size_t(i)], w_(i));
    }
  }
  DenseCycle result(const std::vector<double>& p_top, const std::vector<double>& q_top) const {
    DenseCycle c;
    c.p_top = p_top;
    c.q_top = q_top;
    for (int i = 0; i < n_; ++i) {
      c.slip_range.push_back(w_max_[std::size_t(i)] - w_min_[std::size_t(i)]);
      c.energy_density.push_back(e_(i));
      c.energy += m_.grid.h() * e_(i);
      if (p_top[std::size_t(i)] > 0.0 && !slipped_[std::size_t(i)]) c.stick.push_back(i);
    }
    return c;
  }
  std::vector<double> p() const { return {p_.data(), p_.data() + n_}; }
  std::vector<double> q() const { return {q_.data(), q_.data() + n_}; }

 private:
  enum State { kOff, kStick, kForward, kBackward };
  double sigma(int j) const { return state_[std::size_t(j)] == kForward ? 1.0 : -1.0; }

  const Model& m_;
  double f_;
  int n_;
  Eigen::MatrixXd K_, S_;
  double Ab_ = 0.0;
  Eigen::VectorXd p_, q_, w_, e_;
  std::vector<State> state_;
  std::vector<double> w_min_, w_max_;
  std::vector<char> slipped_;
};

// The dense cycle along the engine's path: first loading, then `cycles` cycles; the last one compared.
DenseCycle dense_cycle(const Model& m, const std::vector<double>& p0, double f, double Q, int cycles) {
  DenseCoupled d(m, f);
  d.start(p0);
  d.begin_cycle();
  const int quarter = kIncrements / 4, half = kIncrements / 2;
  for (int k = 1; k <= quarter; ++k) REQUIRE(d.increment(Q * double(k) / quarter));
  std::vector<double> p_top, q_top;
  for (int c = 0; c < cycles; ++c) {
    d.begin_cycle();
    for (int k = 1; k <= half; ++k) {
      REQUIRE(d.increment(Q * (1.0 - 2.0 * double(k) / half)));
      d.observe();
    }
    for (int k = 1; k <= half; ++k) {
      REQUIRE(d.increment(Q * (-1.0 + 2.0 * double(k) / half)));
      d.observe();
    }
    p_top = d.p();
    q_top = d.q();
  }
  return d.result(p_top, q_top);
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace

TEST_CASE("dissimilar Hertz under force control: the coupled cycle equals a dense active-set solution") {
  // Steel on aluminium (β ≈ −0.11) and steel on titanium (β ≈ −0.05), 256 cells; and β = 0 (steel on steel), where
  // the dense solution must also give Cattaneo–Mindlin's stick zone to a cell or two.
  for (const Material specimen : {Material{71e9, 0.33}, Material{110e9, 0.34}, Material{200e9, 0.3}}) {
    Scene s = test::hertz_cycle(kP, kRatio, 256);
    s.specimen = specimen;
    const Model m = make_model(s);
    const NormalResult n = solve_normal(s, m);
    const double beta = m.pair.beta(), f = *s.friction, Q = kRatio * f * kP;
    CAPTURE(beta);
    IncrementalSlipOptions o;
    o.increments_per_cycle = kIncrements;
    o.cycles = 2;
    const NormalCoupling coupling{beta, m.g0};
    const IncrementalResult r =
        IncrementalSlipSolver(*m.kernel, o).solve(n.state, CyclicLoad{kP, Q, f, 0.0}, nullptr, &coupling);
    const CycleResult& c = r.cycles.back();
    const DenseCycle d = dense_cycle(m, n.state.p, f, Q, 2);
    REQUIRE(c.stick_zone);
    REQUIRE_FALSE(d.stick.empty());
    const double h = m.grid.h();
    const double left = m.grid.x(d.stick.front()) - 0.5 * h, right = m.grid.x(d.stick.back()) + 0.5 * h;
    MESSAGE(fmt::format("beta {:.5f}: stick zone engine [{:.6g}, {:.6g}] mm, dense cells [{:.6g}, {:.6g}] mm; "
                        "energy {:.8g} / {:.8g} J/m",
                        beta, c.stick_zone->first * 1e3, c.stick_zone->second * 1e3, left * 1e3, right * 1e3,
                        c.dissipated_energy, d.energy));
    // The stick zone: the engine locates its ends within a cell, and a cell at an end may slip by round-off in one
    // solution and not in the other: the dense cells that never slipped span it to kEndCells cells.
    constexpr double kEndCells = 1.5;
    CHECK(std::abs(c.stick_zone->first - left) <= kEndCells * h);
    CHECK(std::abs(c.stick_zone->second - right) <= kEndCells * h);
    // The energy, the slip range and the tractions at the top of the cycle, cell by cell.
    CHECK(std::abs(c.dissipated_energy - d.energy) <= kSolverAgreement * d.energy);
    std::vector<double> dp, dq, ds;
    const std::vector<double>& p_top = r.p_top.empty() ? n.state.p : r.p_top;  // β = 0: the pressure stays
    for (int i = 0; i < m.grid.n; ++i) {
      dp.push_back(p_top[std::size_t(i)] - d.p_top[std::size_t(i)]);
      dq.push_back(c.q_top[std::size_t(i)] - d.q_top[std::size_t(i)]);
      ds.push_back(c.slip_range[std::size_t(i)] - d.slip_range[std::size_t(i)]);
    }
    CHECK(max_abs(dp) <= kSolverAgreement * max_abs(d.p_top));
    CHECK(max_abs(dq) <= kSolverAgreement * max_abs(d.p_top));
    CHECK(max_abs(ds) <= kSolverAgreement * max_abs(d.slip_range));
    if (beta == 0.0) {  // Cattaneo–Mindlin: c/a = √(1 − Q/fP)
      const auto hz = closed_form::hertz(kP, m.pair.A(), test::kHertzR);
      CHECK(std::abs(right - hz.a * std::sqrt(1.0 - kRatio)) <= 2.0 * h);
    }
  }
}
