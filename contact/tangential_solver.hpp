// Cyclic partial slip of similar bodies (Dundurs β = 0) under constant P, with Q cycling 0 → +Q → −Q → +Q and a bulk
// tension σ in the specimen in phase with Q: the analogy route of ARCHITECTURE.md.
//
// Ciavarella–Jäger analogy (paper 002; Ciavarella 1998, Jäger 1998) with Mindlin–Deresiewicz superposition
// (PHYSICS.md, "Partial slip under constant P"): at the top of the cycle
//     q = f p − f p*,
// with p* the normal pressure of the same (worn) profile tilted by −(ε/f)·x at the reduced load P − Q/f, where
// ε = σ (κ₂ + 1)/(8 μ₂) is the specimen's bulk strain (so ε/A = σ/4 for similar bodies: Nowell and Hills 1987). The
// stick zone is p*'s contact; the relative slip in the slip zones is f g*, g* the corrective problem's gap.
// Unloading by ΔQ from the top adds −2f p + 2f p**, p** the pressure at P − ΔQ/(2f) with tilt −(ε_Δ/(2f))·x (paper
// 002 eq 19); the bottom of the cycle is the top reversed. Each point of a slip zone therefore travels S = 4 f g*
// per cycle at |q| = f p, and the energy dissipated per cycle is ∫ f p S dx.
//
// The route holds while the corrective contact stays inside the contact (no reverse slip) and Q < fP; outside that
// it reports the regime and leaves the fields empty: reverse slip needs the incremental route.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "contact/contact_zones.hpp"
#include "contact/normal_solver.hpp"

namespace fretwear {

enum class Regime { partial_slip, reverse_slip, gross_slip };
std::string to_string(Regime r);

// One point of a load history (load.history): the cycle as points, repeated.
struct HistoryPoint {
  double t = 0.0;            // time (s): orders the points and shares the increments among the segments
  double P = 0.0;            // normal load (N/m), > 0
  double Q = 0.0;            // tangential load (N/m)
  double bulk_strain = 0.0;  // ε of the specimen
};

struct CyclicLoad {
  double P = 0.0;          // normal load (N/m), constant
  double Q_max = 0.0;      // tangential load at the top of the cycle (N/m), ≥ 0
  double f = 0.0;          // Coulomb friction coefficient, > 0
  double bulk_strain = 0.0;  // ε of the specimen at the top of the cycle (σ (κ₂ + 1)/(8 μ₂)), in phase with Q
  // > 0: displacement control (incremental route only): the datum's δ cycles 0 → +δ → −δ → +δ (m), Q_max is not
  // used and the bulk strain is in phase with δ.
  double delta = 0.0;
  // Non-empty: force control through these points instead (incremental route; the last point repeats the first, and
  // P, Q_max, bulk_strain and delta are not used).
  std::vector<HistoryPoint> history = {};
};

using Interval = std::pair<double, double>;

// One point of the fretting loop: the loads at the end of an increment and the relative tangential displacement of
// the reference points (contact/reference_datum.hpp).
struct LoopPoint {
  double P = 0.0;      // normal load (N/m)
  double Q = 0.0;      // tangential load (N/m)
  double delta = 0.0;  // δ, pad relative to specimen at the reference points (m)
};

struct CycleResult {
  Regime regime = Regime::partial_slip;
  std::optional<Interval> stick_zone;       // never slips in the steady cycle (top = bottom); none in gross slip
  std::vector<Interval> stick_zones;        // every stick region at the top of the cycle
  std::optional<Interval> stick_zone_unloaded;  // at Q = 0 between top and bottom (and, mirrored, reloaded)
  std::vector<double> q_top, q_unloaded, q_bottom, q_reloaded;  // shear traction per cell at the four phases (Pa)
  std::vector<double> slip_range;      // peak-to-peak relative tangential displacement per cell (m)
  std::vector<double> slip_travelled;  // distance slipped per cycle per cell (m)
  // The distance a cell would slip per cycle were it touching without load (m; incremental route): slip_travelled
  // where it carries pressure, Σ |Δw| of IncrementState::dw_touching where it does not (the worn flats at zero gap
  // and zero pressure near a wear limit; wear/contact_response.hpp, CycleResponse::s_touching).
  std::vector<double> slip_if_touching;
  std::vector<double> energy_density;  // frictional energy per cycle per unit area (J/m²)
  double dissipated_energy = 0.0;      // per cycle per unit length (J/m)
  double slip_max = 0.0;               // largest slip range, at the contact's edges to sub-cell accuracy (m)
  std::vector<SolveSummary> solves;    // the corrective normal solves (incremental route: its increments)
  std::string message;                 // why a regime has no fields
  // The fretting loop (incremental route with a datum): the first loading 0 → top, and this cycle, top to top.
  std::vector<LoopPoint> first_loading, loop;
  double delta_max = 0.0;              // the largest |δ| over this cycle (m); 0 without a datum
  double Q_peak = 0.0;                 // the largest |Q| over this cycle (N/m; incremental route)
  double sliding_amplitude = 0.0;      // gross slip under displacement control: the rigid sliding beyond the stick
                                       // limit, half of what the bodies slide each half cycle (m)
};

struct TangentialSolverOptions {
  NormalSolverOptions normal;  // for the corrective normal problems
};

class TangentialSolver {
 public:
  TangentialSolver(const HalfPlaneKernel& kernel, TangentialSolverOptions options = {});

  // One steady cycle. g0: the (worn) initial gap per cell; contact: its normal solution under P with its zones.
  // Throws ConvergenceError if a corrective solve does not converge.
  CycleResult solve_cycle(std::span<const double> g0, const ContactState& contact, const std::vector<Zone>& zones,
                          const CyclicLoad& load) const;

 private:
  // The pressure and gap of the profile g0 − tilt·x at load L, warm-started from p.
  ContactState corrective(std::span<const double> g0, double tilt, double L, const ContactState& start,
                          CycleResult& result) const;
  const HalfPlaneKernel& kernel_;
  TangentialSolverOptions options_;
  NormalSolver normal_;
};

}  // namespace fretwear
