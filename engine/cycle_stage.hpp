// The cycle stage: one steady load cycle of partial slip (contact/tangential_solver.hpp, the analogy route, or
// contact/incremental_slip.hpp, the incremental route), with the route that ran and why, and the displacement datum.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/closed_form.hpp"
#include "contact/tangential_solver.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/stop.hpp"

namespace fretwear {

// The loads at one instant: the surface tractions and the bulk stress.
struct Phase {
  std::string name;  // "top", "bottom"
  std::vector<double> p, q;
  double sigma_bulk = 0.0;
};

// What the cycle stage computed, with the route that ran.
struct CycleStage {
  CyclePlan plan;  // the load and the route as planned (engine/setup.hpp): what the wear stage runs too
  CycleResult result;
  std::string route;  // the route that ran, and why ("incremental (auto: the analogy found reverse slip)")
  TangentialRoute ran = TangentialRoute::analogy;  // analogy or incremental: what the wear stage runs too
  double Q_max = 0.0, f = 0.0, bulk_stress = 0.0;
  // The displacement datum (contact/reference_datum.hpp): reference points at depth reference_depth (m) below
  // reference_x (m), the centre of the contact under P alone.
  double reference_x = 0.0, reference_depth = 0.0;
  // The pressure at the top and the bottom of the steady cycle (Pa per cell): for dissimilar bodies (β ≠ 0), where
  // the shear changes it, and under a load history (any β), where P varies; empty otherwise, where the pressure is
  // the normal contact's at every instant. What the run reports as the coupled pressure (cycle.csv, summary.json,
  // pressure.gp) is this for β ≠ 0 only (plan.dissimilar()).
  std::vector<double> p_top, p_bottom;
  // The bulk stress at the top and the bottom (Pa): ±load.bulk_stress in phase with Q (or δ), and a history's
  // sigma_bulk where its Q is largest and smallest.
  double sigma_top = 0.0, sigma_bottom = 0.0;
  // Each load history whose P moves (the scene's, or a block's of load.blocks), its steady cycle's dissipated energy
  // marched at the scene's increments and at half of them (J/m). Where P moves within an increment the energy
  // converges at first order in the increments (docs/METHODS.md, "Load histories"), so its change from half the
  // increments estimates the error left at the scene's; warned past 1 %. A block's is on the unworn contact.
  struct HistoryEnergy {
    int block = -1;  // the block of load.blocks; -1 for the scene's own history
    double energy = 0.0, energy_half = 0.0;
    int half_increments = 0;  // the increments per cycle of the second march
  };
  std::vector<HistoryEnergy> history_energy;
  // A load history: the cycles marched after the first loading until one ended where it began or repeated the one
  // before it (the steady cycle reported; IncrementalSlipOptions::steady_cycles_max), and whether one did within
  // that cap.
  int history_cycles = 0;
  bool history_steady = true;
};

// The displacement datum's reference points (contact/reference_datum.hpp): below the centre of the contact under P
// alone, grid.reference_depth deep, or 10 contact half-widths. {x_c, d} (m). The one rule for the cycle stage and
// the wear stage's limit under displacement control.
std::pair<double, double> reference_point(const Scene& scene, const NormalResult& normal);

// One steady load cycle, by the plan. Throws UnsupportedError where the analogy, asked for, finds reverse slip.
CycleStage solve_cycle(const Scene& scene, const Model& model, const CyclePlan& plan, const NormalResult& normal,
                       const StopCheck& stop = {});
// The same with the scene's own plan (plan_cycle).
CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal);

// The loads at the top and the bottom of an in-phase cycle of similar bodies under a constant P (just "loaded"
// without one), on the pressure p: the bottom is the top reversed, as the steady cycle is antisymmetric (exactly, so
// that both edges of a symmetric contact tie); q_top empty or null (gross slip) gives q = ±f p. What each wear record
// holds.
// The Cattaneo–Mindlin stick zone of the unworn cycle where PHYSICS.md has it (Hertz under force control, similar
// bodies, one steady partial-slip cycle; shifted by a bulk tension, Nowell and Hills 1987); none elsewhere.
std::optional<closed_form::StickZone> mindlin_stick_zone(const Scene& scene, const NormalResult& n,
                                                         const CycleStage& cycle);

std::vector<Phase> cycle_phases(const Scene& scene, const std::vector<double>& p, const std::vector<double>* q_top);

// The loads at the top and the bottom of the unworn contact's steady cycle, as solved (just "loaded" without one):
// for similar bodies under a constant P, cycle_phases() on the normal pressure; for dissimilar bodies (β ≠ 0) and
// under a load history, the cycle's own pressure, shear and bulk stress at each, CycleStage::p_top with
// CycleResult::q_top and sigma_top, and p_bottom with q_bottom and sigma_bottom. The bottom is not the top reversed
// then: with β ≠ 0 the shear moves the pressure one way at the top and another at the bottom (PHYSICS.md,
// "Dissimilar bodies and per-body wear"), and a history's P and sigma_bulk need not be antisymmetric.
// These are tractions on the specimen's surface: the stresses they cause in the specimen, taken as a half-plane,
// do not depend on its elastic constants (plane elasticity with tractions given on the whole boundary: the
// Flamant kernel carries none), so the stress, crack and life stages take them as they are, whatever the pad. The
// strains do depend on them: the fatigue measures (SWT's strain range, the plane-strain σzz = ν (σxx + σyy) of
// von Mises) use the specimen's E and ν, the body the stresses are in; the pad's enter only through the tractions.
std::vector<Phase> cycle_phases(const Scene& scene, const NormalResult& normal, const CycleStage* cycle);

// Its part of summary.json: "cycle" (the route, the regime, the stick zones, the energy, the slip, the datum).
nlohmann::json summarise_cycle(const Scene& scene, const CycleStage& cycle);

// cycle.csv and loop.csv (when the cycle slips somewhere) and, with plots, cycle.gp (traction and slip) and loop.gp.
void write_cycle(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, OutputFolder& out,
                 Written& written);

}  // namespace fretwear
