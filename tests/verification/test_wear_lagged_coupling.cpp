// The lagged coupling of a dissimilar wear run (engine/wear_contacts.hpp, IncrementalContactResponse): most cycle
// responses take an uncoupled cycle on the worn profile (the analogy's; under a load history the marched one of
// β = 0) plus the coupling's share of the slip from the last coupled cycle, refreshed as the uncoupled wear rate
// moves. It must not change the run: the same contact-
// implicit stepper driven by it and by a response that solves the coupled cycle every time wears the same profile,
// to the stepper's tolerance, and keeps the same stick zone. And it must not change a resumed run: what decides
// its refreshes goes through the checkpoint (save() and restore()), so a restored response answers as the
// uninterrupted one, to the bit.
//
// The case: PHYSICS.md's Hertz wear case (P = 1e5 N/m, Q/fP = 0.5, f = 0.5, Archard k = 1e-12) with a steel pad on
// an aluminium specimen (E = 71 GPa, ν = 0.33; β ≈ −0.11), 128 cells, recorded at 10^3 cycles (the transient) and at
// 10^5 (past the knee, where the worn slip zones approach the limit and the contact's edges move).
#include <algorithm>
#include <cmath>
#include <vector>

#include <doctest/doctest.h>

#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "scenes.hpp"
#include "support.hpp"
#include "wear/implicit_stepper.hpp"

using namespace fretwear;

namespace {

constexpr int kCells = 128;
constexpr double kStepperTolerance = 1e-3;  // effects.wear.tolerance's default, the runs' and the comparison's
// Cell by cell, off the contact (measured: up to 3.1e-3, at the cell beside the contact's edge); on the contact the
// slip differs by up to 0.44 of its own value, at the stick zone's edges where it is small.
constexpr double kTouchingAgreement = 1e-2;

struct Run {
  std::vector<double> w;
  wear::CycleResponse last;
  double Q = 0.0;  // Q at the top of that response's cycle (N/m)
};

// The stepper from the unworn profile to each of `times`, as the wear stage drives it (first jump: one cycle).
std::vector<Run> march(IncrementalContactResponse& contact, double c, const std::vector<double>& times) {
  wear::ImplicitWearStepper stepper(c, kStepperTolerance);
  std::vector<Run> out;
  std::vector<double> w(std::size_t(kCells), 0.0);
  double N = 0.0, dN = 1.0;
  for (double end : times) {
    while (N < end) {
      double step = std::min(dN, end - N);
      stepper.try_step(wear::ResponseRef{&contact}, w, N, step);
      dN = step;  // the next jump the stepper asks for, or after a rejection the smaller one to try
    }
    Run r;
    r.w = w;
    contact.respond(w, r.last);
    r.Q = contact.Q_top();
    out.push_back(std::move(r));
  }
  return out;
}

double area(const std::vector<double>& w, double h) {
  double a = 0.0;
  for (double x : w) a += h * x;
  return a;
}

}  // namespace

enum class Load { force, displacement, history };

struct Case {
  // Force control at Q/fP = 0.5; displacement control at δ = 1 µm (Q/fP = 0.48 in the first cycle, falling as the
  // slip zones wear), where the lag's uncoupled cycle is the analogy's at the Q that reaches δ and Q_top is
  // corrected alike; or a load history with P out of phase with Q (P from 70 to 130 N/mm while Q swings ±25 N/mm),
  // where the lag's uncoupled cycle is the marched one of β = 0 through the same history.
  explicit Case(Load load = Load::force)
      : scene([load] {
          Scene s = test::hertz_wear(1e5, 0.5, 1e5, kCells);
          s.specimen = {71e9, 0.33};
          if (load == Load::displacement) {
            s.Q_ratio.reset();
            s.control = LoadControl::displacement;
            s.delta = 1e-6;
          }
          if (load == Load::history) {
            s.Q_ratio.reset();
            s.history = {{0, 1e5, 2.5e4, 0}, {1, 7e4, 0, 0}, {2, 1e5, -2.5e4, 0}, {3, 1.3e5, 0, 0}, {4, 1e5, 2.5e4, 0}};
          }
          return s;
        }()),
        model(make_model(scene)),
        normal(solve_normal(scene, model)),
        cycle(solve_cycle(scene, model, normal)) {}
  Scene scene;
  Model model;
  NormalResult normal;
  CycleStage cycle;
};

TEST_CASE("the lagged coupling wears the coupled run's profile to the stepper's tolerance") {
  for (const Load load : {Load::force, Load::displacement, Load::history}) {
  CAPTURE(int(load));
  const Case the_case(load);
  const Scene& s = the_case.scene;
  const Model& model = the_case.model;
  const CycleStage& cycle = the_case.cycle;
  REQUIRE(cycle.plan.beta != 0.0);
  const double c = s.wear->coefficient;  // Archard: c = k
  const std::vector<double> times{1e3, 1e5};

  IncrementalContactResponse lagged(s, model, cycle, IncrementalContactResponse::Coupling::lagged);
  IncrementalContactResponse coupled(s, model, cycle, IncrementalContactResponse::Coupling::every_response);
  const std::vector<Run> fast = march(lagged, c, times);
  const std::vector<Run> full = march(coupled, c, times);

  // The lagged run is the faster one: most of its responses took the correction.
  CHECK(lagged.lagged_responses() > lagged.coupled_responses());
  CHECK(coupled.lagged_responses() == 0);
  MESSAGE("responses coupled ", lagged.coupled_responses(), ", lagged ", lagged.lagged_responses());
  const double h = model.grid.h();
  for (std::size_t k = 0; k < times.size(); ++k) {
    CAPTURE(times[k]);
    const double a_full = area(full[k].w, h), a_fast = area(fast[k].w, h);
    const double d_full = *std::max_element(full[k].w.begin(), full[k].w.end());
    const double d_fast = *std::max_element(fast[k].w.begin(), fast[k].w.end());
    REQUIRE(a_full > 0.0);
    CHECK(std::abs(a_fast - a_full) <= kStepperTolerance * a_full);
    CHECK(std::abs(d_fast - d_full) <= kStepperTolerance * d_full);
    CHECK(fast[k].last.has_stick == full[k].last.has_stick);
    // The lagged stick zone is the last refresh's: its edges (interpolated between cells) lag by what the profile
    // moved them since, within the tolerance of their distance from the centre.
    CHECK(std::abs(fast[k].last.stick_left - full[k].last.stick_left) <=
          kStepperTolerance * std::abs(full[k].last.stick_left));
    CHECK(std::abs(fast[k].last.stick_right - full[k].last.stick_right) <=
          kStepperTolerance * std::abs(full[k].last.stick_right));
    // Under displacement control Q is a result: the lagged one is the analogy's plus the last refresh's share.
    CHECK(fast[k].Q == test::rel(full[k].Q, kStepperTolerance));
    // Off the contact the slip on touching, which the contact-implicit step takes for the cells it loads: the
    // analogy's plus the last refresh's share there, against the coupled cycle's own, cell by cell; and on the
    // contact the slip, for scale.
    const std::vector<double>& t_fast = fast[k].last.slip_if_touching();
    const std::vector<double>& t_full = full[k].last.slip_if_touching();
    double touching_apart = 0.0, slip_apart = 0.0;
    for (std::size_t i = 0; i < t_full.size(); ++i) {
      if (fast[k].last.p[i] > 0.0 && full[k].last.p[i] > 0.0 && full[k].last.s[i] > 0.0)
        slip_apart = std::max(slip_apart, std::abs(fast[k].last.s[i] / full[k].last.s[i] - 1.0));
      if (!(full[k].last.p[i] > 0.0) && !(fast[k].last.p[i] > 0.0) && t_full[i] > 0.0)
        touching_apart = std::max(touching_apart, std::abs(t_fast[i] / t_full[i] - 1.0));
    }
    CHECK(touching_apart <= kTouchingAgreement);
    // Under a history neither gives a slip on touching (engine/wear_contacts.cpp says why).
    CHECK(fast[k].last.s_touching.empty() == (load == Load::history));
    CHECK(full[k].last.s_touching.empty() == (load == Load::history));
    MESSAGE("at ", times[k], " cycles: worn area ", a_fast / a_full - 1.0, ", max depth ", d_fast / d_full - 1.0,
            ", Q ", fast[k].Q / full[k].Q - 1.0, ", slip on touching ", touching_apart, " (the slip on the contact ", slip_apart, ")");
  }
  }
}

TEST_CASE("the lagged coupling's state goes through a checkpoint: a restored response answers bit for bit") {
  for (const Load load : {Load::force, Load::displacement, Load::history}) {
  CAPTURE(int(load));
  const Case c(load);
  // Profiles along a run's transient: the worn profile after 10^3 cycles, scaled.
  IncrementalContactResponse run(c.scene, c.model, c.cycle);
  const std::vector<Run> worn = march(run, c.scene.wear->coefficient, {1e3});
  std::vector<std::vector<double>> profiles;
  for (double scale : {0.2, 0.5, 0.5005, 0.501, 0.5015, 0.502, 0.6, 0.6005}) {
    profiles.push_back(worn[0].w);
    for (double& x : profiles.back()) x *= scale;
  }
  IncrementalContactResponse a(c.scene, c.model, c.cycle);
  wear::CycleResponse ra, rb;
  for (std::size_t k = 0; k < 4; ++k) a.respond(profiles[k], ra);
  IncrementalContactResponse b(c.scene, c.model, c.cycle);
  b.restore(a.save());
  rb = ra;  // the stepper hands its last pressure to both as the warm start
  for (std::size_t k = 4; k < profiles.size(); ++k) {
    CAPTURE(k);
    a.respond(profiles[k], ra);
    b.respond(profiles[k], rb);
    CHECK(ra.s == rb.s);
    CHECK(ra.s_touching == rb.s_touching);
    CHECK(ra.p == rb.p);
    CHECK(a.shear_top() == b.shear_top());
    CHECK(a.Q_top() == b.Q_top());
  }
  CHECK(a.lagged_responses() == b.lagged_responses());
  CHECK(a.coupled_responses() == b.coupled_responses());
  CHECK(a.lagged_responses() > 0);  // the sequence exercises the lagged responses
  }
}
