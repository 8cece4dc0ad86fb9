// Wear under displacement control between similar bodies by the analogy (AnalogyContactResponse's displacement mode,
// engine/wear_contacts.hpp): each response finds the Q whose analogy cycle takes the datum's reference points to ±δ
// on the worn profile, δ_top(Q) = f (δ_P − δ*(Q)) + D(q_top) = δ, and wears by that cycle. The independent answer is
// the marched cycle on the same worn profile (effects.tangential.route "incremental": the first loading and a cycle
// of δ in 40 increments, each a search for its Q), whose slip for similar bodies is exact at the increment ends.
//
// Hertz, R = 10 mm, P = 100 N/mm, f = 0.5, steel on steel, δ = 1 µm (0.82 of the stick limit), 256 cells. Measured:
// one response on the unworn profile and one on a worn one, Q 4e-9 and the slip 2.3e-7 of its largest apart; the run
// over 10^5 cycles, worn area 1.5e-7 and Q 3e-10 apart at the end. kAgreement holds those to a hundredth of what the
// wear stepper may err by in a step (τ = 1e-3); the records between, where the two runs' steps part, to τ.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>

#include "scenes.hpp"
#include "support.hpp"

#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "engine/wear_stage.hpp"

using namespace fretwear;
using test::max_abs_diff;

namespace {

constexpr double kP = 1e5, kDelta = 1e-6;
constexpr double kAgreement = 1e-5;  // relative: Q, the slip (of its largest), the worn area

Scene displaced(int cells, double cycles, TangentialRoute route) {
  Scene s = test::hertz_wear(kP, 0.5, cycles, cells);
  s.Q_ratio.reset();
  s.control = LoadControl::displacement;
  s.delta = kDelta;
  s.tangential->route = route;
  return s;
}

struct Responses {
  wear::CycleResponse analogy, marched;
  double Q_analogy = 0.0, Q_marched = 0.0;
};

// The two responses on the worn profile w, each contact built as the wear stage builds it.
Responses respond(const Scene& auto_scene, const Scene& incremental_scene, const std::vector<double>& w) {
  Responses r;
  for (const bool by_analogy : {true, false}) {
    const Scene& s = by_analogy ? auto_scene : incremental_scene;
    const Setup setup = make_setup(s);
    const NormalResult normal = solve_normal(s, setup.model);
    const CycleStage cycle = solve_cycle(s, setup.model, *setup.cycle, normal);
    const std::unique_ptr<WearContact> contact = make_wear_contact(s, setup.model, cycle);
    auto* incremental = dynamic_cast<IncrementalContactResponse*>(contact.get());
    REQUIRE(incremental);
    contact->respond(w, by_analogy ? r.analogy : r.marched);
    (by_analogy ? r.Q_analogy : r.Q_marched) = contact->Q_top();
    CHECK(incremental->analogy_responses() == (by_analogy ? 1 : 0));
  }
  return r;
}

void check_same(const Responses& r) {
  const double s_max = *std::max_element(r.marched.s.begin(), r.marched.s.end());
  MESSAGE(fmt::format("Q {:.10g} (analogy) against {:.10g} N/m ({:.3g}); slip {:.3g} of its largest apart; stick "
                      "zone [{:.8g}, {:.8g}] against [{:.8g}, {:.8g}] m",
                      r.Q_analogy, r.Q_marched, r.Q_analogy / r.Q_marched - 1.0,
                      max_abs_diff(r.analogy.s, r.marched.s) / s_max, r.analogy.stick_left, r.analogy.stick_right,
                      r.marched.stick_left, r.marched.stick_right));
  CHECK(r.Q_analogy == test::rel(r.Q_marched, kAgreement));
  CHECK(max_abs_diff(r.analogy.s, r.marched.s) < kAgreement * s_max);
  CHECK(max_abs_diff(r.analogy.p, r.marched.p) < kAgreement * *std::max_element(r.marched.p.begin(), r.marched.p.end()));
  // Off the contact, the slip on touching: the analogy's 4 f (g* − g), the marched cycle's relative tangential
  // displacement of the surfaces there (CycleResult::slip_if_touching).
  const std::vector<double>& ta = r.analogy.slip_if_touching();
  const std::vector<double>& tm = r.marched.slip_if_touching();
  int open = 0;
  double touching_apart = 0.0, touching_max = 0.0;
  for (std::size_t i = 0; i < ta.size(); ++i) {
    if (r.marched.p[i] > 0.0) continue;
    ++open;
    touching_apart = std::max(touching_apart, std::abs(ta[i] - tm[i]));
    touching_max = std::max(touching_max, ta[i]);
  }
  MESSAGE(fmt::format("slip on touching over {} cells off the contact: up to {:.4g} m, {:.3g} of the largest slip apart",
                      open, touching_max, touching_apart / s_max));
  REQUIRE(open > 0);
  CHECK(touching_max > 0.1 * s_max);  // the cells off the contact would slip, and not a little
  CHECK(touching_apart < kAgreement * s_max);
  REQUIRE(r.analogy.has_stick);
  REQUIRE(r.marched.has_stick);
  CHECK(r.analogy.stick_left == test::rel(r.marched.stick_left, kAgreement));
  CHECK(r.analogy.stick_right == test::rel(r.marched.stick_right, kAgreement));
}

}  // namespace

TEST_CASE("wear under displacement control: the analogy's response at the Q that reaches delta is the marched one") {
  const Scene a = displaced(256, 1e5, TangentialRoute::automatic);
  const Scene m = displaced(256, 1e5, TangentialRoute::incremental);
  const int n = 256;
  SUBCASE("on the unworn profile") { check_same(respond(a, m, std::vector<double>(n, 0.0))); }
  SUBCASE("on a worn profile") {
    // A profile worn by the marched run itself, its last record.
    const RunResult run = Simulation(m).run();
    REQUIRE(run.wear);
    check_same(respond(a, m, run.wear->records.back().w));
  }
}

TEST_CASE("wear under displacement control: the run by the analogy wears as the marched one, and says which ran") {
  const Scene a = displaced(256, 1e5, TangentialRoute::automatic);
  const Scene m = displaced(256, 1e5, TangentialRoute::incremental);
  const RunResult ra = Simulation(a).run(), rm = Simulation(m).run();
  REQUIRE(ra.wear);
  REQUIRE(rm.wear);
  CHECK(ra.wear->route.rfind("analogy (displacement control", 0) == 0);
  CHECK(rm.wear->route == "incremental");
  const auto& ea = ra.wear->records;
  const auto& em = rm.wear->records;
  REQUIRE(ea.size() == em.size());
  // Through the knee the two runs' steps part (their responses differ by 1e-7, and each step's error is held to τ,
  // so their paths differ by a few 1e-4 of the worn area there: 1.6e-4 measured at 1931 cycles); they meet again
  // at the end.
  const double tau = a.wear->tolerance;
  for (std::size_t k = 1; k < ea.size(); ++k) {
    CAPTURE(ea[k].cycles);
    CHECK(ea[k].cycles == em[k].cycles);
    CHECK(ea[k].worn_area == test::rel(em[k].worn_area, tau));
    CHECK(ea[k].Q_max == test::rel(em[k].Q_max, tau));
  }
  CHECK(ea.back().worn_area == test::rel(em.back().worn_area, kAgreement));
  CHECK(ea.back().Q_max == test::rel(em.back().Q_max, kAgreement));
  MESSAGE(fmt::format("after 1e5 cycles: worn area {:.10g} against {:.10g} m² ({:.3g}), Q {:.10g} against {:.10g} "
                      "N/m ({:.3g})",
                      ea.back().worn_area, em.back().worn_area, ea.back().worn_area / em.back().worn_area - 1.0,
                      ea.back().Q_max, em.back().Q_max, ea.back().Q_max / em.back().Q_max - 1.0));
  CHECK(ea.back().Q_max < 0.95 * ea.front().Q_max);  // Q falls as the slip zones wear (a result, not the scene's)
}

TEST_CASE("wear under displacement control: gross slip and a bulk stress keep the marched cycle") {
  Scene sliding = displaced(128, 1e2, TangentialRoute::automatic);
  sliding.delta = 1.5e-6;  // beyond the stick limit, 1.22 µm
  sliding.window = std::pair{-4e-4, 4e-4};  // the sliding contact widens as it wears
  const RunResult r = Simulation(sliding).run();
  REQUIRE(r.wear);
  CHECK(r.wear->route == "incremental");
  Scene stressed = displaced(128, 1e3, TangentialRoute::automatic);
  stressed.bulk_stress = 50e6;
  const RunResult rs = Simulation(stressed).run();
  REQUIRE(rs.wear);
  CHECK(rs.wear->route == "incremental");
}

TEST_CASE("wear under displacement control: where the analogy gives up the cycle is marched, and says why") {
  // A block's δ beyond the stick limit (1.22 µm) on the cycle stage of δ = 1 µm: the analogy finds the bodies
  // sliding and the response is the marched one, in gross slip.
  const Scene s = displaced(128, 1e2, TangentialRoute::automatic);
  const Setup setup = make_setup(s);
  const NormalResult normal = solve_normal(s, setup.model);
  const CycleStage cycle = solve_cycle(s, setup.model, *setup.cycle, normal);
  CyclicLoad beyond = cycle.plan.load;
  beyond.delta = 1.5e-6;
  IncrementalContactResponse contact(s, setup.model, cycle, beyond);
  wear::CycleResponse r;
  contact.respond(std::vector<double>(std::size_t(setup.model.grid.n), 0.0), r);
  CHECK(contact.analogy_responses() == 0);
  CHECK(contact.last_cycle().regime == Regime::gross_slip);
  const std::string why = contact.analogy_gave_up();
  MESSAGE(why);
  CHECK(why.find("slides under delta = 1.5e-06 m") != std::string::npos);
}

TEST_CASE("the analogy's reverse slip advises the incremental route only where nothing falls back to it") {
  // paper 001's reverse slip (a bulk stress of 304 MPa with Q/fP = 0.45), on 256 cells.
  Scene s = test::paper001_mindlin(256, 304.22e6);
  s.wear = test::hertz_wear(1e5, 0.5, 1e3, 256).wear;
  const Model m = make_model(s);
  const std::vector<double> w(std::size_t(m.grid.n), 0.0);
  for (const bool falls_back : {false, true}) {
    CAPTURE(falls_back);
    AnalogyContactResponse contact(s, m, cyclic_load(s, m.pair));
    if (falls_back) contact.falls_back();
    wear::CycleResponse r;
    std::string why;
    try {
      contact.respond(w, r);
    } catch (const UnsupportedError& e) {
      why = e.what();
    }
    MESSAGE(why);
    CHECK(why.find("slips backwards at its leading edge") != std::string::npos);
    CHECK((why.find("set effects.tangential.route to \"incremental\"") != std::string::npos) == !falls_back);
  }
}

TEST_CASE("wear under displacement control at 1024 cells: the marched run reaches the analogy's settled limit") {
  // δ = 1 µm over 10^6 cycles: the run settles, its worn flats at zero gap and zero pressure beside the stick zone.
  // Both responses give those cells the slip they would travel on touching; given none, the marched run's worn
  // flats stood proud of their neighbours by each step's error and the run stopped 2.4e-3 short in worn area.
  Scene a = displaced(1024, 1e6, TangentialRoute::automatic);
  Scene m = displaced(1024, 1e6, TangentialRoute::incremental);
  const RunResult ra = Simulation(a).run(), rm = Simulation(m).run();
  REQUIRE(ra.wear);
  REQUIRE(rm.wear);
  REQUIRE(ra.wear->settled);
  REQUIRE(rm.wear->settled);
  const WearRecord& ea = ra.wear->records.back();
  const WearRecord& em = rm.wear->records.back();
  MESSAGE(fmt::format("worn area {:.10g} (analogy) against {:.10g} m² (marched), {:.3g}; each against its settled "
                      "limit {:.8f} and {:.8f}",
                      ea.worn_area, em.worn_area, em.worn_area / ea.worn_area - 1.0,
                      ea.worn_area / ra.wear->settled->worn_area, em.worn_area / rm.wear->settled->worn_area));
  CHECK(em.worn_area == test::rel(ea.worn_area, kAgreement));
  CHECK(em.worn_area == test::rel(rm.wear->settled->worn_area, kAgreement));
  CHECK(ea.worn_area == test::rel(ra.wear->settled->worn_area, kAgreement));
}
