// Regression: near its limit, a 4096-cell Hertz wear run (examples/hertz_wear.json at 4096 cells) spent 10 of its
// 17 s in about 50 contact-implicit solves of 1000–1800 iterations each, and three did not converge at all. The
// worn zones then hold hundreds of cells at zero gap and zero pressure; each iteration some of them overlapped by
// 1e-15 m, re-entered, and restarted CG, so the preconditioned iteration stalled and the plain one crawled.
// Proportioning (Dostál's test, NormalSolverOptions::proportioning) lets such cells in only when their overlap
// matters against the gradient on the contact set. The data is one of the solves that did not converge, captured
// from that run: n, P, then per cell the gap g0 + w, the shift d = ΔN k s, and the warm start p, as raw doubles.
#include <doctest/doctest.h>

#include <cstdint>
#include <fstream>
#include <vector>

#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"
#include "scenes.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

struct Captured {
  double P = 0.0;
  std::vector<double> gap, shift, p;
};

Captured read_captured(int n) {
  std::ifstream in(FRETWEAR_SOURCE_DIR "/tests/regression/data/worn_zone_reentry.bin", std::ios::binary);
  REQUIRE(in);
  std::int32_t cells = 0;
  Captured c;
  in.read(reinterpret_cast<char*>(&cells), sizeof cells);
  in.read(reinterpret_cast<char*>(&c.P), sizeof c.P);
  REQUIRE(cells == n);
  for (auto* v : {&c.gap, &c.shift, &c.p}) {
    v->resize(std::size_t(n));
    in.read(reinterpret_cast<char*>(v->data()), std::streamsize(n * sizeof(double)));
  }
  REQUIRE(in);
  return c;
}

}  // namespace

TEST_CASE("a contact-implicit solve with hundreds of degenerate worn cells converges with proportioning") {
  Scene s = test::hertz_wear(1e5, 0.5, 1e7, 4096);
  s.name = "reentry";
  const Model m = make_model(s);
  const Captured c = read_captured(m.grid.n);
  REQUIRE(c.P == s.P);

  // Without proportioning (Polonsky and Keer's re-entry) the constrained CG stalls on this solve (200 iterations
  // without halving its best residual), and plain constrained CG does not converge on it in a thousand iterations:
  // the solve converges only through the active-set fallback after that stall (291 iterations in all, measured).
  NormalSolverOptions plain;
  plain.max_iterations = 1000;
  ContactState stalled;
  stalled.p = c.p;
  const SolveSummary hard = NormalSolver(*m.kernel, plain).solve(c.gap, c.P, stalled, c.shift);
  CHECK(hard.iterations > 200);

  // With the wear stage's options it converges in tens of iterations (65 when this test was written).
  NormalSolverOptions worn;
  worn.proportioning = kWearProportioning;
  ContactState state;
  state.p = c.p;
  const SolveSummary summary = NormalSolver(*m.kernel, worn).solve(c.gap, c.P, state, c.shift);
  CHECK(summary.converged());
  CHECK(summary.iterations <= 200);
  // The load is carried and the contact conditions hold to the tolerance, with the shift in the gap.
  double load = 0.0;
  for (double pi : state.p) load += m.grid.h() * pi;
  CHECK(load == test::rel(c.P, 1e-12));
}
