// The life stage (PHYSICS.md, "Fretting-fatigue life"; contact/fatigue_life.hpp): when the contact starts a crack,
// and how long the crack takes to grow, over the states the run went through (the unworn contact, or every wear
// record, each holding from its cycle count to the next record's, the last for ever).
//
// Initiation. At each state k the critical-plane SWT (contact/fatigue_measures.hpp) is evaluated on a layer under
// the contact: points x across the contact and half its half-width beyond, depths y from the surface to the critical
// distance ℓ plus the specimen's deepest wear. A point at depth d below the surface damages at the rate
// 1/N_i(SWT_ℓ(x, d)), SWT_ℓ the SWT of the stress history averaged over the line [d, d + ℓ] below it (Taylor's line
// method, which averages stress: Taylor 2007; the point's own when ℓ = 0). Averaging the stresses, not the SWT, is
// what converges at a square-root singular edge: there σ ∝ r^(−1/2), whose mean over the line is finite, while
// SWT ∝ 1/r, whose mean grows like ln(ℓ/h) as the grid is refined. The layer's stresses are the convolution rows of
// contact/centre_stress.hpp at every cell centre (about 5 ms a state at 1024 cells), not the stress stage's maps,
// which sample too few points across and none graded in depth (docs/METHODS.md, "Fatigue life"); the states' loads
// are the stress stage's records (record_phases). Damage is carried by material
// points fixed in the specimen: the specimen's wear w_s(x) (its own frame's, WearRecord::w_specimen, in gross slip;
// elsewhere (1 − pad_fraction) w(x), the bodies sharing one scar split by pad_fraction) brings a point at original depth y₀ to depth y₀ − w_s, and removes it past the surface,
// taking its damage with it. The crack starts at the surface point x whose material first reaches D = 1:
//     D(N) = Σ_{j<k} (N_{j+1} − N_j) / N_i(SWT_ℓ,j(x, w_s,k − w_s,j)) + (N − N_k) / N_i(SWT_ℓ,k(x, 0)),
// solved in the interval of the state k in force. Without wear there is one state and N_i = N_i(SWT_ℓ(x, 0)), the
// SWT of the one cycle, exactly.
//
// Propagation. The crack grows where effects.crack places it (its position and angle) when the scene has a crack
// effect, otherwise normal to the surface at the initiation site, from a_initial (default ℓ) to a_final, by Paris'
// law on tables of the closed-crack SIFs of each state at kTableLengths lengths log-spaced over [a_initial, a_final]
// (the crack solver's, at the top and the bottom of the cycle), starting at the initiation's cycle count.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/fatigue_life.hpp"
#include "contact/fatigue_measures.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/stop.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

constexpr int kTableLengths = 40;  // crack lengths per SIF table (the growth interpolates between them)

struct LifeInitiationResult {
  double cycles = 0.0;             // N_i (+∞: never)
  double swt = 0.0;                // SWT_ℓ at the site in the state where it started (Pa)
  double x = 0.0, y = 0.0;         // the site (m): a surface point, y = 0
  double angle_deg = 0.0;          // the critical plane's normal at the site, from +x toward +y (degrees)
  double state_cycles = 0.0;       // the cycle count of the state in force then
  // The site is at a singular edge (engine/stress_stage.hpp, SingularEdges): its point SWT grows like 1/h with the
  // grid; the line method's converges (it averages the stresses, ∝ r^(−1/2) there) and is the one to use.
  bool singular = false;
  // The damage map at the initiation (at cycles_max if never): x, and the original depth y₀ below the unworn surface
  // (m); damage row-major, y outer, NaN where wear has removed the material (y₀ < map_surface of its column).
  std::vector<double> map_x, map_y;
  std::vector<double> damage;
  std::vector<double> map_surface;  // the specimen's wear depth per column then (m)
};

struct LifeStage {
  std::optional<LifeInitiationResult> initiation;
  std::optional<GrowthResult> propagation;
  double crack_x = 0.0, crack_angle_deg = 90.0;  // where the crack grows (m, degrees to the surface)
  double a_initial = 0.0, a_final = 0.0;          // m
  double total_cycles = 0.0;                      // +∞ when it never fails
  std::string fate;   // "failure", "arrest", "runout", or "initiation" when growth was not asked for
  double final_length = 0.0;  // m (0 without growth)
};

// The stage, over the unworn contact (wear null) or every wear record; `stop` is asked between initiation and growth,
// the first of its two parts done (stop_point()).
LifeStage run_life(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                   const WearStage* wear, const StopCheck& stop = {});

// SWT_ℓ of the line method at surface point x and depth d below it, for a cycle's phases (its top and bottom): the
// critical-plane SWT of the stresses averaged over [d, d + ℓ] (sampled at 48 depths graded toward d = 0); the
// point's own with ℓ = 0. The life stage evaluates it on its layer.
SwtResult line_swt(const Grid& grid, const std::vector<Phase>& phases, double x, double d, double ell,
                   const Material& specimen, PlaneState plane);

// Its part of summary.json: "life" (SCENES.md; an infinite count is null).
nlohmann::json summarise_life(const Scene& scene, const LifeStage& life);

// crack_growth.csv, damage.csv and, with plots, life.gp with life_damage.png and crack_growth.svg/.png.
void write_life(const Scene& scene, const LifeStage& life, OutputFolder& out, Written& written);

}  // namespace fretwear
