// The fatigue measures of a scene that asks for effects.stress and solves a load cycle (contact/fatigue_measures.hpp):
// Smith–Watson–Topper on critical planes at every stress-map point, from the maps at the top and the bottom of the
// cycle, and Ruiz's F1 = τδ and F2 = σ_T τδ along the surface, for every state the maps show (the initial contact, or
// each wear record).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/fatigue_measures.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/stop.hpp"
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

// The measures of one recorded state.
struct FatigueRecord {
  double cycles = 0.0;              // the wear record (0: the unworn contact)
  SwtMap swt;                       // on that state's stress maps (the last state's full map, kRecordStride before)
  std::optional<RuizProfile> ruiz;  // none in gross slip, where force control leaves the slip undetermined
};

struct FatigueStage {
  std::vector<FatigueRecord> records;  // every state of the stress maps, in their order
  double seconds = 0.0;                // wall time of this stage (part of timings.stress)
  const FatigueRecord& last() const { return records.back(); }  // the state the summary reports
};

// The measures from the stress maps just computed. states: record_phases(), the loads of every state; maps:
// run_stress's output for them, "top" and "bottom" of each; cycle: the cycle solved; wear: the wear stage or null
// (each record's slip is used then, the cycle's otherwise). None when the maps hold no "top" and "bottom" pair.
// `stop` is asked before each row of each SWT map, and once all are done, with the rows done of all the maps'
// (stop_point(); the stage is "stress", whose time this is part of).
std::optional<FatigueStage> run_fatigue(const Scene& scene, const Grid& grid, const std::vector<RecordPhases>& states,
                                        const std::vector<StressMap>& maps, const CycleStage& cycle,
                                        const WearStage* wear, const StopCheck& stop = {});

// Adds the stress.swt_* and stress.ruiz_* keys of the last record to the summary's "stress" object.
// swt_max_singular: the maximum sits at a singular edge (engine/stress_stage.hpp, SingularEdges).
void add_fatigue_summary(nlohmann::json& stress, const FatigueStage& fatigue, const SingularEdges& singular);

// fatigue.csv and ruiz.csv (every record, first column cycles) and, with plots, fatigue.gp with swt_map.png (the
// last record) and ruiz.svg/.png (every record).
void write_fatigue(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, const FatigueStage& fatigue,
                   OutputFolder& out, Written& written);

}  // namespace fretwear
