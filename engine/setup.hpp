// What every stage of a scene shares, resolved once before any stage runs (docs/METHODS.md, "The stage layer"):
// the model (the bodies, the profile, and the grid over the window chosen for them, with the initial gap and the
// kernel), the plan of the load cycle (the cyclic load with its bulk strain, and the route with the reason for it),
// and the effects to run. Stages take these decisions from here and never make them again.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/profile.hpp"
#include "contact/tangential_solver.hpp"
#include "contact/window.hpp"
#include "engine/scene.hpp"

namespace fretwear {

// The bodies, the profile and the discretisation of a scene: what every stage shares.
struct Model {
  ElasticPair pair;
  Profile profile;
  Grid grid;
  WindowChoice window;
  std::vector<double> g0;  // initial gap per cell (m)
  std::unique_ptr<HalfPlaneKernel> kernel;
};

// The model of a scene on `cells` cells (the scene's own when 0).
Model make_model(const Scene& scene, int cells = 0);

// How the steady load cycle is solved, decided from the scene and the bodies alone, before any solve.
struct CyclePlan {
  // P, Q_max, f, δ, and the bulk strain ε = σ (κ₂ + 1)/(8 μ₂) of the bulk stress (ElasticPair::bulk_strain),
  // each history point's too.
  CyclicLoad load;
  TangentialRoute asked = TangentialRoute::automatic;  // effects.tangential.route
  double beta = 0.0;  // Dundurs β of the pair: ≠ 0 couples the normal and the tangential problems
  // Why the incremental route runs without the analogy being tried: empty when the analogy is tried first (asked,
  // or "auto" under force control with one Q amplitude on similar bodies), else "incremental" when asked, or
  // "incremental (auto: displacement control)", "(auto: load history)", "(auto: dissimilar bodies)". Under "auto"
  // the analogy may still hand over to the incremental route once it has solved the cycle and found reverse slip.
  std::string incremental_because;
  bool analogy_first() const { return incremental_because.empty(); }
  bool dissimilar() const { return beta != 0.0; }
};

// The cyclic load of a scene with friction: P, Q_max, f, δ, and the bulk strain of the bulk stress (each history
// point's too).
CyclicLoad cyclic_load(const Scene& scene, const ElasticPair& pair);
// Block b of load.blocks as a scene of its own: the scene with the block's Q, δ or history (and control) in place
// of its own, no blocks, and the block's cycles for the wear's.
Scene block_scene(const Scene& scene, const LoadBlock& b);
// The cyclic load of block b of load.blocks: block_scene's.
CyclicLoad block_load(const Scene& scene, const ElasticPair& pair, const LoadBlock& b);

// The plan of a scene with a tangential effect. Throws UnsupportedError where the route asked for cannot run the
// load or the bodies (the scene's checks refuse these too).
CyclePlan plan_cycle(const Scene& scene, const ElasticPair& pair);

// The effects a scene runs, in order, with those another needs (tangential for wear, and the fatigue measures of a
// stress map under a cycle).
struct Effects {
  bool cycle = false, wear = false, stress = false, fatigue = false, crack = false, life = false;
};

struct Setup {
  Model model;
  std::optional<CyclePlan> cycle;  // with the cycle effect
  Effects effects;
};

Setup make_setup(const Scene& scene);

// Where a wearing scene's worn contact tends to: the worn extent of its asymptote (paper 002's limit), or where the
// scene has none of its own, of stand-ins that have one (the similar pair of the same compliance, each load held
// constant; docs/SCENES.md, "Wear"), the widest; the trial grids are centred at `centre` and start 5 half_width
// wide. `itself`: the scene's own asymptote. None where no stand-in has a limit (gross slip). The default window
// covers it with a margin; a given window that does not is warned (engine/preflight.cpp).
struct WornReach {
  std::pair<double, double> extent;  // m
  bool itself = true;
  bool every_load = true;  // every stand-in has a limit (else a load may wear without one, as in gross slip)
  // The window that covers it as the default window does: the extent with half its half-width to spare each side.
  std::pair<double, double> covered() const {
    const double c = 0.5 * (extent.first + extent.second), hw = 0.5 * (extent.second - extent.first);
    return {c - 1.5 * hw, c + 1.5 * hw};
  }
};
std::optional<WornReach> worn_reach(const Scene& scene, const Profile& profile, double centre, double half_width);

}  // namespace fretwear
