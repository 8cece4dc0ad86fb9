#include "engine/cycle_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "contact/incremental_slip.hpp"
#include "contact/reference_datum.hpp"

namespace fretwear {
namespace {

// δ at the top of an analogy cycle: the stick zone of the steady cycle has never slipped (w = 0 there since the first
// loading), so at its cells the rigid shift is λ = (K q_top)_i + ε x_i (incremental_slip.hpp), and δ follows from the
// datum (reference_datum.hpp). In phase, the bottom is the top reversed: δ_max = |δ_top|.
void analogy_delta_max(const Model& model, const NormalResult& normal, const CyclicLoad& load,
                       const ReferenceDatum& datum, CycleResult& c) {
  if (!c.stick_zone || c.q_top.empty()) return;
  const Grid& g = model.grid;
  const double x_mid = 0.5 * (c.stick_zone->first + c.stick_zone->second);
  const int i = std::clamp(int(std::floor((x_mid - g.x_min) / g.h())), 0, g.n - 1);
  std::vector<double> u(g.n);
  model.kernel->apply(c.q_top, u);
  const double lambda = u[i] + load.bulk_strain * g.x(i);
  const double D0 = datum.relative_displacement(std::vector<double>(g.n, 0.0), normal.state.p);
  c.delta_max = std::abs(lambda + datum.relative_displacement(c.q_top, normal.state.p) - D0 -
                         load.bulk_strain * datum.x_c());
}

}  // namespace

CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal) {
  CycleStage stage;
  stage.f = *scene.friction;
  stage.Q_max = scene.Q_max();
  stage.bulk_stress = scene.bulk_stress;
  const ElasticPair& pair = model.pair;
  const double bulk_strain = pair.bulk_strain(scene.bulk_stress);
  const bool displacement = scene.control == LoadControl::displacement;
  CyclicLoad load{scene.P, stage.Q_max, stage.f, bulk_strain, displacement ? *scene.delta : 0.0};
  for (const auto& pt : scene.history) load.history.push_back({pt[0], pt[1], pt[2], pair.bulk_strain(pt[3])});
  const bool history = !load.history.empty();
  const TangentialRoute route = scene.tangential->route;
  // The datum: reference points 10 contact half-widths (or grid.reference_depth) below the contact's centre.
  const double x_left = normal.zones.front().left.x, x_right = normal.zones.back().right.x;
  stage.reference_x = 0.5 * (x_left + x_right);
  stage.reference_depth = scene.reference_depth ? *scene.reference_depth : 5.0 * (x_right - x_left);
  const ReferenceDatum datum(model.grid, pair, stage.reference_x, stage.reference_depth);
  if (route == TangentialRoute::analogy && (displacement || history))  // parse_scene refuses it too
    throw UnsupportedError("effects.tangential: route \"analogy\" cannot run load.control \"displacement\" or "
                           "load.history; use \"auto\" or \"incremental\"");
  // Dissimilar bodies (Dundurs β ≠ 0): normal and tangential problems coupled, the incremental route only.
  const bool dissimilar = std::abs(pair.beta()) > 1e-12;
  if (route == TangentialRoute::analogy && dissimilar)  // parse_scene refuses it too
    throw UnsupportedError(fmt::format("effects.tangential: route \"analogy\" needs similar bodies, and Dundurs beta "
                                       "= {:.4g}; use \"auto\" or \"incremental\"",
                                       pair.beta()));
  if (route != TangentialRoute::incremental && !displacement && !history && !dissimilar) {
    stage.route = "analogy";
    stage.result = TangentialSolver(*model.kernel).solve_cycle(model.g0, normal.state, normal.zones, load);
    if (stage.result.regime == Regime::partial_slip) analogy_delta_max(model, normal, load, datum, stage.result);
    if (stage.result.regime != Regime::reverse_slip) return stage;
    if (route == TangentialRoute::analogy)
      throw UnsupportedError("effects.tangential: " + stage.result.message +
                             "; the scene asks for route \"analogy\": use \"auto\" or \"incremental\"");
  }
  // The incremental route: the cycle marched in load increments with the traction as memory (reverse slip, and
  // whatever the analogy cannot do). The steady cycle is the second, after the first loading and one full cycle.
  IncrementalSlipOptions options;
  options.increments_per_cycle = scene.tangential->increments;
  if (dissimilar) options.cycles = 2;  // β ≠ 0: the first cycle after the first loading is not yet the steady one
  const IncrementalSlipSolver solver(*model.kernel, options);
  const NormalCoupling coupling{dissimilar ? pair.beta() : 0.0, model.g0};
  const IncrementalResult r = history ? solver.solve_history(normal.state, load, model.g0, &datum)
                                      : solver.solve(normal.state, load, &datum, &coupling);
  stage.ran = TangentialRoute::incremental;
  stage.route = route == TangentialRoute::incremental ? "incremental"
                : displacement ? "incremental (auto: displacement control)"
                : history      ? "incremental (auto: load history)"
                : dissimilar   ? "incremental (auto: dissimilar bodies)"
                               : "incremental (auto: the analogy found reverse slip)";
  if (dissimilar)
    stage.route += fmt::format(" [beta = {:.4g}: {} coupling sweeps over {} increments, at most {}]", pair.beta(),
                               r.n_coupling_sweeps, r.n_increments, r.max_coupling_sweeps);
  stage.result = r.cycles.back();
  if (dissimilar) stage.p_top = r.p_top, stage.p_bottom = r.p_bottom;
  if ((displacement || history) && !stage.result.slip_range.empty())
    stage.Q_max = stage.result.Q_peak;  // the peak Q reached
  return stage;
}

std::vector<Phase> cycle_phases(const Scene& scene, const std::vector<double>& p, const std::vector<double>* q_top) {
  if (!scene.tangential) return {{"loaded", p, {}, 0.0}};
  std::vector<double> q(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) q[i] = q_top && !q_top->empty() ? (*q_top)[i] : *scene.friction * p[i];
  std::vector<double> minus(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) minus[i] = -q[i];
  return {{"top", p, q, scene.bulk_stress}, {"bottom", p, minus, -scene.bulk_stress}};
}

}  // namespace fretwear
