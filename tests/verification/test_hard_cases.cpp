// Hard cases of the normal contact: each must converge to a finite, non-negative pressure carrying the load, with
// its edges where the closed form (or the load–size integral) puts them, or be refused with an actionable error.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include <doctest/doctest.h>

#include "contact/closed_form.hpp"
#include "common/error.hpp"
#include "contact/normal_solver.hpp"
#include "engine/simulation.hpp"
#include "scenes.hpp"

using namespace fretwear;

namespace {

constexpr double kE = 200e9, kNu = 0.3, kR = 0.01;
// The solver balances the load to round-off at every iterate.
constexpr double kLoadBalance = 1e-12;
// A resolved square-root edge is placed within half a cell (see test_normal_profiles.cpp).
constexpr double kEdgeCells = 0.5;
const double kSolverTolerance = NormalSolverOptions{}.tolerance;

double A_strain() { return ElasticPair({kE, kNu}, {kE, kNu}, PlaneState::strain).A(); }

Scene scene(const ProfileSpec& profile, double P, int cells) {
  return test::normal_scene(profile, P, cells, "hard_case");
}

ProfileSpec cylinder(double offset = 0.0) { return test::cylinder(offset); }

double total_load(const NormalResult& r) {
  double load = 0.0;
  for (double p : r.state.p) load += p * r.grid.h();
  return load;
}

// Converged, finite, non-negative, and carrying the load.
void check_sound(const NormalResult& r, double P) {
  CHECK(r.summary.converged());
  CHECK(std::all_of(r.state.p.begin(), r.state.p.end(), [](double p) { return std::isfinite(p) && p >= 0.0; }));
  CHECK(std::abs(total_load(r) / P - 1.0) <= kLoadBalance);
  CHECK(!r.zones.empty());
}

}  // namespace

TEST_CASE("rounded punch with a/b = 0.99: the rounded corners span about three cells") {
  // b − a = 0.01 b, and 1024 cells over 3 b make h = 0.003 b: the corner is barely resolved, so the square-root
  // region is a cell or two and the edge is good to about a cell (not the half cell of a resolved edge).
  const double A = A_strain(), b = 0.2e-3, a_over_b = 0.99;
  ProfileSpec spec;
  spec.type = ProfileType::flat_rounded;
  spec.a = a_over_b * b;
  spec.R = kR;
  const double P = 0.5 * closed_form::D(std::asin(a_over_b)) * b * b / (A * kR);
  const NormalResult r = solve_normal(scene(spec, P, 1024));
  check_sound(r, P);
  REQUIRE(r.zones.size() == 1);
  const double h = r.grid.h();
  CHECK(std::abs(r.zones[0].left.x + b) <= 2.0 * h);
  CHECK(std::abs(r.zones[0].right.x - b) <= 2.0 * h);
  REQUIRE(r.load_size_half_width);
  CHECK(std::abs(*r.load_size_half_width / b - 1.0) <= 1e-12);
}

TEST_CASE("Hertz on 65536 cells converges and stays accurate") {
  const double P = 1e5;
  const NormalResult r = solve_normal(scene(cylinder(), P, 65536));
  check_sound(r, P);
  REQUIRE(r.reference);
  REQUIRE(r.zones.size() == 1);
  CHECK(r.reference->extent_error <= kEdgeCells * r.grid.h() / r.reference->half_width);
  // The peak is sampled h/2 from x = 0: short by h²/(8a²), ~1e-9 here, so the solver's tolerance dominates.
  CHECK(r.reference->p_max_error <= 100.0 * kSolverTolerance);
}

TEST_CASE("a load so small that the contact spans about two cells, on a given window") {
  // Window 2 mm over 1024 cells: h ≈ 2 µm. P = π a² / (2 A R) with a = h gives a contact two cells wide.
  const double A = A_strain();
  Scene s = scene(cylinder(), 1.0, 1024);
  s.window = std::pair(-1e-3, 1e-3);
  const double h = 2e-3 / 1024;
  s.P = std::numbers::pi * h * h / (2.0 * A * kR);
  const NormalResult r = solve_normal(s);
  check_sound(r, s.P);
  REQUIRE(r.zones.size() == 1);
  CHECK(r.cells_in_contact >= 1);
  CHECK(r.cells_in_contact <= 4);
  // Too few cells for a square-root fit: the edges are the zone's outer cell boundaries, which bracket ±a.
  CHECK(r.zones[0].left.method == EdgeMethod::cell_boundary);
  CHECK(r.zones[0].left.x <= -h * (1.0 - 1e-9));
  CHECK(r.zones[0].right.x >= h * (1.0 - 1e-9));
  REQUIRE(r.load_size_half_width);
  CHECK(std::abs(*r.load_size_half_width / h - 1.0) <= 1e-12);
}

TEST_CASE("a given window too narrow for the contact is refused, naming grid.window") {
  // Hertz a = 0.108 mm; windows that cut it on both sides, on the left only and on the right only.
  for (auto window : {std::pair(-0.05e-3, 0.05e-3), std::pair(-0.08e-3, 0.5e-3), std::pair(-0.5e-3, 0.08e-3)}) {
    CAPTURE(window.first);
    CAPTURE(window.second);
    Scene s = scene(cylinder(), 1e5, 512);
    s.window = window;
    try {
      solve_normal(s);
      FAIL("a clipped contact was accepted");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find("grid.window") != std::string::npos);
    }
  }
  // A sharp punch wider than the window is clipped too, even though its gap is finite up to the window's ends.
  ProfileSpec punch;
  punch.type = ProfileType::flat;
  punch.b = 0.5e-3;
  Scene s = scene(punch, 1e5, 512);
  s.window = std::pair(-0.3e-3, 0.3e-3);
  CHECK_THROWS_AS(solve_normal(s), InputError);
}

TEST_CASE("wedge: half-width A P / (2 tan θ), logarithmic peak at the apex") {
  // P = (1/A) ∫ g0′ t / √(b² − t²) dt = 2 b tan θ / A; the pressure (E* tan θ / π) arccosh(b/|x|) is integrable.
  const double A = A_strain(), P = 1e5, theta = 5.0 * std::numbers::pi / 180.0;
  ProfileSpec spec;
  spec.type = ProfileType::wedge;
  spec.angle_deg = 5.0;
  const NormalResult r = solve_normal(scene(spec, P, 1024));
  check_sound(r, P);
  REQUIRE(r.zones.size() == 1);
  const double b = A * P / (2.0 * std::tan(theta)), h = r.grid.h();
  REQUIRE(r.load_size_half_width);
  CHECK(std::abs(*r.load_size_half_width / b - 1.0) <= 1e-12);
  CHECK(std::abs(r.zones[0].left.x + b) <= kEdgeCells * h);
  CHECK(std::abs(r.zones[0].right.x - b) <= kEdgeCells * h);
  // The peak is at the apex, within a cell.
  CHECK(std::abs(r.x_p_max) <= h);
}

TEST_CASE("rounded_wedge: a contact reaching onto the flanks, at the load–size half-width") {
  // x_t = R tan θ = 4.4 µm with R = 50 µm, θ = 5°: the contact (≈ 11 µm) covers the tip and part of each flank.
  const double P = 1e5;
  ProfileSpec spec;
  spec.type = ProfileType::rounded_wedge;
  spec.angle_deg = 5.0;
  spec.R = 50e-6;
  const NormalResult r = solve_normal(scene(spec, P, 1024));
  check_sound(r, P);
  REQUIRE(r.zones.size() == 1);
  REQUIRE(r.load_size_half_width);
  const double b = *r.load_size_half_width, h = r.grid.h();
  CHECK(b > spec.R * std::tan(5.0 * std::numbers::pi / 180.0));
  CHECK(std::abs(r.zones[0].left.x + b) <= kEdgeCells * h);
  CHECK(std::abs(r.zones[0].right.x - b) <= kEdgeCells * h);
}

TEST_CASE("a table sampled from the Hertz parabola gives the Hertz contact") {
  // Nodes every Δ = 0.04 µm over ±0.3 mm (the window, ±1.5 a, lies inside). The interpolant differs from x²/2R by
  // parabolic arcs of height Δ²/(8R) with period Δ; their n-th harmonic (gap ~ Δ²/(2π²n²R)) presses back with
  // k_n·gap/A = Δ/(π n R A), which a cell of width h ≫ Δ averages down by Δ/(π n h): summed over n, at most
  // Δ²/(6 R A h) of pressure. The edges move by far less than a cell.
  const double A = A_strain(), P = 1e5, delta = 0.04e-6;
  ProfileSpec spec;
  spec.type = ProfileType::table;
  for (int k = -7500; k <= 7500; ++k) {
    const double x = k * delta;
    spec.x.push_back(x);
    spec.h.push_back(x * x / (2.0 * kR));
  }
  const NormalResult r = solve_normal(scene(spec, P, 1024));
  check_sound(r, P);
  REQUIRE(r.zones.size() == 1);
  const auto hz = closed_form::hertz(P, A, kR);
  const double h = r.grid.h();
  CHECK(delta < 0.2 * h);
  CHECK(std::abs(r.zones[0].left.x + hz.a) <= kEdgeCells * h);
  CHECK(std::abs(r.zones[0].right.x - hz.a) <= kEdgeCells * h);
  const double interpolation = delta * delta / (6.0 * kR * A * h) / hz.p0;
  CHECK(std::abs(r.p_max / hz.p0 - 1.0) <= 0.25 * (h / hz.a) * (h / hz.a) + 10.0 * kSolverTolerance + interpolation);
}

namespace {

// Two equal cylinders at ±d on `cells`: two zones, each carrying half the load at its own asperity, to the O(h/a) of
// its sub-cell placement.
void check_two_asperities(double d, int cells) {
  const double A = A_strain(), P = 1e5;
  ProfileSpec spec;
  spec.type = ProfileType::envelope;
  spec.terms = {cylinder(), cylinder()};
  spec.terms[0].offset_x = -d;
  spec.terms[1].offset_x = d;
  const NormalResult r = solve_normal(scene(spec, P, cells));
  check_sound(r, P);
  REQUIRE(r.zones.size() == 2);
  const auto hz = closed_form::hertz(0.5 * P, A, kR);
  const double h = r.grid.h();
  for (int k = 0; k < 2; ++k) {
    const Zone& z = r.zones[k];
    double load = 0.0;
    for (int i = z.first_cell; i <= z.last_cell; ++i) load += r.state.p[i] * h;
    CHECK(std::abs(load / (0.5 * P) - 1.0) <= h / hz.a);
    CHECK(std::abs(0.5 * (z.left.x + z.right.x) - (k == 0 ? -d : d)) <= h);
  }
}

}  // namespace

TEST_CASE("two asperities 60 mm apart: the window chooser finds both") {
  // Far beyond the chooser's scan of ±100 contact widths about the first asperity (27 mm here): the second is found
  // from the envelope's terms. 16384 cells over ~60 mm leave ~40 cells per zone.
  check_two_asperities(30e-3, 16384);
}

TEST_CASE("two asperities 1 m apart, each contact far narrower than a trial cell: the window chooser finds both") {
  // The trial solve's 512 cells over 1.5 m are 3 mm wide, 20 times the contacts (0.15 mm): the cell nearer to one
  // asperity's lowest point takes the whole load, and the other asperity, pressed through by the trial's approach,
  // is taken into the window all the same. 262144 cells leave ~19 cells per zone.
  check_two_asperities(0.5, 262144);
}
