#include "engine/convergence.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "common/error.hpp"
#include "contact/closed_form.hpp"
#include "engine/simulation.hpp"

namespace fretwear {

namespace {

std::vector<double> orders(const std::vector<ConvergenceRow>& rows, double ConvergenceRow::*error) {
  std::vector<double> k;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const double e0 = rows[i].*error, e1 = rows[i + 1].*error;
    k.push_back(e0 > 0.0 && e1 > 0.0 ? std::log2(e0 / e1) : std::nan(""));
  }
  return k;
}

// The closed-form stick zone [left, right] (m) of the scene, where PHYSICS.md has one.
std::optional<std::pair<double, double>> closed_form_stick(const Scene& scene, const ElasticPair& pair,
                                                           const Reference& ref, const CycleStage& cycle) {
  if (cycle.result.regime != Regime::partial_slip || !scene.friction) return std::nullopt;
  const double f = *scene.friction, ratio = cycle.Q_max / (f * scene.P);
  if (ref.kind == "hertz") {
    const auto z = closed_form::hertz_stick(closed_form::hertz(scene.P, pair.A(), scene.profile.R), ratio, f,
                                            cycle.bulk_stress);
    return std::pair{ref.centre + z.centre - z.c, ref.centre + z.centre + z.c};
  }
  if (ref.kind == "rounded_punch" && cycle.bulk_stress == 0.0) {
    const double c = closed_form::rounded_punch_stick(
        closed_form::rounded_punch(scene.P, pair.A(), scene.profile.a, scene.profile.R), ratio);
    return std::pair{ref.centre - c, ref.centre + c};
  }
  return std::nullopt;
}

}  // namespace

std::vector<double> ConvergenceStudy::observed_order() const { return orders(rows, &ConvergenceRow::extent_error); }

std::vector<double> ConvergenceStudy::observed_stick_order() const {
  if (stick_against.empty()) return {};
  return orders(rows, &ConvergenceRow::stick_error);
}

std::string ConvergenceStudy::table() const {
  const bool rms = has_rms();
  std::string s = fmt::format("errors against {}\n", against);
  s += fmt::format("{:>8} {:>8} {:>13} {:>13} {:>12} {:>10} {:>10}", "cells", "contact", "x_left (m)", "x_right (m)",
                   "p_max (Pa)", "extent", "p_max");
  s += rms ? fmt::format(" {:>10}", "rms p") : "";
  s += fmt::format(" {:>6} {:>10}\n", "iter", "time (ms)");
  for (const auto& r : rows) {
    s += fmt::format("{:>8} {:>8} {:>13.6e} {:>13.6e} {:>12.6e} {:>10.2e} {:>10.2e}", r.cells, r.cells_in_contact,
                     r.x_left, r.x_right, r.p_max, r.extent_error, r.p_max_error);
    s += rms ? fmt::format(" {:>10.2e}", r.rms_error) : "";
    s += fmt::format(" {:>6} {:>10.3f}\n", r.iterations, 1e3 * r.seconds);
  }
  if (!not_studied.empty()) {
    std::string names;
    for (const auto& e : not_studied) names += (names.empty() ? "" : ", ") + e;
    s += fmt::format("not part of the study: {} (convergence refines the normal problem and the load cycle; `fretwear "
                     "run` computes the rest)\n",
                     names);
  }
  if (stick_against.empty()) return s;
  s += fmt::format("stick zone at the top of the cycle, errors against {}\n", stick_against);
  s += fmt::format("{:>8} {:>13} {:>13} {:>10} {:>6}\n", "cells", "c_left (m)", "c_right (m)", "stick", "order");
  const std::vector<double> k = observed_stick_order();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    const std::string order = i > 0 && std::isfinite(k[i - 1]) ? fmt::format("{:.2f}", k[i - 1]) : "";
    s += fmt::format("{:>8} {:>13.6e} {:>13.6e} {:>10.2e} {:>6}\n", r.cells, r.stick_left, r.stick_right,
                     r.stick_error, order);
  }
  return s;
}

std::string ConvergenceStudy::csv() const {
  const bool stick = !stick_against.empty();
  const bool rms = has_rms();
  std::string s = "cells,cells_in_contact,x_left_m,x_right_m,p_max_Pa,extent_error,p_max_error,";
  s += rms ? "rms_error,iterations,seconds" : "iterations,seconds";
  s += stick ? ",stick_left_m,stick_right_m,stick_error\n" : "\n";
  for (const auto& r : rows) {
    s += fmt::format("{},{},{:.12g},{:.12g},{:.12g},{:.6g},{:.6g},", r.cells, r.cells_in_contact, r.x_left,
                     r.x_right, r.p_max, r.extent_error, r.p_max_error);
    s += rms ? fmt::format("{:.6g},", r.rms_error) : "";
    s += fmt::format("{},{:.6g}", r.iterations, r.seconds);
    s += stick ? fmt::format(",{:.12g},{:.12g},{:.6g}\n", r.stick_left, r.stick_right, r.stick_error) : "\n";
  }
  return s;
}

std::string grid_range_problem(int cells_from, int cells_to) {
  if (cells_from > cells_to)
    return fmt::format("--from {} is above --to {}; give --from at most --to (the coarsest grid, then the finest)",
                       cells_from, cells_to);
  if (const unsigned first = std::bit_ceil(unsigned(cells_from)); first > unsigned(cells_to))
    return fmt::format("--from {} rounds up to {} cells (the grids are powers of two), above --to {}; give --to at "
                       "least {}",
                       cells_from, first, cells_to, first);
  return "";
}

ConvergenceStudy run_convergence(const Scene& scene, int cells_from, int cells_to, std::ostream* progress) {
  if (const std::string problem = grid_range_problem(cells_from, cells_to); !problem.empty())
    throw InputError(problem);
  ConvergenceStudy study;
  if (scene.wear) study.not_studied.push_back("wear");
  if (scene.stress) study.not_studied.push_back("stress");
  if (scene.crack) study.not_studied.push_back("crack");
  if (scene.life) study.not_studied.push_back("life");
  std::vector<NormalResult> results;
  for (int n = int(std::bit_ceil(unsigned(cells_from))); n <= cells_to; n *= 2) {
    const Model model = make_model(scene, n);
    NormalResult r = solve_normal(scene, model);
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
    if (scene.tangential) {
      const CycleStage cycle = solve_cycle(scene, model, r);
      if (cycle.result.stick_zone) {
        row.has_stick = true;
        row.stick_left = cycle.result.stick_zone->first;
        row.stick_right = cycle.result.stick_zone->second;
        const auto want = r.reference ? closed_form_stick(scene, model.pair, *r.reference, cycle) : std::nullopt;
        if (want) {
          study.stick_against = r.reference->kind;
          row.stick_error = std::max(std::abs(row.stick_left - want->first), std::abs(row.stick_right - want->second)) /
                            (0.5 * (want->second - want->first));
        }
      }
    }
    if (progress) *progress << fmt::format("  {} cells: {}\n", n, r.summary.brief()) << std::flush;
    study.rows.push_back(row);
  }
  const bool all_stick = !study.rows.empty() && std::all_of(study.rows.begin(), study.rows.end(),
                                                            [](const ConvergenceRow& r) { return r.has_stick; });
  if (scene.tangential && !all_stick)
    throw UnsupportedError("convergence: the cycle has no stick zone on every grid (gross slip?): no stick-zone "
                           "error to report");
  if (all_stick && study.stick_against.empty()) {
    study.stick_against = "finest grid";
    const ConvergenceRow& f = study.rows.back();
    const double c = 0.5 * (f.stick_right - f.stick_left);
    for (auto& r : study.rows)
      r.stick_error = std::max(std::abs(r.stick_left - f.stick_left), std::abs(r.stick_right - f.stick_right)) / c;
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
