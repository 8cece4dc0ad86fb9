// The normal solver against closed forms for every profile family (PHYSICS.md, "Normal contact" and the rounded-punch
// table): the rounded punch, the sharp flat punch, several zones (a waviness on a cylinder, two separate asperities),
// tilt, plane stress, and the observed order of convergence as the grid is refined.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include <doctest/doctest.h>

#include "contact/closed_form.hpp"
#include "contact/normal_solver.hpp"
#include "engine/simulation.hpp"
#include "scenes.hpp"

using namespace fretwear;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kE = 200e9, kNu = 0.3, kR = 0.01;
// The load–size integral and its root find are converged to round-off (load_size.hpp: ~1e-13 relative).
constexpr double kLoadSizeTolerance = 1e-12;
// The solver balances the load to round-off at every iterate: h Σ p = P to a few ulps per cell summed.
constexpr double kLoadBalance = 1e-12;
// The square-root fit extrapolates p² from the two cells inside the outermost loaded one; for a resolved edge it
// lands within half a cell of the closed form (its own error is O(h²/b), the solver's pressure error there O(h)·h).
constexpr double kEdgeCells = 0.5;
// The solver's stopping tolerance on the complementarity residual (normal_solver.hpp).
const double kSolverTolerance = NormalSolverOptions{}.tolerance;

double A_strain() { return ElasticPair({kE, kNu}, {kE, kNu}, PlaneState::strain).A(); }

Scene scene(const ProfileSpec& profile, double P, int cells) {
  return test::normal_scene(profile, P, cells, "verification");
}

ProfileSpec cylinder(double offset = 0.0) { return test::cylinder(offset); }

double load_of(const NormalResult& r, int first, int last) {
  double load = 0.0;
  for (int i = first; i <= last; ++i) load += r.state.p[i] * r.grid.h();
  return load;
}

double total_load(const NormalResult& r) { return load_of(r, 0, r.grid.n - 1); }

bool all_finite(const NormalResult& r) {
  return std::all_of(r.state.p.begin(), r.state.p.end(), [](double p) { return std::isfinite(p) && p >= 0.0; });
}

// Peak sampling: cell centres lie within h/2 of a smooth peak whose curvature length is ℓ (p″ ≈ p/ℓ²), so the
// largest cell value falls short of it by at most (h/2)²/(2ℓ²) relative; we allow twice that, plus the solver's
// tolerance.
double peak_tolerance(double h, double ell) { return 0.25 * (h / ell) * (h / ell) + 10.0 * kSolverTolerance; }

}  // namespace

TEST_CASE("rounded punch at the table's four a/b: half-width, p_max, and the load–size integral") {
  // b fixed, P from P A R / b² = D(φ0)/2; 1024 cells over the load–size window x_low ± 1.5 b put ~680 cells in
  // contact. The peak's curvature length is the rounded corner's width b − a.
  const double A = A_strain(), b = 0.2e-3;
  for (double a_over_b : {0.25, 0.5, 0.75, 0.9}) {
    CAPTURE(a_over_b);
    ProfileSpec spec;
    spec.type = ProfileType::flat_rounded;
    spec.a = a_over_b * b;
    spec.R = kR;
    const double P = 0.5 * closed_form::D(std::asin(a_over_b)) * b * b / (A * kR);
    const NormalResult r = solve_normal(scene(spec, P, 1024));
    const auto rp = closed_form::rounded_punch(P, A, spec.a, kR);
    REQUIRE(r.zones.size() == 1);
    const Zone& z = r.zones.front();
    const double h = r.grid.h();
    CHECK(z.left.method == EdgeMethod::square_root_fit);
    CHECK(z.right.method == EdgeMethod::square_root_fit);
    CHECK(std::abs(z.left.x + b) <= kEdgeCells * h);
    CHECK(std::abs(z.right.x - b) <= kEdgeCells * h);
    CHECK(std::abs(r.p_max / rp.peak() - 1.0) <= peak_tolerance(h, b - spec.a));
    CHECK(std::abs(std::abs(r.x_p_max) - rp.peak_x()) <= h);
    REQUIRE(r.load_size_half_width);
    CHECK(std::abs(*r.load_size_half_width / b - 1.0) <= kLoadSizeTolerance);
    CHECK(std::abs(total_load(r) / P - 1.0) <= kLoadBalance);
  }
}

TEST_CASE("sharp flat punch: the load, p = P/(π√(b² − x²)) away from the corners, edges at the corners") {
  const double b = 0.5e-3, P = 1e5;
  ProfileSpec spec;
  spec.type = ProfileType::flat;
  spec.b = b;
  const NormalResult r = solve_normal(scene(spec, P, 1024));
  const double h = r.grid.h();
  REQUIRE(r.zones.size() == 1);
  const Zone& z = r.zones.front();
  CHECK(z.left.method == EdgeMethod::corner);
  CHECK(z.right.method == EdgeMethod::corner);
  // The window is aligned so that the corners are cell boundaries: the edges are the corners to round-off.
  CHECK(std::abs(z.left.x + b) <= 1e-9 * h);
  CHECK(std::abs(z.right.x - b) <= 1e-9 * h);
  CHECK(std::abs(total_load(r) / P - 1.0) <= kLoadBalance);
  const auto fp = closed_form::flat_punch(P, b);
  // Away from the corners (|x| < b/2, ~170 cells from them) the pressure varies on the scale b, and piecewise-
  // constant collocation matches its cell averages to first order in h/b.
  const double kInterior = 0.5 * b;
  const double tolerance = h / b;
  double worst = 0.0;
  for (int i = 0; i < r.grid.n; ++i) {
    const double x = r.grid.x(i);
    if (std::abs(x) >= kInterior) continue;
    const double want = fp.cell_average(r.grid.left(i), r.grid.left(i + 1));
    worst = std::max(worst, std::abs(r.state.p[i] / want - 1.0));
  }
  CAPTURE(worst);
  CHECK(worst <= tolerance);
}

TEST_CASE("a waviness on a cylinder gives several zones, mirrored about the centre, carrying the load") {
  // Hertz alone: a = 0.108 mm, approach ~ A P = 1.8 µm. A waviness of 0.5 µm at a wavelength of 40 µm opens gaps
  // between its crests inside the Hertz zone.
  ProfileSpec wavy;
  wavy.type = ProfileType::wavy;
  wavy.amplitude = 0.5e-6;
  wavy.wavelength = 40e-6;
  ProfileSpec spec;
  spec.type = ProfileType::sum;
  spec.terms = {cylinder(), wavy};
  const double P = 1e5;
  const NormalResult r = solve_normal(scene(spec, P, 4096));
  CHECK(all_finite(r));
  CHECK(r.zones.size() >= 3);
  CHECK(r.zones.size() % 2 == 1);  // g0 is even: a central zone and mirrored pairs
  CHECK(std::abs(total_load(r) / P - 1.0) <= kLoadBalance);
  const double h = r.grid.h();
  for (std::size_t k = 0; k < r.zones.size(); ++k) {
    const Zone& z = r.zones[k];
    const Zone& m = r.zones[r.zones.size() - 1 - k];
    CHECK(z.left.method == EdgeMethod::square_root_fit);
    CHECK(z.right.method == EdgeMethod::square_root_fit);
    // The grid is symmetric about 0 only to within a cell, so mirrored edges agree to about a cell.
    CHECK(std::abs(z.left.x + m.right.x) <= 2.0 * kEdgeCells * h + 1e-3 * h);
  }
}

TEST_CASE("two far-apart cylinders (an envelope): each zone is Hertz under half the load") {
  // Each zone feels the other's pressure as u = −(A/π)(P/2) ln|x − ξ|, i.e. a tilt of slope −A P/(4π d) at distance
  // 2d, which moves each zone outward by A P R/(4π d) (a tilted cylinder shifts by −tilt·R): 7e-7 m here, 9 % of a
  // cell, checked with the edges. The curvature of that field changes a by (R A P/(8π d²)), below 1e-5 relative.
  const double A = A_strain(), P = 1e5, d = 2e-3;
  ProfileSpec spec;
  spec.type = ProfileType::envelope;
  spec.terms = {cylinder(-d), cylinder(d)};
  const NormalResult r = solve_normal(scene(spec, P, 8192));
  CHECK(all_finite(r));
  REQUIRE(r.zones.size() == 2);
  const auto hz = closed_form::hertz(0.5 * P, A, kR);
  const double h = r.grid.h(), shift = A * P * kR / (4.0 * kPi * d);
  CHECK(hz.a / h > 50.0);  // resolved
  for (int k = 0; k < 2; ++k) {
    CAPTURE(k);
    const Zone& z = r.zones[k];
    const double centre = (k == 0 ? -1.0 : 1.0) * (d + shift);
    CHECK(z.left.method == EdgeMethod::square_root_fit);
    CHECK(std::abs(z.left.x - (centre - hz.a)) <= kEdgeCells * h);
    CHECK(std::abs(z.right.x - (centre + hz.a)) <= kEdgeCells * h);
    // Each zone's share: the two carry P/2 each by symmetry; the grid's sub-cell placement of the two zones differs,
    // which changes a zone's discrete stiffness by O(h/a) of its load.
    CHECK(std::abs(load_of(r, z.first_cell, z.last_cell) / (0.5 * P) - 1.0) <= h / hz.a);
    double p_max = 0.0;
    for (int i = z.first_cell; i <= z.last_cell; ++i) p_max = std::max(p_max, r.state.p[i]);
    CHECK(std::abs(p_max / hz.p0 - 1.0) <= peak_tolerance(h, hz.a) + h / hz.a);
  }
}

TEST_CASE("a tilted cylinder is a Hertz contact shifted to −tilt·R") {
  const double A = A_strain(), P = 1e5;
  const auto hz = closed_form::hertz(P, A, kR);
  for (double tilt : {2e-3, -5e-3}) {
    CAPTURE(tilt);
    ProfileSpec spec = cylinder();
    spec.tilt_rad = tilt;
    const NormalResult r = solve_normal(scene(spec, P, 1024));
    REQUIRE(r.zones.size() == 1);
    const Zone& z = r.zones.front();
    const double h = r.grid.h(), centre = -tilt * kR;
    CHECK(r.window.method == "trial_solve");
    CHECK(std::abs(z.left.x - (centre - hz.a)) <= kEdgeCells * h);
    CHECK(std::abs(z.right.x - (centre + hz.a)) <= kEdgeCells * h);
    CHECK(std::abs(r.p_max / hz.p0 - 1.0) <= peak_tolerance(h, hz.a));
    CHECK(std::abs(r.x_p_max - centre) <= h);
    CHECK(std::abs(total_load(r) / P - 1.0) <= kLoadBalance);
    // The window covers the contact with a margin of about half its half-width each side (SCENES.md, "Grid").
    CHECK(r.grid.x_min < centre - 1.4 * hz.a);
    CHECK(r.grid.x_max > centre + 1.4 * hz.a);
  }
}

TEST_CASE("plane stress with E replaced so that A matches gives the plane-strain contact") {
  // Plane strain: A = 4(1 − ν²)/E; plane stress: A = 4/E′. With E′ = E/(1 − ν²) the two discrete problems agree to
  // round-off in A, so the solutions agree to the solver's tolerance.
  Scene strain = scene(cylinder(), 1e5, 1024);
  Scene stress = strain;
  stress.plane = PlaneState::stress;
  stress.pad = stress.specimen = {kE / (1.0 - kNu * kNu), kNu};
  const NormalResult a = solve_normal(strain), b = solve_normal(stress);
  const double A = A_strain();
  CHECK(std::abs(ElasticPair(stress.pad, stress.specimen, stress.plane).A() / A - 1.0) <= 4.0 * kEps);
  REQUIRE(a.grid.n == b.grid.n);
  CHECK(std::abs(a.grid.x_min / b.grid.x_min - 1.0) <= kLoadSizeTolerance);
  // The stopping test allows a gap error of tolerance · g_max on each cell; the pressure that corrects a gap error δg
  // on one cell is δg / K_ii with K_ii ≥ A h / π, so two stopped solves may differ by π · tolerance · g_max / (A h).
  const double g_max = *std::max_element(a.g0.begin(), a.g0.end());
  const double dp = kPi * kSolverTolerance * g_max / (A * a.grid.h());
  double worst = 0.0;
  for (int i = 0; i < a.grid.n; ++i) worst = std::max(worst, std::abs(a.state.p[i] - b.state.p[i]));
  CHECK(worst <= dp);
  REQUIRE(a.zones.size() == 1);
  REQUIRE(b.zones.size() == 1);
  CHECK(a.zones[0].first_cell == b.zones[0].first_cell);
  CHECK(a.zones[0].last_cell == b.zones[0].last_cell);
  // And a plane-stress pair with the strain pair's E is softer by 1/(1 − ν²): a grows by 1/√(1 − ν²).
  Scene soft = strain;
  soft.plane = PlaneState::stress;
  const NormalResult c = solve_normal(soft);
  REQUIRE(c.reference);
  CHECK(c.reference->extent_error <= kEdgeCells * c.grid.h() / c.reference->half_width);
  CHECK(std::abs(c.reference->half_width / a.reference->half_width - 1.0 / std::sqrt(1.0 - kNu * kNu)) <= 1e-14);
}

TEST_CASE("convergence rate: the L1 pressure error of Hertz falls like h^(3/2)") {
  // With the window [−2a, 2a] the edges ±a are cell boundaries at every n, so the error's leading term keeps one
  // constant as the grid doubles. That term comes from the O(1) cells at each edge where p ~ p0 √(h/a) is not
  // resolved by a constant: each contributes h · p0 √(h/a) to ∫|p − p̄|, so ‖p − p̄‖₁ = O(h^{3/2}). The interior's
  // O(h²) error is relatively (h/a)^{1/2} smaller; at the coarsest grid here (h = a/32) it can move an observed order
  // by a few hundredths, so we require 1.5 ± 0.1. The grids stop at 2048 cells: the solver's stopping tolerance
  // (1e-8 on its residual) leaves an error floor near 2e-6 p0 a, which 4096 cells begin to reach.
  const double A = A_strain(), P = 1e5;
  const auto hz = closed_form::hertz(P, A, kR);
  constexpr double kExpectedOrder = 1.5, kOrderMargin = 0.1;
  double previous = 0.0;
  for (int n = 128; n <= 2048; n *= 2) {
    CAPTURE(n);
    Scene s = scene(cylinder(), P, n);
    s.window = std::pair(-2.0 * hz.a, 2.0 * hz.a);
    const NormalResult r = solve_normal(s);
    double error = 0.0;
    for (int i = 0; i < n; ++i)
      error += std::abs(r.state.p[i] - hz.cell_average(r.grid.left(i), r.grid.left(i + 1))) * r.grid.h();
    error /= hz.p0 * hz.a;
    if (previous > 0.0) {
      const double order = std::log2(previous / error);
      CAPTURE(order);
      CHECK(std::abs(order - kExpectedOrder) <= kOrderMargin);
    }
    previous = error;
  }
}
