#include <bit>
#include "engine/convergence.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/simulation.hpp"

namespace fretwear {

std::vector<double> ConvergenceStudy::observed_order() const {
  std::vector<double> k;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const double e0 = rows[i].extent_error, e1 = rows[i + 1].extent_error;
    k.push_back(e0 > 0.0 && e1 > 0.0 ? std::log2(e0 / e1) : std::nan(""));
  }
  return k;
}

std::string ConvergenceStudy::table() const {
  std::string s = fmt::format("errors against {}\n", against);
  s += fmt::format("{:>8} {:>8} {:>13} {:>13} {:>12} {:>10} {:>10} {:>10} {:>6} {:>10}\n", "cells", "contact",
                   "x_left (m)", "x_right (m)", "p_max (Pa)", "extent", "p_max", "rms p", "iter", "time (ms)");
  for (const auto& r : rows)
    s += fmt::format("{:>8} {:>8} {:>13.6e} {:>13.6e} {:>12.6e} {:>10.2e} {:>10.2e} {:>10.2e} {:>6} {:>10.3f}\n",
                     r.cells, r.cells_in_contact, r.x_left, r.x_right, r.p_max, r.extent_error, r.p_max_error,
                     r.rms_error, r.iterations, 1e3 * r.seconds);
  return s;
}

std::string ConvergenceStudy::csv() const {
  std::string s = "cells,cells_in_contact,x_left_m,x_right_m,p_max_Pa,extent_error,p_max_error,rms_error,"
                  "iterations,seconds\n";
  for (const auto& r : rows)
    s += fmt::format("{},{},{:.12g},{:.12g},{:.12g},{:.6g},{:.6g},{:.6g},{},{:.6g}\n", r.cells, r.cells_in_contact,
                     r.x_left, r.x_right, r.p_max, r.extent_error, r.p_max_error, r.rms_error, r.iterations,
                     r.seconds);
  return s;
}

ConvergenceStudy run_convergence(const Scene& scene, int cells_from, int cells_to, std::ostream* progress) {
  ConvergenceStudy study;
  std::vector<NormalResult> results;
  for (int n = int(std::bit_ceil(unsigned(cells_from))); n <= cells_to; n *= 2) {
    NormalResult r = solve_normal(scene, n);
    ConvergenceRow row;
    row.cells = n;
    row.cells_in_contact = r.cells_in_contact;
    row.iterations = r.summary.iterations;
    row.x_left = r.zones.front().left.x;
    row.x_right = r.zones.back().right.x;
    row.p_max = r.p_max;
    row.seconds = r.summary.seconds;
    if (r.reference) {
      study.against = r.reference->kind;
      row.extent_error = r.reference->extent_error;
      row.p_max_error = r.reference->p_max_error;
      row.rms_error = r.reference->rms_error;
    }
    if (progress) *progress << fmt::format("  {} cells: {}\n", n, r.summary.brief()) << std::flush;
    study.rows.push_back(row);
  }
  if (study.against.empty() && !study.rows.empty()) {
    study.against = "finest grid";
    const ConvergenceRow& f = study.rows.back();
    const double w = 0.5 * (f.x_right - f.x_left);
    for (auto& r : study.rows) {
      r.extent_error = std::max(std::abs(r.x_left - f.x_left), std::abs(r.x_right - f.x_right)) / w;
      r.p_max_error = std::abs(r.p_max - f.p_max) / f.p_max;
    }
  }
  return study;
}

}  // namespace fretwear
