// Fretting-fatigue life (contact/fatigue_life.hpp) against PHYSICS.md's closed forms: the Basquin–Coffin–Manson
// inversion, Paris' law for an edge crack in remote tension (m = 3 and 4), a change of state part-way, fracture at
// K_c, El Haddad's threshold arresting a crack whose ΔK falls with its length, and the line method's average.
#include <cmath>
#include <numbers>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "support.hpp"

#include "contact/fatigue_life.hpp"

using namespace fretwear;

namespace {

// A steel's strain–life constants (Araújo and Nowell 2002 use values of this size for Al 4%Cu; any valid set serves).
constexpr InitiationConstants kSteel{1.817e9, -0.08, 0.35, -0.52, 200e9};

// The integration's tolerance is kGrowthTolerance per unit length; the table is exact for K ∝ √a (K/√a constant), so
// the life agrees with the closed form to a few times the tolerance over the growth.
constexpr double kPathAgreement = 1e-6;

// PHYSICS.md: N = [a0^{1−m/2} − af^{1−m/2}] / [C (1.1215 σ √π)^m (m/2 − 1)].
double paris_closed_form(double C, double m, double sigma, double a0, double af) {
  return (std::pow(a0, 1.0 - m / 2) - std::pow(af, 1.0 - m / 2)) /
         (C * std::pow(1.1215 * sigma * std::sqrt(std::numbers::pi), m) * (m / 2 - 1));
}

// The edge crack in remote tension 0 → σ: K_I at the top 1.1215 σ √(πa), the bottom closed (0), no mode II.
SifTable tension_table(double sigma, double a_lo, double a_hi, int n = 40) {
  std::vector<double> a, top, zero(std::size_t(n), 0.0);
  for (int j = 0; j < n; ++j) {
    a.push_back(a_lo * std::pow(a_hi / a_lo, double(j) / (n - 1)));
    top.push_back(1.1215 * sigma * std::sqrt(std::numbers::pi * a.back()));
  }
  return SifTable(a, top, zero, zero, zero);
}

}  // namespace

TEST_CASE("initiation: Basquin-Coffin-Manson inverted to 1e-10 against its direct evaluation") {
  for (double N : {1.0, 37.0, 1e3, 2.5e5, 1e7, 3e9, 1e15}) {
    const double swt = swt_of_life(kSteel, N);
    CHECK(initiation_life(kSteel, swt) == test::rel(N, 1e-10));
  }
  CHECK(std::isinf(initiation_life(kSteel, 0.0)));
  CHECK(std::isinf(initiation_life(kSteel, -1e5)));
  CHECK(std::isinf(initiation_life(kSteel, 0.5 * swt_of_life(kSteel, kMaxLife))));
  CHECK(initiation_life(kSteel, 2.0 * swt_of_life(kSteel, kMinLife)) == kMinLife);
}

TEST_CASE("initiation: a uniaxial cycle's SWT, sigma_a^2 (1 - nu^2)/E, gives the life of PHYSICS.md's check") {
  // σ_a = 400 MPa about zero in plane strain, σ_yy = 0: SWT = σ_a²(1 − ν²)/E; N_i solves the curve for it.
  const double sigma_a = 400e6, nu = 0.3, swt = sigma_a * sigma_a * (1 - nu * nu) / kSteel.E;
  const double N = initiation_life(kSteel, swt);
  MESSAGE(fmt::format("SWT {:.6g} Pa gives N_i = {:.6g} cycles", swt, N));
  CHECK(swt_of_life(kSteel, N) == test::rel(swt, 1e-12));
}

TEST_CASE("the line method's average over depth is exact for a linear profile and holds past the samples") {
  const std::vector<double> y{0.0, 1e-5, 2e-5, 4e-5}, v{10.0, 8.0, 6.0, 2.0};  // v = 10 − 2e5 y
  CHECK(line_average(y, v, 0.0) == 10.0);
  CHECK(line_average(y, v, 1e-5) == test::rel(9.0, 1e-14));
  CHECK(line_average(y, v, 3e-5) == test::rel(7.0, 1e-14));   // ends between samples
  CHECK(line_average(y, v, 4e-5) == test::rel(6.0, 1e-14));
  CHECK(line_average(y, v, 8e-5) == test::rel(6.0, 1e-14));   // past the last sample: the mean over the samples
}

TEST_CASE("propagation: Paris for an edge crack in remote tension matches the closed form, m = 3 and m = 4") {
  const double sigma = 200e6, a0 = 2e-5, af = 1e-3;
  for (double m : {3.0, 4.0}) {
    const GrowthConstants g{m == 3.0 ? 5e-30 : 1e-37, m, 0.0, 0.0, 0.0, false};
    const SifTable table = tension_table(sigma, a0, af);
    const GrowthState state{0.0, &table};
    const GrowthResult r = grow_crack(g, a0, af, 0.0, {&state, 1}, 1e12);
    const double expected = paris_closed_form(g.C, m, sigma, a0, af);
    MESSAGE(fmt::format("m = {}: {:.10g} cycles against {:.10g} ({} steps)", m, r.cycles, expected, r.path.size()));
    CHECK(r.fate == GrowthFate::failure);
    CHECK(r.cycles == test::rel(expected, kPathAgreement));
    CHECK(r.final_length == test::rel(af, kPathAgreement));
    // The path is monotone, and its rate is Paris' at each point.
    for (std::size_t j = 1; j < r.path.size(); ++j) {
      CHECK(r.path[j].a >= r.path[j - 1].a);
      CHECK(r.path[j].da_dN == test::rel(g.C * std::pow(r.path[j].dK_I, m), 1e-12));
    }
  }
}

TEST_CASE("propagation: a change of state part-way is two closed-form pieces, and K_c ends it early") {
  const double a0 = 2e-5, af = 1e-3, m = 3.0, C = 5e-30;
  const GrowthConstants g{C, m, 0.0, 0.0, 0.0, false};
  const SifTable first = tension_table(200e6, a0, af), second = tension_table(300e6, a0, af);
  // Under 200 MPa until the crack is 1e-4 m long, then 300 MPa.
  const double a_mid = 1e-4, N_mid = paris_closed_form(C, m, 200e6, a0, a_mid);
  const GrowthState states[] = {{0.0, &first}, {N_mid, &second}};
  const GrowthResult r = grow_crack(g, a0, af, 0.0, states, 1e12);
  CHECK(r.fate == GrowthFate::failure);
  CHECK(r.cycles == test::rel(N_mid + paris_closed_form(C, m, 300e6, a_mid, af), kPathAgreement));

  // Fracture where K_max = K_c: a_c = (K_c / (1.1215 σ))² / π.
  GrowthConstants tough = g;
  tough.K_c = 10e6;
  const double a_c = std::pow(tough.K_c / (1.1215 * 200e6), 2) / std::numbers::pi;
  const GrowthState one{0.0, &first};
  const GrowthResult k = grow_crack(tough, a0, af, 0.0, {&one, 1}, 1e12);
  CHECK(k.fate == GrowthFate::failure);
  CHECK(k.final_length == test::rel(a_c, 1e-8));
  CHECK(k.cycles == test::rel(paris_closed_form(C, m, 200e6, a0, a_c), kPathAgreement));

  // A run stopped at cycles_max is a runout at the length the closed form reaches then.
  const double N_stop = 0.5 * paris_closed_form(C, m, 200e6, a0, af);
  const GrowthResult out = grow_crack(g, a0, af, 0.0, {&one, 1}, N_stop);
  CHECK(out.fate == GrowthFate::runout);
  const double c = C * std::pow(1.1215 * 200e6 * std::sqrt(std::numbers::pi), m) * (m / 2 - 1);
  const double a_stop = std::pow(std::pow(a0, 1 - m / 2) - c * N_stop, 1.0 / (1 - m / 2));
  CHECK(out.final_length == test::rel(a_stop, kPathAgreement));
}

TEST_CASE("propagation: a crack whose dK falls below El Haddad's threshold arrests, and the fate says so") {
  // ΔK = σ √(πa) e^{−a/L}: a contact's field decaying with depth. With ΔK_th = 3 MPa√m and a₀ from Δσ_e = 200 MPa
  // the crack grows while ΔK > ΔK_th √(a/(a + a₀)) and stops where they meet.
  const double sigma = 300e6, L = 1e-4, a_lo = 1e-6, a_hi = 2e-3;
  std::vector<double> a, top, zero(60, 0.0);
  for (int j = 0; j < 60; ++j) {
    a.push_back(a_lo * std::pow(a_hi / a_lo, j / 59.0));
    top.push_back(sigma * std::sqrt(std::numbers::pi * a.back()) * std::exp(-a.back() / L));
  }
  const SifTable table(a, top, zero, zero, zero);
  GrowthConstants g{5e-30, 3.0, 3e6, el_haddad_length(3e6, 200e6), 0.0, false};
  CHECK(g.a0 == test::rel(std::pow(3e6 / (1.12 * 200e6), 2) / std::numbers::pi, 1e-15));
  const GrowthState state{0.0, &table};
  const GrowthResult r = grow_crack(g, 1e-5, 1e-3, 0.0, {&state, 1}, 1e15);
  CHECK(r.fate == GrowthFate::arrest);
  CHECK(std::isinf(r.cycles));
  // It stopped where ΔK meets the threshold (the table's interpolation error aside).
  CHECK(table.dK(r.final_length, g) == test::rel(growth_threshold(g, r.final_length), 1e-3));
  CHECK(r.final_length > 1e-5);
  CHECK(r.final_length < 1e-3);
}
