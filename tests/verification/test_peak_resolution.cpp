// Whether the grid resolves contact.p_max where no closed form and no singular edge says so (engine/normal_stage.hpp,
// check_peak): the run solves the normal contact again on half the cells over the same window, reports that peak
// (contact.p_max_half_cells) and warns `peak_unconverged` past kPeakChangeShare, or under any point of a linearly
// interpolated table inside the contact.
//
// Measured (plane stress, E = 115 GPa, ν = 0.32, P = 300 N/mm; a flat of half-width 1 mm tilted by 2e-4 rad):
// with rounded corners of R = 0.1 mm the peak moves 15 %, 5.3 %, 1.2 % and 0.0014 % from 256 to 4096 cells (it sits
// in the corner's rounding, 4 cells wide at 1024); with R = 10 µm, under a cell, 45 %, 16 %, 32 %, 7.4 %, never
// settling; with R = 1 mm at most 2 %. A parabola (R = 10 mm, steel, 100 N/mm; Hertz p0 = 591 MPa) sampled every
// 10 µm: linearly, 616, 631, 651, 661, 678 MPa from 256 to 4096 cells, growing by 1.5 to 3 % a doubling; by makima,
// 596.59 to 596.75 MPa, 0.04 % at most.
#include <algorithm>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "support.hpp"

#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/warnings.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json tilted_punch(double R, int cells) {
  return {{"name", "tilted"},
          {"plane", "stress"},
          {"materials", {{"both", {{"E", 115e9}, {"nu", 0.32}}}}},
          {"profile", {{"type", "flat_rounded"}, {"a", 1e-3}, {"R", R}, {"tilt_rad", 2e-4}}},
          {"load", {{"P", 3e5}}},
          {"grid", {{"cells", cells}}}};
}

json sampled_parabola(const std::string& interpolation, int cells) {
  std::vector<double> x, h;
  for (int i = 0; i <= 100; ++i) {
    x.push_back(-5e-4 + 1e-5 * i);
    h.push_back(x.back() * x.back() / (2.0 * 0.01));
  }
  return {{"name", "table"},
          {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
          {"profile", {{"type", "table"}, {"x", x}, {"h", h}, {"interpolation", interpolation}}},
          {"load", {{"P", 1e5}}},
          {"grid", {{"cells", cells}}}};
}

struct Checked {
  double p_max = 0.0, p_half = 0.0;
  bool warned = false;
  std::string message;
};

Checked check(const json& j) {
  const Scene s = parse_scene(j);
  const json summary = make_summary(s, Simulation(s).run());
  Checked c;
  c.p_max = summary["contact"]["p_max"].get<double>();
  REQUIRE(summary["contact"]["p_max_half_cells"].is_number());
  c.p_half = summary["contact"]["p_max_half_cells"].get<double>();
  for (const auto& w : summary["warnings"])
    if (w["code"] == "peak_unconverged") c.warned = true, c.message = w["message"].get<std::string>();
  return c;
}

}  // namespace

TEST_CASE("peak check: a tilted flat punch's rounded corner warns while the grid does not resolve it, then not") {
  const Checked coarse = check(tilted_punch(1e-4, 512)), fine = check(tilted_punch(1e-4, 4096));
  MESSAGE(fmt::format("R = 0.1 mm: p_max {:.6g} Pa (256 cells {:.6g}) at 512; {:.6g} Pa (2048 cells {:.6g}) at 4096",
                      coarse.p_max, coarse.p_half, fine.p_max, fine.p_half));
  CHECK(coarse.warned);
  CHECK(coarse.message.find("a feature of the profile there") != std::string::npos);
  CHECK(coarse.message.find("on 512 cells") != std::string::npos);
  CHECK(std::abs(coarse.p_max / coarse.p_half - 1.0) > kPeakChangeShare);
  CHECK_FALSE(fine.warned);
  CHECK(std::abs(fine.p_max / fine.p_half - 1.0) < 1e-3);
  // Corners far below a cell are never resolved: warned at every grid here.
  for (int cells : {1024, 4096}) {
    CAPTURE(cells);
    CHECK(check(tilted_punch(1e-5, cells)).warned);
  }
  // A gentle rounding is resolved at once.
  CHECK_FALSE(check(tilted_punch(1e-3, 1024)).warned);
}

TEST_CASE("peak check: a table interpolated linearly warns of its points inside the contact, makima does not") {
  std::vector<double> linear;
  for (int cells : {512, 2048}) {
    CAPTURE(cells);
    const Checked l = check(sampled_parabola("linear", cells));
    CHECK(l.warned);  // the change may be under kPeakChangeShare: the kinks are warned whatever it is
    CHECK(l.message.find("of the table's points lie inside the contact") != std::string::npos);
    CHECK(l.message.find("\"makima\"") != std::string::npos);
    linear.push_back(l.p_max);
    const Checked m = check(sampled_parabola("makima", cells));
    CHECK_FALSE(m.warned);
    CHECK(std::abs(m.p_max / m.p_half - 1.0) < 1e-3);
  }
  MESSAGE(fmt::format("linear: p_max {:.6g} Pa at 512 cells, {:.6g} at 2048", linear[0], linear[1]));
  CHECK(linear[1] > 1.03 * linear[0]);  // it grows, as ln(1/h)
}

TEST_CASE("peak check: a contact with a closed form, or a peak at a singular edge, is not solved again") {
  for (const json& profile : {json{{"type", "cylinder"}, {"R", 0.01}}, json{{"type", "flat"}, {"b", 5e-4}}}) {
    CAPTURE(profile.dump());
    json j = sampled_parabola("linear", 512);
    j["profile"] = profile;
    const Scene s = parse_scene(j);
    const RunResult r = Simulation(s).run();
    CHECK_FALSE(r.normal.peak_check);
    CHECK(make_summary(s, r)["contact"]["p_max_half_cells"].is_null());
  }
}
