// The fatigue measures of a scene that asks for effects.stress and solves a load cycle (contact/fatigue_measures.hpp):
// Smith–Watson–Topper on critical planes at every stress-map point, from the maps at the top and the bottom of the
// cycle, and Ruiz's F1 = τδ and F2 = σ_T τδ along the surface, for the state the maps show (the initial contact, or
// the last wear record).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/fatigue_measures.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/stress_stage.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

// SWT on the stress map's points.
struct SwtMap {
  std::vector<double> x, y;         // the stress maps' axes (m); the first row is the surface, y = 0
  std::vector<SwtResult> points;    // row-major: y outer, x inner
  SwtResult max;                    // the largest SWT over the map
  double max_x = 0.0, max_y = 0.0;  // where (m)
};

struct FatigueStage {
  SwtMap swt;
  std::optional<RuizProfile> ruiz;  // none in gross slip, where force control leaves the slip undetermined
  double seconds = 0.0;             // wall time of this stage (part of timings.stress)
};

// The measures from the stress maps just computed. maps: stress_maps' output at "top" and "bottom"; top: the loads
// at the top of the cycle (the same state as the maps); cycle: the cycle solved; wear: the wear stage or null (its
// last record's slip is used then). None when the maps hold no "top" and "bottom" pair.
std::optional<FatigueStage> run_fatigue(const Scene& scene, const Grid& grid, const Phase& top,
                                        const std::vector<StressMap>& maps, const CycleStage& cycle,
                                        const WearStage* wear);

// Adds the stress.swt_* and stress.ruiz_* keys to the summary's "stress" object.
void add_fatigue_summary(nlohmann::json& stress, const FatigueStage& fatigue);

// fatigue.csv, ruiz.csv and, with plots, fatigue.gp with swt_map.png and ruiz.svg/.png.
void write_fatigue(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, const FatigueStage& fatigue,
                   OutputFolder& out, Written& written);

}  // namespace fretwear
