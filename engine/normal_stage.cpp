#include "engine/normal_stage.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "contact/closed_form.hpp"
#include "contact/load_size.hpp"

namespace fretwear {
namespace {

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

NormalResult solve_normal(const Scene& scene, int cells) { return solve_normal(scene, make_model(scene, cells)); }

NormalResult solve_normal(const Scene& scene, const Model& model) {
  const ElasticPair& pair = model.pair;
  const Profile& profile = model.profile;
  NormalResult r;
  r.window = model.window;
  r.grid = model.grid;
  if (profile.symmetric_single_zone()) r.load_size_half_width = half_width_for_load(profile, pair.A(), scene.P);
  const Grid& g = r.grid;
  r.g0 = model.g0;
  const NormalSolver solver(*model.kernel);
  r.summary = solver.solve(r.g0, scene.P, r.state);
  if (r.summary.termination == Termination::no_admissible_cell)
    throw InputError(fmt::format("grid.window: [{:.6g}, {:.6g}] m holds no cell where the profile's gap is finite (the "
                                 "pad is absent there, or its gap overflows); give a window around the contact",
                                 g.x_min, g.x_max));
  r.zones = locate_zones(g, r.state.p, r.g0);
  if (r.zones.empty() && r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve carried the load on no cell of {} (residual {:.3g})",
                                       g.n, r.summary.residual));
  // A contact clipped by a given window is the scene's problem, whether or not the solve converged.
  if (!r.zones.empty()) {
    const bool at_left = r.zones.front().first_cell == 0 && r.zones.front().left.method != EdgeMethod::corner;
    const bool at_right = r.zones.back().last_cell == g.n - 1 && r.zones.back().right.method != EdgeMethod::corner;
    if (at_left || at_right)
      throw InputError(fmt::format("grid.window: the contact reaches the window's {} end (x = {:.6g} m) and would "
                                   "be clipped; widen grid.window or leave it out to have it chosen",
                                   at_left ? "left" : "right", at_left ? g.x_min : g.x_max));
  }
  if (!r.summary.converged())
    throw ConvergenceError(fmt::format("normal contact: the solve stopped ({}) with residual {:.3g} above the "
                                       "tolerance {:.3g} on {} cells",
                                       to_string(r.summary.termination), r.summary.residual,
                                       solver.options().tolerance, g.n));
  for (int i = 0; i < g.n; ++i) {
    if (r.state.p[i] > r.p_max) r.p_max = r.state.p[i], r.x_p_max = g.x(i);
    r.cells_in_contact += r.state.p[i] > 0.0;
  }
  r.reference = closed_form_reference(scene, pair, r);
  return r;
}

}  // namespace fretwear
