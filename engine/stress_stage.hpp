// The stress stage: the stresses under the surface (contact/subsurface_stress.hpp) at the top and the bottom of the
// load cycle, over a map around the contact, for every state the run records: the unworn contact (cycles = 0), and
// each wear record when the scene wears. The last state's maps are at the scene's resolution; the earlier records'
// maps, which feed the fatigue measures at every record, on a subset of the same points (kRecordStride).
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
#include "engine/stop.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

// One phase's map. Rows: the surface y = 0, where σyy = −p, σxy = −q and σxx are the tractions' exact limits
// (contact/subsurface_stress.hpp), then ny rows at y_j = (j + ½) depth / ny, j = 0 … ny − 1.
struct StressMap {
  std::string phase;
  double cycles = 0.0;          // the wear record it shows (0: the unworn contact)
  std::vector<double> x, y;     // map axes (m); y[0] = 0
  std::vector<Stress> sigma;    // row-major: y outer, x inner
  std::vector<double> surface_sxx;  // σxx of the surface row per map x (Pa)
  double trailing_peak = 0.0, trailing_peak_x = 0.0;  // largest surface σxx on the trailing half (Pa, m)
};

// The earlier records' maps take every kRecordStride-th point of the full map across and in depth (the surface row
// and the first column always, the last where the stride reaches it): a map at every record costs 1/stride² of the
// last one, and its values are those of the full map at the same points.
inline constexpr int kRecordStride = 2;

// Stress maps over [x_lo, x_hi] × [0, depth] for each phase, on every stride-th point of the effect's nx × (ny + 1)
// points.
// The surface stresses at x (y = 0): linear between the two nearest cell centres (the source says why).
Stress surface_stress(const SurfaceTractions& t, const Grid& grid, double x);

// `stop` is asked before each column, with the columns done of all the phases' (stop_point()).
std::vector<StressMap> stress_maps(const Grid& grid, const std::vector<Phase>& phases, double x_lo, double x_hi,
                                   double depth, const StressEffect& effect, double cycles = 0.0, int stride = 1,
                                   const StopCheck& stop = {});

// The loads of one recorded state: the cycle's top and bottom (or the loaded state without a cycle).
struct RecordPhases {
  double cycles = 0.0;
  std::vector<Phase> phases;
};

// The loads of every state the run records, in order: the unworn contact alone, or each wear record (the first the
// unworn one, cycles = 0). cycle and wear may be null.
std::vector<RecordPhases> record_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle,
                                        const WearStage* wear);

// The loads of the state the run ends in: record_phases().back().phases.
std::vector<Phase> final_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle,
                                const WearStage* wear);

// The stage: the maps over the contact and half its width on either side, down to effects.stress.depth (the contact
// half-width when 0), of every state of record_phases(), in its order, each state's phases together; the last state
// on the full map, the earlier ones with stride kRecordStride.
// `stop` is asked before each column of each map, and once all are done, with the columns done of all the maps'
// (stop_point()).
std::vector<StressMap> run_stress(const Scene& scene, const Model& model, const NormalResult& normal,
                                  const CycleStage* cycle, const WearStage* wear, const StopCheck& stop = {});

// The maps of the last state in `maps` (run_stress's order).
std::vector<StressMap> last_record(const std::vector<StressMap>& maps);

// Its part of summary.json: "stress" (each phase's peaks, the map's window and depth, the record it shows), from
// the last state's maps.
// Where the pressure of the state the maps show is square-root singular (PHYSICS.md, "Singular edges"): the outer
// ends of a complete contact (the corners whose K_N the normal stage fits) and, on a worn contact at its limit (the
// last record within kNearLimit of the asymptote's worn area), the ends of the stick zones, which wear leaves a
// complete contact over. A stress or fatigue maximum there grows with the grid by nature: its value is reported with
// "singular": true, and what converges is the edge's intensity K_N.
struct SingularEdges {
  std::vector<double> x;  // m
  double reach = 0.0;     // m: a point within this distance of an edge (and this deep at most) sits at it
  bool at(double px, double py) const;
};
constexpr double kNearLimit = 0.95;  // a worn contact this close to its asymptote's worn area is at its limit
// maps: the stress stage's (their spacing widens the reach), or empty.
SingularEdges singular_edges(const NormalResult& normal, const CycleStage* cycle, const WearStage* wear,
                             const std::vector<StressMap>& maps);

nlohmann::json summarise_stress(const Scene& scene, const std::vector<StressMap>& maps, const WearStage* wear,
                                const SingularEdges& singular);

// From the last state's maps: stress.csv, surface_stress.csv and, with plots, stress.gp with the von Mises and σxx
// maps. A map at every record would make stress.csv some 3 MB per record (161 × 82 points, two phases).
void write_stress(const Scene& scene, const std::vector<StressMap>& maps, OutputFolder& out, Written& written);

}  // namespace fretwear
