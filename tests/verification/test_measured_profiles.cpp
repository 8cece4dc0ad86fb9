// Measured profiles (SCENES.md, "Measured profiles"): a table read from a file in mm and µm is the same contact as
// the table in metres, and a smooth profile sampled finely and read by makima or pchip gives the smooth profile's
// pressure, where linear interpolation leaves a pressure spike at every kink.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <doctest/doctest.h>
#include <unistd.h>

#include "contact/normal_solver.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "scenes.hpp"

using namespace fretwear;
namespace fs = std::filesystem;

namespace {

const fs::path kExample = fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "measured_profile";

double max_difference(const NormalResult& a, const NormalResult& b) {
  double d = 0.0;
  for (int i = 0; i < a.grid.n; ++i) d = std::max(d, std::abs(a.state.p[i] - b.state.p[i]));
  return d;
}

// The public cylinder (R = 10 mm) sampled every dx over ±0.6 mm, read by interpolation.
ProfileSpec sampled_cylinder(double dx, Interpolation interpolation) {
  ProfileSpec s;
  s.type = ProfileType::table;
  s.interpolation = interpolation;
  const int n = int(std::lround(1.2e-3 / dx));
  for (int i = 0; i <= n; ++i) {
    const double x = -0.6e-3 + 1.2e-3 * i / n;
    s.x.push_back(x);
    s.h.push_back(x * x / (2.0 * test::kHertzR));
  }
  return s;
}

}  // namespace

TEST_CASE("a profile file in mm and um gives the contact of the same profile in metres, to round-off") {
  // The example's crowned pad, and the same numbers written in metres: each row's text with e-3 and e-6 appended,
  // so that the two tables differ only by the rounding of the unit conversion (one ulp).
  const Scene in_mm = load_scene(kExample / "crowned_pad.json");
  const fs::path dir = fs::temp_directory_path() / ("fretwear_measured_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    std::ifstream in(kExample / "crowned_pad.csv");
    std::ofstream out(dir / "crowned_pad_m.csv");
    bool header = true;
    for (std::string line; std::getline(in, line);) {
      if (line.empty() || line[0] == '#') continue;
      if (header) {
        out << "x_m,h_m\n";
        header = false;
        continue;
      }
      const auto comma = line.find(',');
      out << line.substr(0, comma) << "e-3," << line.substr(comma + 1) << "e-6\n";
    }
  }
  nlohmann::json j = in_mm.to_json();
  j["profile"] = {{"type", "table"}, {"file", "crowned_pad_m.csv"}, {"interpolation", "makima"}};
  const Scene in_m = parse_scene(j, "scene", dir);
  fs::remove_all(dir);
  REQUIRE(in_m.profile.x.size() == in_mm.profile.x.size());
  for (std::size_t i = 0; i < in_m.profile.x.size(); ++i) {
    CHECK(in_m.profile.x[i] == doctest::Approx(in_mm.profile.x[i]).epsilon(4e-16));
    CHECK(in_m.profile.h[i] == doctest::Approx(in_mm.profile.h[i]).epsilon(4e-16));
  }
  const NormalResult a = solve_normal(in_mm), b = solve_normal(in_m);
  REQUIRE(a.grid.n == b.grid.n);
  // Inputs one ulp apart: both solves stop within the solver's tolerance of the same solution.
  const double tolerance = NormalSolverOptions{}.tolerance;
  CHECK(std::abs(a.grid.left(0) - b.grid.left(0)) <= tolerance * a.grid.h());
  CHECK(max_difference(a, b) <= tolerance * a.p_max);
  CHECK(std::abs(b.p_max / a.p_max - 1.0) <= tolerance);
}

TEST_CASE("a finely sampled cylinder read by makima or pchip: Hertz's p_max within 0.1 %, where linear spikes") {
  // Samples every 1 µm across a contact of half-width a ≈ 108 µm. makima and pchip are C¹ and miss the parabola's
  // curvature only near its apex (where the neighbouring slopes change sign), over about one spacing: p_max moves by
  // O(dx/a). Linear interpolation puts a kink, and a pressure spike, at every sample.
  constexpr double kDx = 1e-6, kP = 1e5;
  constexpr int kCells = 512;
  // The criterion: the interpolated profile's p_max within 0.1 % of the smooth profile's run on the same
  // grid (whose own error against Hertz is the grid's, not the interpolation's).
  constexpr double kPeakTolerance = 1e-3;
  const NormalResult smooth = solve_normal(test::normal_scene(test::cylinder(), kP, kCells));
  for (Interpolation i : {Interpolation::makima, Interpolation::pchip, Interpolation::linear}) {
    CAPTURE(to_string(i));
    const NormalResult r = solve_normal(test::normal_scene(sampled_cylinder(kDx, i), kP, kCells));
    const double peak = std::abs(r.p_max / smooth.p_max - 1.0);
    MESSAGE(to_string(i) << ": p_max off by " << peak << ", largest pressure difference / p_max "
                         << max_difference(r, smooth) / smooth.p_max);
    if (i == Interpolation::linear)
      CHECK(peak > kPeakTolerance);
    else
      CHECK(peak <= kPeakTolerance);
  }
}
