// What `fretwear convergence` prints (engine/convergence.hpp): only the columns that mean something for the scene,
// and a line naming the scene's effects the study does not run.
#include <algorithm>
#include <string>

#include <doctest/doctest.h>

#include "engine/convergence.hpp"
#include "scenes.hpp"

using namespace fretwear;

namespace {
std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }
std::string second_line(const std::string& s) {
  const std::size_t k = s.find('\n') + 1;
  return s.substr(k, s.find('\n', k) - k);
}
}  // namespace

TEST_CASE("convergence prints the RMS pressure error against a closed form, and leaves it out without one") {
  const ConvergenceStudy hertz = run_convergence(test::normal_scene(test::cylinder(), 1e5, 128), 128, 256, nullptr);
  REQUIRE(hertz.against == "hertz");
  CHECK(hertz.has_rms());
  CHECK(second_line(hertz.table()).find("rms p") != std::string::npos);
  CHECK(first_line(hertz.csv()).find(",rms_error,") != std::string::npos);

  ProfileSpec tilted = test::cylinder();
  tilted.tilt_rad = 2e-3;  // no closed form: errors against the finest grid, and no pressure field to compare
  const ConvergenceStudy finest = run_convergence(test::normal_scene(tilted, 1e5, 128), 128, 512, nullptr);
  REQUIRE(finest.against == "finest grid");
  CHECK_FALSE(finest.has_rms());
  CHECK(second_line(finest.table()).find("rms") == std::string::npos);
  CHECK(first_line(finest.csv()) == "cells,cells_in_contact,x_left_m,x_right_m,p_max_Pa,extent_error,p_max_error,"
                                    "iterations,seconds");
  // Every row as many cells as the header.
  const std::string csv = finest.csv();
  std::size_t start = 0;
  while (start < csv.size()) {
    const std::size_t end = csv.find('\n', start);
    const std::string row = csv.substr(start, end - start);
    CHECK(std::count(row.begin(), row.end(), ',') == 8);
    start = end + 1;
  }
}

TEST_CASE("convergence says which of the scene's effects are not part of the study") {
  Scene s = test::hertz_wear(1e5, 0.5, 1e6, 128);
  s.life = LifeEffect{};
  const ConvergenceStudy study = run_convergence(s, 128, 256, nullptr);
  CHECK(study.not_studied == std::vector<std::string>{"wear", "life"});
  CHECK(study.table().find("not part of the study: wear, life") != std::string::npos);
  const ConvergenceStudy cycle = run_convergence(test::hertz_cycle(1e5, 0.5, 128), 128, 256, nullptr);
  CHECK(cycle.not_studied.empty());
  CHECK(cycle.table().find("not part of the study") == std::string::npos);
}
