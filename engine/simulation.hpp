// One scene, run: the normal contact (this issue), then the stages later issues add (the cycle, wear, stresses,
// cracks). Simulation::run() reads like the method; the physics lives in contact/ and wear/.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/normal_solver.hpp"
#include "contact/profile.hpp"
#include "contact/tangential_solver.hpp"
#include "contact/window.hpp"
#include "engine/crack_stage.hpp"
#include "engine/scene.hpp"
#include "engine/warnings.hpp"

namespace fretwear {

// The closed form the scene's profile has, if any, compared with the solution.
struct Reference {
  std::string kind;             // "hertz", "rounded_punch", "flat_punch"
  double half_width = 0.0;      // closed-form half-width (m)
  double centre = 0.0;          // m
  double p_max = 0.0;           // closed-form peak pressure (Pa); for the flat punch, that of the edge cells
  std::vector<double> p_cell;   // closed-form cell-average pressure per cell (Pa)
  double extent_error = 0.0;    // max |edge − closed form| / half-width
  double p_max_error = 0.0;     // |p_max − closed form| / closed form
  double rms_error = 0.0;       // RMS of p − p_cell over the contact cells less two at each edge, / p_max
};

struct NormalResult {
  Grid grid;
  WindowChoice window;
  std::vector<double> g0;       // initial gap per cell (m), +∞ off the pad
  ContactState state;
  SolveSummary summary;
  std::vector<Zone> zones;
  double p_max = 0.0, x_p_max = 0.0;
  int cells_in_contact = 0;
  std::optional<double> load_size_half_width;  // second, independent answer for symmetric single-zone profiles
  std::optional<Reference> reference;
};

struct Timings {
  double total = 0.0, normal = 0.0;   // wall seconds
  std::optional<double> tangential;   // present when the stage ran
  std::optional<double> wear;
  std::optional<double> stress, crack;
};

struct WearStage;
struct WearControl;  // engine/wear_stage.hpp
struct FatigueStage;  // engine/fatigue_stage.hpp

// What the cycle stage computed, with the route that ran.
struct CycleStage {
  CycleResult result;
  std::string route;  // "analogy"
  double Q_max = 0.0, f = 0.0, bulk_stress = 0.0;
  // The displacement datum (contact/reference_datum.hpp): reference points at depth reference_depth (m) below
  // reference_x (m), the centre of the contact under P alone.
  double reference_x = 0.0, reference_depth = 0.0;
  // Dissimilar bodies (β ≠ 0): the pressure at the top and the bottom of the steady cycle (Pa per cell), which the
  // shear changes; empty for similar bodies, whose pressure is the normal contact's at every instant.
  std::vector<double> p_top, p_bottom;
};

struct RunResult {
  NormalResult normal;
  std::optional<CycleStage> cycle;
  std::shared_ptr<const WearStage> wear;  // engine/wear_stage.hpp
  std::vector<StressMap> stress_maps;      // at the top and bottom (initial state, and the last record when wearing)
  std::vector<SifSet> sifs;                // at the top and bottom of every state (initial, then each record)
  double crack_x = 0.0;                    // where the crack is (m)
  std::shared_ptr<const FatigueStage> fatigue;  // SWT and Ruiz, with the stress maps of a cycle
  Timings timings;
  std::vector<Warning> warnings;  // what the results cannot be trusted for (engine/warnings.hpp)
};

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

// The normal contact. Throws ConvergenceError when the solve does not converge, InputError when the contact
// reaches the end of a given window or no cell of it can touch.
NormalResult solve_normal(const Scene& scene, const Model& model);
NormalResult solve_normal(const Scene& scene, int cells = 0);

// One steady load cycle. Throws UnsupportedError where the route the cycle needs is not built.
CycleStage solve_cycle(const Scene& scene, const Model& model, const NormalResult& normal);

class Simulation {
 public:
  explicit Simulation(Scene scene) : scene_(std::move(scene)) {}
  // control (optional) steers the wear stage: progress, checkpoints, resume, stop. A wear stage stopped on request
  // (WearStage::interrupted) ends the run there: stress and crack, which use the last record, are not computed.
  RunResult run(const WearControl* control = nullptr) const;
  const Scene& scene() const { return scene_; }

 private:
  Scene scene_;
};

// summary.json (SCENES.md's contract).
nlohmann::json make_summary(const Scene& scene, const RunResult& result);

}  // namespace fretwear
