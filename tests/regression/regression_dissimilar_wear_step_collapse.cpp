// A dissimilar Hertz wear run (steel on aluminium, β ≈ −0.11, 512 cells, k = 1e-12 1/Pa) cut its wear jump to
// 1e-307 cycles near the limit and ran on without end: the slip handed to the stepper, e / (f p_ref), divides the
// coupled cycle's energy by the uncoupled pressure under P, and where the coupled cycle still loads cells that the
// worn contact under P has left, that ratio of two small pressures swung from step to step (engine/wear_contacts.hpp).
// It is capped now, and a stepper whose error estimate does not fall with its jump stops with a ConvergenceError
// (wear/implicit_stepper.hpp) instead of running for ever.
#include <doctest/doctest.h>

#include "engine/simulation.hpp"
#include "scenes.hpp"

using namespace fretwear;

TEST_CASE("dissimilar wear near the limit keeps its step, and the transient is the energy's") {
  // 10^5 cycles recorded at 500 and at the end: the stall began after some 6 000. Under the cap the run takes
  // about 130 steps (bound: kMaxSteps).
  constexpr int kMaxSteps = 250;
  Scene s = test::hertz_wear(1e5, 0.5, 1e5, 512);
  s.specimen = {71e9, 0.33};
  s.wear->record = {500.0, 1e5};
  const RunResult r = Simulation(s).run();
  REQUIRE(r.wear);
  CHECK_FALSE(r.wear->interrupted);
  CHECK(r.wear->cycles_reached == 1e5);
  CHECK(r.wear->steps < kMaxSteps);
  // Far from the limit the cap does not bind (p_ref ≥ p̄/2 on every slipping cell): the first record, at 500
  // cycles, wears c e / f per cycle exactly; against the energy of the unworn cycle, the worn area after N cycles
  // is N c ∫ e dx / f to the first order while the contact barely changes (kTransient covers the change).
  constexpr double kTransient = 0.05;
  const WearRecord& first = r.wear->records.at(1);
  double energy = 0.0;
  for (double e : r.cycle->result.energy_density) energy += e;
  energy *= make_model(s).grid.h();
  const double expected = first.cycles * r.wear->rate_coefficient * energy / *s.friction;
  CAPTURE(first.cycles);
  CHECK(first.worn_area == doctest::Approx(expected).epsilon(kTransient));
}
