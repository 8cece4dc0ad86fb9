// Regression: a dissimilar wear run at Q/fP = 0.99 (steel on aluminium; rounded wedge, flat_rounded and tilted
// cylinder pads, 256 cells) stopped with exit 3 after some 10^4 cycles: "the normal solve on the worn profile stopped
// (max_iterations) with residual 0.0106". Its stick zone, ten cells wide, stood 0.57 µm proud of the worn slip
// zones: the solution carries the load there at up to 5.9 GPa, and the worn zones touch at about 2 MPa. From the
// warm start, the last response's pressure, the preconditioned run stalled, and the plain constrained CG it fell
// back to cycled for 20 000 iterations: each re-entry at −τ g loaded some 130 cells beside the stick zone far past
// their share, which the next three steps took away again. Both converge from the cold start (20 iterations), and
// NormalSolver::solve now tries it when the plain run stalls. The data is the captured solve: the worn gap g0 + w
// and the warm start p per cell.
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr int kCells = 256;
constexpr double kXMin = -0.00042288660020773727, kXMax = 0.00042288660020773749, kP = 1e5;

}  // namespace

TEST_CASE("the normal solve of a contact worn down to a narrow punch converges from a warm start far from it") {
  const test::CapturedSolve c = test::read_captured_solve("narrow_worn_contact.csv", kCells);
  const Grid grid{kXMin, kXMax, kCells};
  const ElasticPair pair({200e9, 0.3}, {71e9, 0.33}, PlaneState::strain);
  const HalfPlaneKernel kernel(grid, pair.A());
  NormalSolverOptions worn;  // the wear stage's cycle solves (engine/wear_contacts.hpp)
  worn.proportioning = kWearProportioning;
  const NormalSolver solver(kernel, worn);

  ContactState warm;
  warm.p = c.p;
  REQUIRE(std::count_if(warm.p.begin(), warm.p.end(), [](double p) { return p > 0.0; }) == 168);
  const SolveSummary s = solver.solve(c.gap, kP, warm);
  CAPTURE(s.brief());
  CHECK(s.converged());

  // The same contact from the cold start: the stick zone's ten cells carry all but a thousandth of the peak, and
  // the two starts reach the same pressure to the tolerance.
  ContactState cold;
  const SolveSummary sc = solver.solve(c.gap, kP, cold);
  REQUIRE(sc.converged());
  CHECK(sc.iterations < 100);
  const double p_max = *std::max_element(cold.p.begin(), cold.p.end());
  CHECK(std::count_if(cold.p.begin(), cold.p.end(), [p_max](double p) { return p > 1e-3 * p_max; }) == 10);
  CHECK(test::max_abs_diff(warm.p, cold.p) <= 1e-6 * p_max);
}
