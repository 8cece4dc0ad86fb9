// PHYSICS.md's public cases as scenes, shared by the tests.
#pragma once

#include <string>

#include "engine/scene.hpp"

namespace fretwear::test {

// The public Hertz case: E = 200 GPa, ν = 0.3 both, plane strain, R = 10 mm, f = 0.5.
constexpr double kHertzE = 200e9, kHertzNu = 0.3, kHertzR = 0.01, kHertzF = 0.5;

// Hertz under load P (N/m) on `cells` cells, with one steady cycle at Q/fP = ratio and bulk tension sigma (Pa).
inline Scene hertz_cycle(double P, double ratio, int cells, double sigma = 0.0) {
  Scene s;
  s.name = "cycle";
  s.pad = s.specimen = {kHertzE, kHertzNu};
  s.profile.type = ProfileType::cylinder;
  s.profile.R = kHertzR;
  s.P = P;
  s.cells = cells;
  s.friction = kHertzF;
  s.Q_ratio = ratio;
  s.bulk_stress = sigma;
  s.tangential = TangentialEffect{};
  return s;
}

// The same worn by `law` ("archard": k = c; "energy": α = c) for `cycles` cycles, recorded 8 times.
inline Scene hertz_wear(double P, double ratio, double cycles, int cells, const std::string& law = "archard",
                        double c = 1e-12) {
  Scene s = hertz_cycle(P, ratio, cells);
  s.name = "wear";
  s.tangential_implied = true;
  WearEffect w;
  w.law = law;
  w.coefficient = c;
  w.cycles = cycles;
  w.record_count = 8;
  s.wear = w;
  return s;
}

}  // namespace fretwear::test
