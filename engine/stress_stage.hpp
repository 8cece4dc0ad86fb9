// The stress stage: the stresses under the surface (contact/subsurface_stress.hpp) at the top and the bottom of the
// load cycle, over a map around the contact, for the state the run ends in (the unworn contact, or the last wear
// record).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/grid.hpp"
#include "contact/subsurface_stress.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

// One phase's map. Rows: the surface y = 0, where σyy = −p, σxy = −q and σxx are the tractions' exact limits
// (contact/subsurface_stress.hpp), then ny rows at y_j = (j + ½) depth / ny, j = 0 … ny − 1.
struct StressMap {
  std::string phase;
  std::vector<double> x, y;     // map axes (m); y[0] = 0
  std::vector<Stress> sigma;    // row-major: y outer, x inner
  std::vector<double> surface_sxx;  // σxx of the surface row per map x (Pa)
  double trailing_peak = 0.0, trailing_peak_x = 0.0;  // largest surface σxx on the trailing half (Pa, m)
};

// Stress maps over [x_lo, x_hi] × [0, depth] for each phase, nx × (ny + 1) points.
std::vector<StressMap> stress_maps(const Grid& grid, const std::vector<Phase>& phases, double x_lo, double x_hi,
                                   double depth, const StressEffect& effect);

// The loads of the state the run ends in: the cycle's top and bottom on the unworn contact, or on the last wear
// record (cycle and wear may be null).
std::vector<Phase> final_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle,
                                const WearStage* wear);

// The stage: the maps over the contact and half its width on either side, down to effects.stress.depth (the contact
// half-width when 0), of final_phases().
std::vector<StressMap> run_stress(const Scene& scene, const Model& model, const NormalResult& normal,
                                  const CycleStage* cycle, const WearStage* wear);

// Its part of summary.json: "stress" (each phase's peaks, the map's window and depth, the record it shows).
nlohmann::json summarise_stress(const Scene& scene, const std::vector<StressMap>& maps, const WearStage* wear);

// stress.csv, surface_stress.csv and, with plots, stress.gp with the von Mises and σxx maps.
void write_stress(const Scene& scene, const std::vector<StressMap>& maps, OutputFolder& out, Written& written);

}  // namespace fretwear
