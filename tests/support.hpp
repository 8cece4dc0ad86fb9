// Helpers shared by the tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

namespace fretwear::test {

// A strictly relative comparison: |got − want| < rel · max(|got|, |want|). doctest::Approx adds a scale of 1 to the
// magnitudes, which makes its epsilon absolute for SI-sized values (metres of 1e-4, compliances of 1e-11) and such
// a check unable to fail; never use Approx on dimensional values.
inline doctest::Approx rel(double want, double tolerance) {
  return doctest::Approx(want).epsilon(tolerance).scale(0.0);
}

// max_i |a_i − b_i| of two fields on the same cells (a test failure when their sizes differ).
inline double max_abs_diff(const std::vector<double>& a, const std::vector<double>& b) {
  REQUIRE(a.size() == b.size());
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

// A normal solve captured from a run (tests/regression/data/*.csv): per cell the gap g0 + w (m) and the warm start p
// (Pa), one "gap,p" row a cell after '#' comments and a header; a test failure unless it has `cells` rows.
struct CapturedSolve {
  std::vector<double> gap, p;
  std::vector<double> shift;  // a contact-implicit solve's diag(shift) (m/Pa per cell): a third column; else empty
};

inline CapturedSolve read_captured_solve(const std::string& name, int cells) {
  std::ifstream in(FRETWEAR_SOURCE_DIR "/tests/regression/data/" + name);
  REQUIRE(in);
  CapturedSolve c;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 'g') continue;  // comments and the header
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream row(line);
    double g = 0.0, p = 0.0, d = 0.0;
    row >> g >> p;
    REQUIRE(row);
    c.gap.push_back(g);
    c.p.push_back(p);
    if (row >> d) c.shift.push_back(d);
  }
  REQUIRE(int(c.gap.size()) == cells);
  REQUIRE((c.shift.empty() || int(c.shift.size()) == cells));
  return c;
}

// `got` equals `want` (two summaries, or parts of them) in every value but wall time (timings, seconds,
// fatigue_seconds, brief): the same keys, numbers to the bit; a key of `got` alone is an error unless it is `extra`.
// Returns how many numbers were compared.
inline int compare_summaries(const nlohmann::json& got, const nlohmann::json& want, const std::string& at = "",
                             const std::string& extra = "") {
  const auto wall_time = [](const std::string& key) {
    return key == "timings" || key == "seconds" || key == "fatigue_seconds" || key == "brief";
  };
  int numbers = 0;
  if (want.is_object()) {
    REQUIRE_MESSAGE(got.is_object(), at);
    for (const auto& [key, value] : want.items()) {
      if (wall_time(key)) continue;
      CHECK_MESSAGE(got.contains(key), (at + "." + key + " missing"));
      if (got.contains(key)) numbers += compare_summaries(got[key], value, at + "." + key, extra);
    }
    for (const auto& [key, value] : got.items())
      CHECK_MESSAGE((want.contains(key) || key == extra), (at + "." + key + " extra"));
  } else if (want.is_array()) {
    REQUIRE_MESSAGE(got.size() == want.size(), at);
    for (std::size_t i = 0; i < want.size(); ++i)
      numbers += compare_summaries(got[i], want[i], at + "[" + std::to_string(i) + "]", extra);
  } else if (want.is_number() && got.is_number()) {
    CHECK_MESSAGE(got.get<double>() == want.get<double>(), at);
    ++numbers;
  } else {
    CHECK_MESSAGE(got == want, at);
  }
  return numbers;
}

}  // namespace fretwear::test
