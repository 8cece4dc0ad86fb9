// One scene, run: the normal contact (this issue), then the stages later issues add (the cycle, wear, stresses,
// cracks). Simulation::run() reads like the method; the physics lives in contact/ and wear/.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"
#include "contact/normal_solver.hpp"
#include "contact/profile.hpp"
#include "contact/window.hpp"
#include "engine/scene.hpp"

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
  double total = 0.0, normal = 0.0;  // wall seconds
};

struct RunResult {
  NormalResult normal;
  Timings timings;
};

// The normal contact of a scene on `cells` cells (the scene's own when 0). Throws ConvergenceError when the solve
// does not converge, InputError when the contact reaches the end of a given window.
NormalResult solve_normal(const Scene& scene, int cells = 0);

class Simulation {
 public:
  explicit Simulation(Scene scene) : scene_(std::move(scene)) {}
  RunResult run() const;
  const Scene& scene() const { return scene_; }

 private:
  Scene scene_;
};

// summary.json (SCENES.md's contract).
nlohmann::json make_summary(const Scene& scene, const RunResult& result);

}  // namespace fretwear
