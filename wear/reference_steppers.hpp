// The reference wear steppers of ARCHITECTURE.md ("Wear in time"), against which the contact-implicit stepper is
// checked. Both integrate the wear-rate system (paper 002 §3; PHYSICS.md, "Wear")
//     dw/dN = c p(w) s(w),
// with p and s the pressure and the slip travelled per cycle of the steady cycle on the profile worn by w, explicitly:
// each evaluation of the rate is one ContactResponse::respond. An explicit jump ΔN is stable only while
//     ΔN ≲ 1.5 Δx / (E* c s_max)                                   (the stability limit, cycles)
// — halving the cell halves it — and beyond it the worn profile grows a checkerboard. Both are meant for small
// problems and short runs: their cost grows like cycles / limit, where the implicit stepper's does not.
//
// - ExplicitWearStepper: Boost.Odeint's runge_kutta_dopri5 (order 5, embedded order-4 error estimate) under
//   make_controlled(abs, rel, max_dt): per cell, err_i = |e_i| / (abs + rel (|w_i| + ΔN |dw_i/dN|)) ≤ 1, with the
//   step capped at max_dt, which the caller sets below the stability limit (odeint rejects a longer step and
//   retries at the cap). The cap, not the tolerance, sets the cost on any run long against the limit.
// - CycleByCycleStepper: every cycle resolved and worn, w_{N+1} = w_N + c p(w_N) s(w_N): odeint's explicit Euler
//   with ΔN = 1, no jumping. It is itself an explicit jump of one cycle, so it is stable (and a reference) only
//   while one cycle is below the stability limit (PHYSICS.md's Hertz case at k = 1e-12 and 1024 cells: a limit of
//   about 16 cycles; 1e-13: about 160).
#pragma once

#include <algorithm>
#include <span>
#include <utility>
#include <vector>

#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <boost/numeric/odeint/stepper/euler.hpp>
#include <boost/numeric/odeint/stepper/generation/generation_controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/generation/generation_runge_kutta_dopri5.hpp>
#include <boost/numeric/odeint/stepper/generation/make_controlled.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <boost/numeric/odeint/stepper/stepper_categories.hpp>

#include "wear/contact_response.hpp"

namespace fretwear::wear {

// The largest stable explicit (forward Euler) jump 1.5 Δx / (E* c s_max), cycles; 0 when nothing slips.
// E_star in Pa, cell_width in m, c in 1/Pa, s_max in m.
inline double explicit_stability_limit(double cell_width, double E_star, double c, double s_max) {
  return s_max > 0.0 ? 1.5 * cell_width / (E_star * c * s_max) : 0.0;
}

// The wear-rate system dw/dN = c p(w) s(w) for odeint (STYLE.md point 3): (const State&, State& dwdN, double N).
// Pass it by std::ref, so that the count of evaluations and the last response survive odeint's copies.
class WearRateSystem {
 public:
  // c: the rate coefficient of dw/dN = c p s (1/Pa).
  WearRateSystem(ContactResponse& contact, double c) : contact_(&contact), c_(c) {}

  void operator()(const std::vector<double>& w, std::vector<double>& dwdN, double /*N*/) {
    contact_->respond(w, response_);
    ++evaluations_;
    dwdN.resize(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) dwdN[i] = c_ * response_.p[i] * response_.s[i];
  }

  long evaluations() const { return evaluations_; }  // responses solved (two contact solves each)
  const CycleResponse& last_response() const { return response_; }
  // The rate of the last evaluation, c p s, computed as operator() does (bit for bit).
  std::vector<double> last_rate() const {
    std::vector<double> r(response_.p.size());
    for (std::size_t i = 0; i < r.size(); ++i) r[i] = c_ * response_.p[i] * response_.s[i];
    return r;
  }
  // For a resumed run: the count and the last response as they were at a step boundary.
  void restore(long evaluations, CycleResponse last) {
    evaluations_ = evaluations;
    response_ = std::move(last);
  }

 private:
  ContactResponse* contact_;
  double c_;
  long evaluations_ = 0;
  CycleResponse response_;
};

struct ExplicitStepperStats {
  int accepted = 0, rejected = 0;  // steps
  double max_step = 0.0;           // the longest accepted step (cycles), ≤ the cap
};

// Dormand–Prince 5(4) under odeint's step control, capped below the explicit stability limit (see the top).
class ExplicitWearStepper {
 public:
  using state_type = std::vector<double>;
  using deriv_type = std::vector<double>;
  using value_type = double;
  using time_type = double;
  using order_type = unsigned short;
  using stepper_category = boost::numeric::odeint::controlled_stepper_tag;
  using dopri5_type = boost::numeric::odeint::runge_kutta_dopri5<state_type>;
  using controlled_type = boost::numeric::odeint::controlled_runge_kutta<dopri5_type>;

  // abs_tolerance (m) and rel_tolerance: odeint's error checker (see the top); max_step: the cap (cycles, > 0).
  ExplicitWearStepper(double abs_tolerance, double rel_tolerance, double max_step)
      : controlled_(boost::numeric::odeint::make_controlled(abs_tolerance, rel_tolerance, max_step, dopri5_type())),
        cap_(max_step) {}

  static constexpr order_type order() { return 5; }

  // odeint's controlled-stepper interface; `system` is a WearRateSystem (or a reference wrapper of one). A step
  // longer than the cap is rejected by odeint and dN set to the cap.
  template <class System>
  boost::numeric::odeint::controlled_step_result try_step(System system, state_type& w, time_type& N,
                                                          time_type& dN) {
    const double tried = dN;  // on success odeint takes exactly this step, then proposes the next in dN
    const auto result = controlled_.try_step(system, w, N, dN);
    if (result == boost::numeric::odeint::controlled_step_result::success) {
      ++stats_.accepted;
      stats_.max_step = std::max(stats_.max_step, tried);
    } else {
      ++stats_.rejected;
    }
    return result;
  }

  double cap() const { return cap_; }
  const ExplicitStepperStats& stats() const { return stats_; }
  // For a resumed run: the counts, and the derivative at the current state that Dormand–Prince carries from one
  // step to the next (first same as last; WearRateSystem::last_rate() after an accepted step; null before the first
  // step, when odeint evaluates it). Sized first, so that odeint's next try_step keeps it.
  void restore(const ExplicitStepperStats& stats, const state_type& w, const std::vector<double>* dwdN) {
    stats_ = stats;
    if (!dwdN) return;
    controlled_.adjust_size(w);
    controlled_.initialize(*dwdN);
  }

 private:
  controlled_type controlled_;
  double cap_;
  ExplicitStepperStats stats_;
};

// Every cycle resolved and worn: odeint's explicit Euler, driven with ΔN = 1 (kCycle).
using CycleByCycleStepper = boost::numeric::odeint::euler<std::vector<double>>;
inline constexpr double kCycle = 1.0;

}  // namespace fretwear::wear
