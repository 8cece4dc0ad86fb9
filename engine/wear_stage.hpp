// The wear stage of a scene: the contact seen by wear (the analogy route on the worn profile), the asymptotic state
// computed directly, and the run driven through Boost.Odeint with records.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "contact/normal_solver.hpp"
#include "engine/scene.hpp"
#include "wear/contact_response.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"

namespace fretwear {

struct Model;
struct NormalResult;

using Interval = std::pair<double, double>;

// The asymptotic state of paper 002 (PHYSICS.md, "Wear"): complete contact over the initial stick zone on the
// original profile; the worn depth is the overlap it leaves outside.
struct WearAsymptote {
  std::vector<double> p;       // pressure (Pa), zero outside the stick zone
  std::vector<double> w;       // worn depth, both bodies (m)
  double worn_area = 0.0;      // ∫ w dx (m²)
  double max_depth = 0.0;      // m
  double x_max_depth = 0.0;    // m
  Interval extent{0.0, 0.0};   // where w > 0 (outer ends, m)
};

// One record of the run.
struct WearRecord {
  double cycles = 0.0;
  double worn_area = 0.0, max_depth = 0.0, p_max = 0.0;
  std::optional<Interval> stick_zone;
  Interval contact{0.0, 0.0};
  double fraction = 0.0;  // worn area over the asymptote's
  std::vector<double> w, p, s;  // per cell
  std::vector<double> q;        // shear traction at the top of the cycle per cell (Pa); the bottom is −q
};

struct WearStage {
  std::vector<WearRecord> records;
  WearAsymptote asymptote;
  double rate_coefficient = 0.0;    // c in dw/dN = c p s (1/Pa)
  double stability_limit = 0.0;     // the explicit jump limit 1.5 Δx/(E* c s_max) at the start (cycles)
  double explicit_step_cap = 0.0;   // stepper "explicit": the cap on ΔN, kExplicitCapFraction · stability_limit
                                    // (cycles); 0 for the other steppers
  double explicit_max_step = 0.0;   // stepper "explicit": the longest accepted step (cycles), ≤ the cap
  int steps = 0, rejected_steps = 0, implicit_solves = 0, responses = 0;
  double mean_iterations_cycle = 0.0, mean_iterations_implicit = 0.0;  // CG iterations per warm-started solve
};

// The steady-cycle slip and stick zone on a worn profile, by the analogy route (similar bodies, constant P).
class AnalogyContactResponse : public wear::ContactResponse {
 public:
  AnalogyContactResponse(const Scene& scene, const Model& model);
  int cells() const override;
  double cell_width() const override;
  void respond(std::span<const double> w, wear::CycleResponse& out) override;
  void implicit_pressure(std::span<const double> w, std::span<const double> d, std::vector<double>& p) override;
  // The last normal and corrective pressures (for records).
  const std::vector<double>& corrective_pressure() const { return corrective_.p; }
  // Solves and their CG iterations, by kind: the cycle (normal and corrective) and the contact-implicit steps.
  long cycle_solves = 0, cycle_iterations = 0, implicit_solves = 0, implicit_iterations = 0;

 private:
  const Scene& scene_;
  const Model& model_;
  NormalSolver solver_;
  double tilt_ = 0.0, corrective_load_ = 0.0;
  ContactState normal_, corrective_, implicit_;
  std::vector<double> gap_;
};

WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& normal);

// The explicit stepper's cap on ΔN as a share of the forward-Euler limit 1.5 Δx/(E* c s_max). Dormand–Prince's
// stability region reaches about 3.3 along the negative real axis where Euler's reaches 2, so this leaves dopri5 a
// margin of about 1.5 for the limit's drift as the profile wears and for the estimate's own approximation.
inline constexpr double kExplicitCapFraction = 0.9;

// Runs the wear of a scene with the stepper it names (effects.wear.stepper): "implicit" (the default), "explicit"
// (Dormand–Prince capped below the stability limit; small problems) or "cycle_by_cycle" (every cycle worn, the
// reference on short runs; throws UnsupportedError when one cycle exceeds the stability limit). The normal solution
// and the first cycle have been computed on the same model.
WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal);

}  // namespace fretwear
