// The stress and crack stages of a scene: stresses under the surface and the SIFs of a crack at the contact edge, at
// the top and the bottom of the load cycle, for the initial contact and every recorded wear state.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "contact/crack_solver.hpp"
#include "contact/grid.hpp"
#include "contact/subsurface_stress.hpp"
#include "engine/scene.hpp"

namespace fretwear {

// The loads at one instant: the surface tractions and the bulk stress.
struct Phase {
  std::string name;  // "top", "bottom"
  std::vector<double> p, q;
  double sigma_bulk = 0.0;
};

struct SifSet {
  std::string phase;
  double cycles = 0.0;
  CrackResult result;
};

struct StressMap {
  std::string phase;
  std::vector<double> x, y;     // map axes (m)
  std::vector<Stress> sigma;    // row-major: y outer, x inner
  std::vector<double> surface_sxx;  // σxx at y = 0 per map x (Pa)
  double trailing_peak = 0.0, trailing_peak_x = 0.0;  // largest surface σxx on the trailing half (Pa, m)
};

// SIFs at x_c for each phase.
std::vector<SifSet> crack_sifs(const Grid& grid, const std::vector<Phase>& phases, double x_c,
                               const CrackEffect& effect, double cycles);

// Stress maps over [x_lo, x_hi] × [0, depth] for each phase.
std::vector<StressMap> stress_maps(const Grid& grid, const std::vector<Phase>& phases, double x_lo, double x_hi,
                                   double depth, const StressEffect& effect);

}  // namespace fretwear
