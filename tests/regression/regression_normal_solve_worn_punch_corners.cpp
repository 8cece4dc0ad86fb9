// Regression: a similar Hertz wear run on the incremental route at Q/fP = 0.97 (f = 0.5, 1024 cells, 10^5 cycles)
// stopped with exit 3 at 4942 cycles: "the normal solve on the worn profile stopped (max_iterations) with residual
// 0.00537". Its stick zone, 68 cells wide, stood 0.11 µm proud of the worn slip zones with a one-cell step at each
// edge, which carries some 7 GPa (a flat punch's corners), while the worn zones touch at tens of MPa. From the
// stepper's warm start the preconditioned run reached 2e-3 in four iterations and then cycled between working sets,
// the plain run started where it stopped cycled likewise, and so did both from the cold start (25 485 iterations in
// all). Plain constrained CG from the caller's own warm start converges, and NormalSolver::solve now tries it before
// the cold start. The data is the captured solve: the worn gap g0 + w and the warm start p per cell.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "support.hpp"

using namespace fretwear;

namespace {

constexpr int kCells = 1024;
constexpr double kXMin = -0.00027986628047502979, kXMax = 0.00028316529360440261, kP = 1e5;

struct Captured {
  std::vector<double> gap, p;
};

Captured read_captured() {
  std::ifstream in(FRETWEAR_SOURCE_DIR "/tests/regression/data/worn_punch_corners.csv");
  REQUIRE(in);
  Captured c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'g') continue;  // comments and the header
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double g = 0.0, p = 0.0;
    row >> g >> p;
    REQUIRE(row);
    c.gap.push_back(g);
    c.p.push_back(p);
  }
  REQUIRE(int(c.gap.size()) == kCells);
  return c;
}

}  // namespace

TEST_CASE("the normal solve of a contact worn to a punch with sharp corners converges from the stepper's start") {
  const Captured c = read_captured();
  const Grid grid{kXMin, kXMax, kCells};
  const ElasticPair pair({200e9, 0.3}, {200e9, 0.3}, PlaneState::strain);
  const HalfPlaneKernel kernel(grid, pair.A());
  NormalSolverOptions worn;  // the wear stage's cycle solves (engine/wear_contacts.hpp)
  worn.proportioning = kWearProportioning;
  const NormalSolver solver(kernel, worn);

  ContactState warm;
  warm.p = c.p;
  const SolveSummary s = solver.solve(c.gap, kP, warm);
  CAPTURE(s.brief());
  REQUIRE(s.converged());

  // The same solution by another path: plain constrained CG alone from the same start.
  NormalSolverOptions plain = worn;
  plain.preconditioner = NormalSolverOptions::Preconditioner::none;
  ContactState other;
  other.p = c.p;
  const SolveSummary so = NormalSolver(kernel, plain).solve(c.gap, kP, other);
  CAPTURE(so.brief());
  REQUIRE(so.converged());
  const double p_max = *std::max_element(warm.p.begin(), warm.p.end());
  CHECK(test::max_abs_diff(warm.p, other.p) <= 1e-6 * p_max);

  // The punch's corners carry the peak: the first and the last cell of the stick zone standing proud.
  const auto peak = std::max_element(warm.p.begin(), warm.p.end()) - warm.p.begin();
  const int step_left = 475, step_right = 542;  // where the gap drops by 0.11 µm from one cell to the next
  CHECK((peak == step_left || peak == step_right));
  CHECK(c.gap[step_left - 1] - c.gap[step_left] > 1e-7);
  CHECK(c.gap[step_right + 1] - c.gap[step_right] > 1e-7);
}
