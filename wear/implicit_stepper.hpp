// The contact-implicit wear stepper of ARCHITECTURE.md ("Wear in time"), as a Boost.Odeint controlled stepper, so
// that integrate_adaptive / integrate_times, observers and the failed-step checker drive it.
//
// One step of size ΔN from w_n, with the slip s lagged at w_n (backward Euler in the pressure; s is the slip each
// cell would travel were it touching, CycleResponse::slip_if_touching, for the reason below):
//     w_{n+1} = w_n + ΔN c s ⊙ p_{n+1},   p_{n+1} from the contact with gap g0 + w_n + ΔN c diag(s) p_{n+1},
// a normal solve with the operator K + ΔN c diag(s): stable for any ΔN and any grid (no checkerboard), unlike the
// explicit update, whose jump is limited to about 1.5 Δx/(E* c s_max). Raised to second order by Richardson
// extrapolation over one step of ΔN and two of ΔN/2 (the slip refreshed at the half step): their difference
// estimates the error, which sets the next ΔN from the tolerance on the worn profile
//     err = max_i e_i / (tolerance · max_i w) ≤ 1,   e_i = |w_two halves − w_one step|,   ΔN ← ΔN · 0.9/√err.
// Wear never decreases: the extrapolated state is kept at least w_n.
//
// Why, and which s. On the contact set C a perturbation δw of the worn profile moves the pressure by
// δp = −K_C⁻¹ δw (the load held by the mean gap), so with S = diag(s) frozen the step maps
//     δw_{n+1} = (I + ΔN c S K_C⁻¹)⁻¹ δw_n,
// and S K_C⁻¹ is similar to S^½ K_C⁻¹ S^½ ⪰ 0: every mode is damped, by 1/(1 + ΔN c s λ) with λ up to about
// E*/(1.5 Δx) for the checkerboard (the explicit map 1 − ΔN c s λ is what limits the explicit jump). This holds only
// if s > 0 on every cell that p_{n+1} may load. The slip travelled in the cycle is 0 off the contact, and in gross
// slip (the whole contact slides; inside a worn flat every cell is within one step's wear of touching) lagging that
// zero breaks it: a cell out of contact at w_n gets d_i = 0 beside neighbours of compliance d = ΔN c s, which
// exceeds the kernel's diagonal (about Δx/E*) by ΔN over the stability limit; the end-of-step solve loads it, it
// carries its neighbours' load without wearing and protrudes; at w_{n+1} they lift off and get s = 0 in turn. s
// switches cell by cell with the state, the lag does not see it, and the alternation grows step by step (1024 to
// 4096 cells, 18 000 cycles of 25 µm stroke: every other cell of the worn zone open, single-cell edge pressures of
// 170–600 MPa against a smooth 38, the worn area 19 % low at 4096 cells). Since p = 0 wherever s was cut, the rate
// c p s does not depend on what s is there: the step lags instead the slip each cell would travel were it
// touching (CycleResponse::slip_if_touching; in gross slip the bodies slide past every x alike, and the contact
// continues s over the cells out of contact), which makes S > 0 on every cell that can be loaded and the argument
// above hold. In partial slip the stick zone keeps s = 0 (it carries load and does not wear, as it should; it is one
// contiguous zone set by the load, not by the cells' state); the cells beyond the contact get the slip they would
// travel there where the route knows it (the analogy route), so that the contact spreading over them is worn by
// the one step as by the two half steps (below). What remains at a moving contact edge is the extrapolation's
// error: the pressure of a worn flat moves by about E*/Δx per metre of wear, and the edge cells' pressure is rough by
// tens of percent at tolerance 1e-3 (smooth at 1e-4) where the every-cycle solution is flat (37 and 72 MPa beside 55
// on the gross-slip example with only the pad wearing, 1024 cells, 5000 cycles), from an error in the worn depth of a
// few 1e-10 m, under the tolerance. Tried and not kept: bounding also the Richardson difference of the two
// end-of-step pressures, by 0.1 of the largest, where the whole contact slides. The edge cells then came within 7 %
// of the flat, but a cell entering the contact makes that difference insensitive to ΔN, and the run took more
// rejected steps than accepted ones: 18 000 cycles at 1024 / 2048 / 4096 cells in 440 / 696 / 1281 steps and
// 1.4 / 4.8 / 20 s instead of 201 / 214 / 233 steps and 1.3 / 2.6 / 5.3 s (a first-order controller for that
// criterion was slower still). With both bodies wearing, each in its own frame (engine/body_frames.hpp), the edges
// are smooth at the default tolerance: the specimen's scar, spread over the stroke, leaves the contact's ends lightly
// loaded.
//
// Cells that start to wear within the step (where the route lags s = 0 beyond the contact: the incremental route in
// partial slip). The slip is lagged, so a cell that enters the contact (or the slip zone)
// during the step with no slip lagged is not worn by the one step of ΔN at all, while the two half steps
// wear it over the second half: the difference is then first order in ΔN, not second, and extrapolating doubles the
// half steps' increment (it assumes the cell wore from the start). Such a cell entered between N and N + ΔN/2, so it
// wore between one and two times the half steps' increment Δ2: the midpoint w_n + 1.5 Δ2 is kept and e_i = 0.5 Δ2.
// Measured (docs/PERFORMANCE.md, "Wear steppers") when the analogy route still lagged s = 0 there: these cells, at the
// outer edge of the worn zone as the contact spreads, set most rejections and the largest errors of the transient;
// with the midpoint, 1 % cost about 40 accepted steps on the benchmark's case instead of about 60, tight tolerances
// were unchanged, and the loosest (1e-1, 3e-2) erred more than before (16 % and 4.3 % against 11.5 % and 2 %, with 5
// steps fewer). A cell that enters in the second half is seen by neither solution (both leave it unworn) and is
// picked up by the next step: that error, bounded by half a step of its rate, remains where s = 0 is lagged. With the
// slip on touching lagged beyond the contact (the analogy route now) the same case errs by 0.11–0.47 of the
// tolerance from 1e-1 to 1e-4 and 1 % costs 14 steps ("Does the tolerance bound the error?"). Tried and not kept (measured on the same case): a mixed abs/rel norm weighting by the
// local depth (more steps for the same error: it tightens the edge cells), an RMS norm (fewer steps, 2–4 % max-norm
// errors), err^(−1/3) (the estimate is of the Euler solution, O(ΔN²), as 1/2 assumes), a PI controller (fewer
// rejections, more accepted steps), growth caps 2–8 and safety factors 0.8–0.95 (changes within the scatter), and a
// check of the state at the step's end for cells entering in the second half (errors 10× below the tolerance, but 1 %
// then costs 45–60 steps and an extra contact solve per step).
//
// A contact-implicit solve that does not converge rejects the step like a too-large error, and ΔN is cut by 4: near
// the asymptote a large jump gives d = ΔN c s up to 10^5 times the kernel's diagonal on the worn cells, and the
// constrained CG can stall there (4096 cells, hertz_wear), while a jump a few times smaller converges in a thousand
// iterations. Below one cycle there is nothing left to cut: ImplicitSolveFailure is thrown.
//
// An error estimate that stays above the tolerance as the jump shrinks (a response that is not smooth in w, so that
// the one step and the two half steps differ by a fixed fraction whatever ΔN) would cut ΔN toward zero for ever: a
// rejection at a jump below kMinJump cycles throws ConvergenceError with the error, the jump and the cycle instead.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <vector>

#include <boost/numeric/odeint/stepper/controlled_step_result.hpp>
#include <boost/numeric/odeint/stepper/stepper_categories.hpp>
#include <boost/numeric/odeint/util/unwrap_reference.hpp>

#include "common/error.hpp"
#include "wear/contact_response.hpp"

namespace fretwear::wear {

// A contact-implicit solve that did not converge even for a jump of one cycle.
struct ImplicitSolveFailure : ConvergenceError {
  using ConvergenceError::ConvergenceError;
};

struct ImplicitStepperStats {
  int accepted = 0, rejected = 0;  // steps (rejected counts both causes)
  int unconverged = 0;             // steps rejected because a contact-implicit solve did not converge
  int implicit_solves = 0, responses = 0;
  double last_error = 0.0;  // err of the last try, ≤ 1 when accepted
};

// What the stepper carries from one accepted step to the next and what the next step's result depends on: the warm
// starts of its contact-implicit solves (they move the answer within the solver's tolerance) and its counts. Saved
// at a step boundary and restored, the stepper repeats the steps it would have taken to the last bit (a resumed run).
struct ImplicitStepperState {
  ImplicitStepperStats stats;
  std::vector<double> p_full, p_half;
};

// A jump below this is no step of a wear run (cycles): the error control has failed (above).
inline constexpr double kMinJump = 1e-6;

class ImplicitWearStepper {
 public:
  using state_type = std::vector<double>;
  using deriv_type = std::vector<double>;
  using value_type = double;
  using time_type = double;
  using order_type = unsigned short;
  using stepper_category = boost::numeric::odeint::controlled_stepper_tag;

  // c: the rate coefficient of dw/dN = c p s (1/Pa); tolerance: relative, on the worn profile.
  ImplicitWearStepper(double c, double tolerance) : c_(c), tolerance_(tolerance) {}

  static constexpr order_type order() { return 2; }

  // odeint's controlled-stepper interface; `system` is a ContactResponse (or a reference wrapper of one).
  template <class System>
  boost::numeric::odeint::controlled_step_result try_step(System system, state_type& w, time_type& N,
                                                          time_type& dN) {
    ContactResponse& contact = boost::numeric::odeint::unwrap_reference<System>::type::get_reference(system);
    return try_step_impl(contact, w, N, dN);
  }

  // One lagged-slip backward-Euler step of exactly dN from w, without error control (for tests and studies).
  void euler_step(ContactResponse& contact, state_type& w, double dN) {
    CycleResponse r;
    contact.respond(w, r);
    std::vector<double> p = r.p;
    state_type out;
    if (!euler(contact, w, r.slip_if_touching(), dN, p, out))
      throw ImplicitSolveFailure("wear: the contact-implicit solve did not converge");
    w = out;
  }

  const ImplicitStepperStats& stats() const { return stats_; }
  // The state at a step boundary (after an accepted step, or before the first), and its restoration.
  ImplicitStepperState state() const { return {stats_, p_full_, p_half_}; }
  void restore(const ImplicitStepperState& s) {
    stats_ = s.stats;
    p_full_ = s.p_full;
    p_half_ = s.p_half;
    response_valid_ = false;
  }
  // The response at the last accepted state (valid after a step), to spare the observer a solve.
  const CycleResponse* last_response() const { return response_valid_ ? &response_ : nullptr; }

 private:
  boost::numeric::odeint::controlled_step_result try_step_impl(ContactResponse& contact, state_type& w,
                                                               time_type& N, time_type& dN);
  // One lagged-slip backward-Euler step of size dN from w with slip s; p is the warm start and the result. False
  // when its solve did not converge.
  bool euler(ContactResponse& contact, const state_type& w, const std::vector<double>& s, double dN,
             std::vector<double>& p, state_type& out);

  double c_, tolerance_;
  ImplicitStepperStats stats_;
  CycleResponse response_;          // at state_at_ (valid when response_valid_)
  state_type state_at_;
  bool response_valid_ = false;
  std::vector<double> p_full_, p_half_, d_;
  state_type w_full_, w_half_, w_two_;
  CycleResponse half_;
};

// Adapts a ContactResponse reference for odeint's system argument.
struct ResponseRef {
  ContactResponse* contact;
  static ContactResponse& get_reference(ResponseRef r) { return *r.contact; }
};

}  // namespace fretwear::wear
