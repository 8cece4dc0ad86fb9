// The cycle stage: one steady load cycle of partial slip (contact/tangential_solver.hpp, the analogy route, or
// contact/incremental_slip.hpp, the incremental route), with the route that ran and why, and the displacement datum.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/tangential_solver.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"

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
  // Dissimilar bodies (β ≠ 0): the pressure at the top and the bottom of the steady cycle (Pa per cell), which the
  // shear changes; empty for similar bodies, whose pressure is the normal contact's at every instant.
  std::vector<double> p_top, p_bottom;
};

// One steady load cycle, by the plan. Throws UnsupportedError where the analogy, asked for, finds reverse slip.
CycleStage solve_cycle(const Scene& scene, const Model& model, const CyclePlan& plan, const NormalResult& normal);
// The same with the scene's own plan (plan_cycle).
CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal);

// The loads at the top and the bottom of the cycle (just "loaded" without one): in phase, the bottom is the top
// reversed; q_top empty or null (gross slip) gives q = ±f p.
std::vector<Phase> cycle_phases(const Scene& scene, const std::vector<double>& p, const std::vector<double>* q_top);

// Its part of summary.json: "cycle" (the route, the regime, the stick zones, the energy, the slip, the datum).
nlohmann::json summarise_cycle(const Scene& scene, const CycleStage& cycle);

// cycle.csv and loop.csv (when the cycle slips somewhere) and, with plots, cycle.gp (traction and slip) and loop.gp.
void write_cycle(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, OutputFolder& out,
                 Written& written);

}  // namespace fretwear
