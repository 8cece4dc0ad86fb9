#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/load_size.hpp"
#include "engine/version.hpp"

namespace fretwear {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The closed form of an untilted cylinder, rounded punch or sharp punch, on the grid.
std::optional<Reference> closed_form_reference(const Scene& scene, const ElasticPair& pair, const NormalResult& r) {
  const ProfileSpec& s = scene.profile;
  if (s.tilt_rad != 0.0) return std::nullopt;
  Reference ref;
  ref.centre = s.offset_x;
  const Grid& g = r.grid;
  ref.p_cell.resize(g.n);
  if (s.type == ProfileType::cylinder) {
    const auto hz = closed_form::hertz(scene.P, pair.A(), s.R);
    ref.kind = "hertz";
    ref.half_width = hz.a;
    ref.p_max = hz.p0;
    for (int i = 0; i < g.n; ++i) ref.p_cell[i] = hz.cell_average(g.left(i) - ref.centre, g.left(i + 1) - ref.centre);
  } else if (s.type == ProfileType::flat_rounded) {
    const auto rp = closed_form::rounded_punch(scene.P, pair.A(), s.a, s.R);
    ref.kind = "rounded_punch";
    ref.half_width = rp.b;
    ref.p_max = rp.peak();
    // The pressure is smooth inside the contact: a 3-point Gauss rule gives the cell average well below the error.
    const double w[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0}, z[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
    for (int i = 0; i < g.n; ++i)
      for (int k = 0; k < 3; ++k) ref.p_cell[i] += w[k] * rp.pressure(g.x(i) + 0.5 * z[k] * g.h() - ref.centre);
  } else if (s.type == ProfileType::flat) {
    const auto fp = closed_form::flat_punch(scene.P, s.b);
    ref.kind = "flat_punch";
    ref.half_width = s.b;
    for (int i = 0; i < g.n; ++i) ref.p_cell[i] = fp.cell_average(g.left(i) - ref.centre, g.left(i + 1) - ref.centre);
    ref.p_max = *std::max_element(ref.p_cell.begin(), ref.p_cell.end());
  } else {
    return std::nullopt;
  }
  if (r.zones.size() != 1) return ref;
  const Zone& z = r.zones.front();
  ref.extent_error = std::max(std::abs(z.left.x - (ref.centre - ref.half_width)),
                              std::abs(z.right.x - (ref.centre + ref.half_width))) / ref.half_width;
  ref.p_max_error = std::abs(r.p_max - ref.p_max) / ref.p_max;
  double e2 = 0.0;
  int m = 0;
  for (int i = z.first_cell + 2; i <= z.last_cell - 2; ++i, ++m) e2 += std::pow(r.state.p[i] - ref.p_cell[i], 2);
  ref.rms_error = m > 0 ? std::sqrt(e2 / m) / ref.p_max : 0.0;
  return ref;
}

}  // namespace

NormalResult solve_normal(const Scene& scene, int cells) {
  if (cells <= 0) cells = scene.cells;
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  const Profile profile(scene.profile);
  NormalResult r;
  if (scene.window) {
    r.window = {scene.window->first, scene.window->second, "given", 0.0};
    r.grid = Grid{scene.window->first, scene.window->second, cells};
  } else {
    r.window = choose_window(profile, pair.A(), scene.P, cells);
    r.grid = align_to_support(profile, r.window.x_min, r.window.x_max, cells);
  }
  if (profile.symmetric_single_zone()) r.load_size_half_width = half_width_for_load(profile, pair.A(), scene.P);

  const Grid& g = r.grid;
  r.g0.resize(g.n);
  for (int i = 0; i < g.n; ++i) r.g0[i] = profile.gap(g.x(i));
  const HalfPlaneKernel kernel(g, pair.A());
  const NormalSolver solver(kernel);
  r.summary = solver.solve(r.g0, scene.P, r.state);
  if (!r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve stopped ({}) with residual {:.3g} above the "
                                       "tolerance {:.3g} on {} cells",
                                       to_string(r.summary.termination), r.summary.residual,
                                       solver.options().tolerance, g.n));

  r.zones = locate_zones(g, r.state.p, r.g0);
  for (int i = 0; i < g.n; ++i) {
    if (r.state.p[i] > r.p_max) r.p_max = r.state.p[i], r.x_p_max = g.x(i);
    r.cells_in_contact += r.state.p[i] > 0.0;
  }
  const bool at_left = r.zones.front().first_cell == 0 && r.zones.front().left.method != EdgeMethod::corner;
  const bool at_right = r.zones.back().last_cell == g.n - 1 && r.zones.back().right.method != EdgeMethod::corner;
  if (at_left || at_right)
    throw InputError(fmt::format("grid.window: the contact reaches the window's {} end (x = {:.6g} m) and would be "
                                 "clipped; widen grid.window or leave it out to have it chosen",
                                 at_left ? "left" : "right", at_left ? g.x_min : g.x_max));
  r.reference = closed_form_reference(scene, pair, r);
  return r;
}

RunResult Simulation::run() const {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult result;
  result.normal = solve_normal(scene_);
  result.timings.normal = seconds_since(t0);
  result.timings.total = seconds_since(t0);
  return result;
}

nlohmann::json make_summary(const Scene& scene, const RunResult& result) {
  using nlohmann::json;
  const NormalResult& n = result.normal;
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  json zones = json::array();
  for (const auto& z : n.zones) zones.push_back({z.left.x, z.right.x});
  const Edge& left = n.zones.front().left;
  const Edge& right = n.zones.back().right;
  double load = 0.0;
  for (double p : n.state.p) load += p * n.grid.h();

  json contact = {
      {"extent", {left.x, right.x}},
      {"zones", zones},
      {"edge_method", left.method == right.method ? to_string(left.method) : "mixed"},
      {"edge_methods", {to_string(left.method), to_string(right.method)}},
      {"p_max", n.p_max},
      {"x_p_max", n.x_p_max},
      {"cells_in_contact", n.cells_in_contact},
      {"load", load},
  };
  if (n.load_size_half_width) contact["load_size_half_width"] = *n.load_size_half_width;
  if (n.reference) {
    const Reference& ref = *n.reference;
    contact["closed_form"] = {{"kind", ref.kind},       {"half_width", ref.half_width},
                              {"p_max", ref.p_max},     {"extent_error", ref.extent_error},
                              {"p_max_error", ref.p_max_error}, {"rms_error", ref.rms_error}};
  }
  return {
      {"scene", scene.name},
      {"version", kVersion},
      {"status", "completed"},
      {"effects_run", {"normal"}},
      {"materials", {{"A", pair.A()}, {"E_star", pair.E_star()}, {"alpha", pair.alpha()}, {"beta", pair.beta()}}},
      {"grid",
       {{"cells", n.grid.n}, {"window", {n.grid.x_min, n.grid.x_max}}, {"window_method", n.window.method},
        {"h", n.grid.h()}}},
      {"contact", contact},
      {"solver",
       {{"normal",
         {{"termination", to_string(n.summary.termination)},
          {"iterations", n.summary.iterations},
          {"residual", n.summary.residual},
          {"seconds", n.summary.seconds},
          {"brief", n.summary.brief()}}}}},
      {"timings", {{"total", result.timings.total}, {"normal", result.timings.normal}}},
  };
}

}  // namespace fretwear
