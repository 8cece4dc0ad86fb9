// The normal stage: the contact under the normal load P alone (contact/normal_solver.hpp), its zones located to
// sub-cell accuracy, and its closed form where the profile has one (Hertz, the rounded and the sharp punch).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/contact_zones.hpp"
#include "contact/edge_intensity.hpp"
#include "contact/grid.hpp"
#include "contact/normal_solver.hpp"
#include "contact/window.hpp"
#include "engine/folder.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"

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
  // K_N at the outer ends of the contact (Pa·m^0.5): fitted where an end is a corner of the pad the contact reaches
  // (complete contact: the pressure is square-root singular there), empty at an incomplete edge.
  EdgeIntensities edge_intensity;
  double p_max = 0.0, x_p_max = 0.0;
  int cells_in_contact = 0;
  std::optional<double> load_size_half_width;  // second, independent answer for symmetric single-zone profiles
  std::optional<Reference> reference;
  // p_max solved again on half the cells over the same window (check_peak): how far the grid resolves the peak.
  struct PeakCheck {
    int cells = 0;
    double p_max = 0.0;  // Pa
    double change = 0.0;  // |p_max − this p_max| / p_max
  };
  std::optional<PeakCheck> peak_check;
};

// The normal contact. Throws ConvergenceError when the solve does not converge, InputError when the contact
// reaches the end of a given window or no cell of it can touch.
NormalResult solve_normal(const Scene& scene, const Model& model);
NormalResult solve_normal(const Scene& scene, int cells = 0);

// contact.p_max on half the cells over the same window, where nothing else says whether the grid resolves it: no
// closed form to meet (Reference), and not at a singular edge (p_max_singular), whose peak grows with the grid by
// nature. A peak that changes by more than kPeakChangeShare from half the cells is warned (`peak_unconverged`): a
// feature of the profile narrower than a few cells (a corner's rounding), or a kink (a table's linear interpolation
// bends the profile at each point, where the pressure peaks like ln(1/h)). Empty when skipped, or when the coarser
// solve fails (it is only a check).
std::optional<NormalResult::PeakCheck> check_peak(const Scene& scene, const NormalResult& normal);

// Its part of summary.json: "contact" (the extent, the zones, the peak, the load balance, the closed form), "grid",
// "materials" and "solver.normal".
nlohmann::json summarise_normal(const Scene& scene, const NormalResult& normal);

// Whether contact.p_max sits at a singular edge: within two cells of an outer end of the contact where the pressure
// is square-root singular (an edge intensity was fitted there: a corner of the pad). There it is the cell's share of
// an infinite peak and grows like √(1/h) with the grid; contact.edge_intensity is what converges.
bool p_max_singular(const NormalResult& normal);

// contact.csv and, with plots, pressure.gp (with the coupled pressure at the top and the bottom of the cycle of
// dissimilar bodies, when `p_top` and `p_bottom` are given).
void write_normal(const Scene& scene, const NormalResult& normal, const std::vector<double>& p_top,
                  OutputFolder& out, Written& written);

}  // namespace fretwear
