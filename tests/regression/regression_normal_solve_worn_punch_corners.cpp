// Regression: wear runs near the stick limit on fine grids stopped with exit 3, "the normal solve on the worn
// profile stopped (max_iterations)": a similar Hertz run on the incremental route at Q/fP = 0.97 (f = 0.5, 1024
// cells) at 4942 cycles, and a steel-on-aluminium one at f = 0.9, Q/fP = 0.99 (1024 cells) after 6.3e6 cycles. Each
// worn contact is a stick zone standing 0.1–0.5 µm proud of the worn slip zones, its edges one-cell steps that carry
// several GPa like a flat punch's corners, beside hundreds of worn cells in light contact or at zero gap and zero
// pressure. The constrained CG's working set took those cells in at once and shed them a few an iteration, over and
// over, preconditioned or plain, from the warm and from the cold start (some 25 000 iterations in all). NormalSolver
// now tries the active-set iteration, whose pressure the constrained CG then accepts at its first iteration. The
// data are the captured solves: the worn gap g0 + w and the stepper's warm start p per cell (and a contact-implicit
// solve's shift).
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr int kCells = 1024;
constexpr double kP = 1e5;

// The captured solve converges from the stepper's start and from the cold start, to the same pressure as another
// path reaches; the peak sits on a corner of the proud stick zone, [first, last], whose edges are steps of more than
// 0.1 µm.
void check(const test::CapturedSolve& c, const Grid& grid, const ElasticPair& pair, int first, int last) {
  const HalfPlaneKernel kernel(grid, pair.A());
  NormalSolverOptions worn;  // the wear stage's cycle solves (engine/wear_contacts.hpp)
  worn.proportioning = kWearProportioning;
  const NormalSolver solver(kernel, worn);

  ContactState warm;
  warm.p = c.p;
  const SolveSummary s = solver.solve(c.gap, kP, warm);
  CAPTURE(s.brief());
  REQUIRE(s.converged());
  ContactState cold;
  const SolveSummary sc = solver.solve(c.gap, kP, cold);
  CAPTURE(sc.brief());
  REQUIRE(sc.converged());

  // Another path: the constrained CG with a reluctant proportioning (Γ = 3) converges on these two on its own, in
  // its first run (its fallbacks, the active set among them, would take thousands of iterations), here to a
  // hundredth of the tolerance: at the tolerance itself its pressure is off by 1.2e-6 of the peak at the corners,
  // where the active set's answer (residual 2e-10) and this one agree to 3e-8.
  NormalSolverOptions reluctant = worn;
  reluctant.proportioning = 3.0;
  reluctant.tolerance = 1e-2 * worn.tolerance;
  ContactState other;
  other.p = c.p;
  const SolveSummary so = NormalSolver(kernel, reluctant).solve(c.gap, kP, other);
  CAPTURE(so.brief());
  REQUIRE(so.converged());
  CHECK(so.iterations < 500);
  const double p_max = *std::max_element(warm.p.begin(), warm.p.end());
  CHECK(test::max_abs_diff(warm.p, other.p) <= 1e-7 * p_max);
  CHECK(test::max_abs_diff(cold.p, other.p) <= 1e-7 * p_max);

  const auto peak = std::max_element(warm.p.begin(), warm.p.end()) - warm.p.begin();
  CHECK((peak == first || peak == last));
  CHECK(c.gap[first - 1] - c.gap[first] > 1e-7);
  CHECK(c.gap[last + 1] - c.gap[last] > 1e-7);
}

}  // namespace

TEST_CASE("the normal solve of a contact worn to a punch with sharp corners converges (similar, incremental route)") {
  const Grid grid{-0.00027986628047502979, 0.00028316529360440261, kCells};
  check(test::read_captured_solve("worn_punch_corners.csv", kCells), grid,
        ElasticPair({200e9, 0.3}, {200e9, 0.3}, PlaneState::strain), 475, 542);
}

TEST_CASE("the normal solve of a contact worn to a punch with sharp corners converges (dissimilar)") {
  // Here the worn zones hold cells at zero gap and zero pressure whose overlap is round-off (1e-15 m). An active set
  // that dropped such a cell at p = 0 and took it back at g < 0 cycled between two sets after eight; it keeps a cell
  // at p = 0 and takes one in only past the equality solves' gap error (either rule alone settles this case).
  const Grid grid{-0.00042288660020773727, 0.00042288660020773749, kCells};
  check(test::read_captured_solve("worn_punch_corners_dissimilar.csv", kCells), grid,
        ElasticPair({200e9, 0.3}, {71e9, 0.33}, PlaneState::strain), 494, 529);
}

TEST_CASE("a contact-implicit solve on a contact worn to a punch converges within its iteration limit (dissimilar)") {
  // The same run at 2048 cells stopped with exit 3: its contact-implicit solves (the operator K + diag(ΔN c s), at
  // most max(2000, cells) iterations: engine/wear_contacts.hpp) spent their limit in the plain run after the stalled
  // preconditioned one, and the stepper retried ever smaller jumps, down to 0.39 cycles. The active set goes before
  // the plain run, and settles this captured solve (1024 cells) in 281 iterations in all; with the plain run first,
  // from where the preconditioned run stalled, the solve stops at the limit (2201 iterations, residual 0.097).
  const Grid grid{-0.00042288660020773727, 0.00042288660020773749, kCells};
  const test::CapturedSolve c = test::read_captured_solve("worn_punch_corners_implicit.csv", kCells);
  REQUIRE(int(c.shift.size()) == kCells);
  const HalfPlaneKernel kernel(grid, ElasticPair({200e9, 0.3}, {71e9, 0.33}, PlaneState::strain).A());
  NormalSolverOptions implicit;  // WearContact::implicit_options(1024)
  implicit.proportioning = kWearProportioning;
  implicit.max_iterations = 2000;

  ContactState warm;
  warm.p = c.p;
  const SolveSummary s = NormalSolver(kernel, implicit).solve(c.gap, kP, warm, c.shift);
  CAPTURE(s.brief());
  REQUIRE(s.converged());
  CHECK(s.iterations > 200);  // the preconditioned run stalled: this is a fallback's solve
  CHECK(s.iterations < 500);
  double load = 0.0;
  for (double pi : warm.p) load += grid.h() * pi;
  CHECK(load == test::rel(kP, 1e-12));
}
