// PHYSICS.md's public cases as scenes, shared by the tests.
#pragma once

#include <string>

#include "engine/scene.hpp"

namespace fretwear::test {

// The public Hertz case: E = 200 GPa, ν = 0.3 both, plane strain, R = 10 mm, f = 0.5.
constexpr double kHertzE = 200e9, kHertzNu = 0.3, kHertzR = 0.01, kHertzF = 0.5;

// A normal-contact scene of the public materials (E = 200 GPa, ν = 0.3 both, plane strain) on any profile.
inline Scene normal_scene(const ProfileSpec& profile, double P, int cells, const std::string& name = "normal") {
  Scene s;
  s.name = name;
  s.pad = s.specimen = {kHertzE, kHertzNu};
  s.profile = profile;
  s.P = P;
  s.cells = cells;
  return s;
}

// The public cylinder (R = 10 mm), shifted along x by offset (m).
inline ProfileSpec cylinder(double offset = 0.0) {
  ProfileSpec p;
  p.type = ProfileType::cylinder;
  p.R = kHertzR;
  p.offset_x = offset;
  return p;
}

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
  w.law = wear::law_from_string(law);
  w.coefficient = c;
  w.cycles = cycles;
  w.record_count = 8;
  s.wear = w;
  return s;
}

// Paper 001's Mindlin case in SI (PHYSICS.md, "Public reference cases"): P = 1200 lbf/in, Q = 270 lbf/in, μ = 0.5,
// R = 25.4 mm, E = 63.545 GPa, ν = 0.3, which give a = 0.01737 in; bulk tension sigma (Pa) in phase.
inline Scene paper001_mindlin(int cells, double sigma = 0.0) {
  Scene s = hertz_cycle(210152.2, 0.0, cells, sigma);
  s.Q_ratio.reset();
  s.Q_amplitude = 47284.25;
  s.profile.R = 25.4e-3;
  s.pad = s.specimen = {63.545e9, 0.3};
  return s;
}

}  // namespace fretwear::test
