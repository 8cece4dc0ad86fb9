// The stress and crack effects of a scene, end to end: what reaches summary.json against closed forms.
#include <cmath>
#include <numbers>
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "common/error.hpp"
#include "engine/simulation.hpp"
#include "support.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {
json cycle_scene() {
  return {{"name", "crack_scene"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", 1e8}}}}},
          {"grid", {{"cells", 512}}},
          {"effects", {{"tangential", json::object()}}}};
}
json run(const json& j) {
  const Scene s = parse_scene(j);
  return make_summary(s, Simulation(s).run());
}
}  // namespace

TEST_CASE("a crack far from the contact sees the bulk stress: K_I = 1.1215 sigma sqrt(pi l), closed at the bottom") {
  // At 1000 contact half-widths the contact's stresses are about P/(π x) = 0.3 MPa against σ = 100 MPa: 0.3 %.
  json j = cycle_scene();
  const double a = 0.107641e-3, sigma = 1e8;
  j["effects"]["crack"] = {{"at", -1000 * a}, {"lengths", {1e-5, 1e-4}}};
  const json s = run(j);
  const json& c = s["crack"];
  for (int k = 0; k < 2; ++k) {
    const double l = c["lengths"][k].get<double>();
    const double K = 1.121522 * sigma * std::sqrt(std::numbers::pi * l);
    CHECK(c["K_I_max"][k].get<double>() == test::rel(K, 5e-3));
    CHECK(c["K_I_min"][k].get<double>() == 0.0);
    CHECK(c["closed_min"][k].get<bool>());
    CHECK(c["K_I_open_min"][k].get<double>() == test::rel(-K, 5e-3));
  }
  CHECK(c["x"].get<double>() == test::rel(-1000 * a, 1e-15));
}

TEST_CASE("the trailing edge crack sits at the contact's left edge, stresses report the surface peak there") {
  json j = cycle_scene();
  j["effects"]["crack"] = {{"lengths", {1e-5}}};
  j["effects"]["stress"] = {{"nx", 81}, {"ny", 21}};
  const json s = run(j);
  CHECK(s["crack"]["x"].get<double>() == test::rel(s["contact"]["extent"][0].get<double>(), 1e-15));
  CHECK(s["crack"]["K_I_max"][0].get<double>() > 0.0);  // tension at the trailing edge at the top of the cycle
  // Surface σxx peaks near the trailing edge at the top of the cycle, in tension (Hills and Nowell 1994).
  const json& top = s["stress"]["phases"]["top"];
  CHECK(top["surface_sxx_trailing_peak"].get<double>() > 1e8);
  CHECK(std::abs(top["surface_sxx_trailing_peak_x"].get<double>() - s["contact"]["extent"][0].get<double>()) <
        0.1 * s["contact"]["extent"][1].get<double>());
  for (const char* key : {"K_I_max", "K_II_max", "K_I_min", "K_II_min", "K_I_open_max", "K_I_open_min"})
    CHECK(s["crack"][key].size() == 1);
}

TEST_CASE("an inclined crack with rough faces far from the contact: the inclined edge crack's factors, closed at the bottom") {
  // 45° in σxx = ±100 MPa: K_I = 0.70507 σ√(πl) at N = 60 (test_crack_inclined.cpp) at the top; at the bottom the
  // faces close (K_I = 0, the open value −0.70507) and friction f = 0.5 < cot 45° lets them slip: |K_II| below the
  // frictionless value 0.5328 σ√(πl) (test_crack_friction.cpp) and above 0.
  json j = cycle_scene();
  const double a = 0.107641e-3, sigma = 1e8;
  j["effects"]["crack"] = {{"at", -1000 * a}, {"angle_deg", 45}, {"face_friction", 0.5}, {"lengths", {1e-5}}};
  const json s = run(j);
  const json& c = s["crack"];
  const double K = sigma * std::sqrt(std::numbers::pi * 1e-5);
  CHECK(c["K_I_max"][0].get<double>() == test::rel(0.70507 * K, 5e-3));
  CHECK(c["K_II_max"][0].get<double>() == test::rel(0.36450 * K, 5e-3));
  CHECK(c["K_I_min"][0].get<double>() == 0.0);
  CHECK(c["closed_min"][0].get<bool>());
  CHECK(c["K_I_open_min"][0].get<double>() == test::rel(-0.70507 * K, 5e-3));
  CHECK(std::abs(c["K_II_min"][0].get<double>()) < 0.5328 * K);
  CHECK(std::abs(c["K_II_min"][0].get<double>()) > 0.1 * K);
  CHECK(c["angle_deg"].get<double>() == 45.0);
}

TEST_CASE("crack and stress keys: errors name the key and what is allowed") {
  json j = cycle_scene();
  j["effects"]["crack"] = {{"angle_deg", 10}, {"face_friction", -0.3}, {"at", "middle"}};
  j["effects"]["stress"] = {{"nx", 2}};
  try {
    parse_scene(j);
    FAIL("the scene should be invalid");
  } catch (const SceneError& e) {
    std::string all;
    for (const auto& p : e.problems()) all += p + "\n";
    CHECK(all.find("effects.crack.angle_deg: 10 is not allowed; give an angle to the surface in [15, 165] degrees") !=
          std::string::npos);
    CHECK(all.find("effects.crack.face_friction: -0.3 is not allowed") != std::string::npos);
    CHECK(all.find("effects.crack.at") != std::string::npos);
    CHECK(all.find("effects.crack.lengths: missing") != std::string::npos);
    CHECK(all.find("effects.stress.nx") != std::string::npos);
  }
}

TEST_CASE("a shallow closed crack without face friction settles, and its SIFs converge with the quadrature") {
  // Q/fP = 0.6, σ_bulk = 100 MPa, 256 cells, a crack at 20°, 5e-5 m, closed at both ends of the cycle. The SIFs at 40
  // points are within 4e-4 of those at 120 (K_II at the top: 2.3074e6, 2.3068e6 and 2.3066e6 Pa√m at 40, 60 and
  // 120 points).
  json j = cycle_scene();
  j["grid"]["cells"] = 256;
  j["load"]["Q"]["ratio"] = 0.6;
  j["effects"]["crack"] = {{"angle_deg", 20.0}, {"lengths", {5e-5}}, {"quadrature", 40}};
  const json coarse = run(j)["crack"];
  j["effects"]["crack"]["quadrature"] = 120;
  const json fine = run(j)["crack"];
  for (const char* k : {"K_II_max", "K_II_min"}) {
    CAPTURE(k);
    CHECK(coarse[k][0].get<double>() == test::rel(fine[k][0].get<double>(), 1e-3));
  }
  CHECK(coarse["K_I_max"][0].get<double>() == 0.0);
  CHECK(fine["K_I_max"][0].get<double>() == 0.0);
}

TEST_CASE("a crack whose face contact cycles says how far from settled and to change the quadrature") {
  // At 22.5° on a 256-cell contact the open/stick/slip set of the 2 µm crack cycles, also from the complementarity
  // problem's set and with the mouth's points held (crack_solver.hpp), between sets that violate their inequalities
  // by 2 % of the load.
  json j = cycle_scene();
  j["grid"]["cells"] = 256;
  j["effects"]["crack"] = {{"angle_deg", 22.5}, {"face_friction", 0.5}, {"lengths", {2e-6}}, {"quadrature", 60}};
  try {
    run(j);
    FAIL("the face contact settled");
  } catch (const ConvergenceError& e) {
    const std::string m = e.what();
    CHECK(m.find("cycles after") != std::string::npos);
    CHECK(m.find("also when started from its complementarity problem's solution") != std::string::npos);
    CHECK(m.find("of the largest load on the faces") != std::string::npos);
    CHECK(m.find("change effects.crack.quadrature") != std::string::npos);
    CHECK(m.find("max_contact_iterations") == std::string::npos);
  }
}

TEST_CASE("a crack at 165 degrees whose passes cycled settles through its complementarity problem") {
  // At 165° and 60 points the passes alone cycle between sets that violate their inequalities by 7 % of the load.
  json j = cycle_scene();
  j["grid"]["cells"] = 256;
  j["load"]["Q"]["ratio"] = 0.6;
  j["effects"]["crack"] = {{"angle_deg", 165.0}, {"lengths", {1e-5, 5e-5}}, {"quadrature", 60}};
  const json c60 = run(j)["crack"];
  j["effects"]["crack"]["quadrature"] = 120;
  const json c120 = run(j)["crack"];
  for (int k = 0; k < 2; ++k) {
    CAPTURE(k);
    const double scale = std::abs(c120["K_II_min"][k].get<double>()) + std::abs(c120["K_II_max"][k].get<double>());
    CHECK(std::abs(c60["K_II_min"][k].get<double>() - c120["K_II_min"][k].get<double>()) < 0.03 * scale);
    CHECK(std::abs(c60["K_II_max"][k].get<double>() - c120["K_II_max"][k].get<double>()) < 0.03 * scale);
  }
}
