// `fretwear convergence`: the scene's normal problem on grids of doubling size, against the closed form where the
// profile has one (Hertz, rounded punch, flat punch) and against the finest grid otherwise. What accuracy costs.
// When the scene names effects.tangential, the cycle is solved on every grid too and its stick zone compared with
// the closed form (Hertz with or without bulk tension; the rounded punch without it; PHYSICS.md, "Partial slip") or
// else with the finest grid.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "engine/scene.hpp"

namespace fretwear {

struct ConvergenceRow {
  int cells = 0, cells_in_contact = 0, iterations = 0;
  double x_left = 0.0, x_right = 0.0, p_max = 0.0;
  double extent_error = 0.0, p_max_error = 0.0, rms_error = 0.0;  // rms_error only against a closed form (has_rms)
  double seconds = 0.0;  // wall time of the normal solve
  // With effects.tangential: the stick zone at the top of the cycle (m) and max |edge − reference| / c_reference.
  bool has_stick = false;
  double stick_left = 0.0, stick_right = 0.0, stick_error = 0.0;
};

struct ConvergenceStudy {
  std::string against;  // "hertz", "rounded_punch", "flat_punch" or "finest grid"
  std::string stick_against;  // with effects.tangential: "hertz", "rounded_punch" or "finest grid"
  std::vector<ConvergenceRow> rows;
  // The scene's effects the study does not run ("wear", "stress", "crack", "life"): it refines the normal problem
  // and the cycle only. table() says so in a line.
  std::vector<std::string> not_studied;
  // Whether the RMS pressure error has a meaning: only against a closed form (against the finest grid there is no
  // pressure field to compare cell by cell), and table() and csv() leave the column out otherwise.
  bool has_rms() const { return against != "finest grid"; }
  // Observed order of the extent error between consecutive grids, log2(e_k / e_{k+1}).
  std::vector<double> observed_order() const;
  // The same for the stick-zone error (empty without effects.tangential).
  std::vector<double> observed_stick_order() const;
  std::string table() const;  // fixed-width text
  std::string csv() const;
};

// Why the grids from cells_from up to cells_to hold none (empty: they hold one at least). The grids are the powers
// of two n with bit_ceil(cells_from) <= n <= cells_to; the message names --from and --to, as the command line does.
std::string grid_range_problem(int cells_from, int cells_to);

// The grids are the powers of two from bit_ceil(cells_from) to cells_to; throws InputError when there is none
// (grid_range_problem()).
ConvergenceStudy run_convergence(const Scene& scene, int cells_from, int cells_to, std::ostream* progress);

}  // namespace fretwear
