#include "engine/warnings.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "contact/closed_form.hpp"
#include "contact/window.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace {

// The contact as the advice sees it: from its first zone's left end to its last zone's right end, with the
// half-widths of those outer zones (m). A single zone's come from its closed form, or else from the load–size
// integral, where it has one: exact however coarse the grid. Otherwise they are the zones this grid locates, which a
// zone over a few cells can show wider than it is.
struct ContactSpan {
  double left = 0.0, right = 0.0;      // m
  double b_first = 0.0, b_last = 0.0;  // m
};

ContactSpan contact_span(const NormalResult& n) {
  const Zone& first = n.zones.front();
  const Zone& last = n.zones.back();
  if (n.zones.size() == 1 && (n.reference || n.load_size_half_width)) {
    const double c = n.reference ? n.reference->centre : 0.5 * (first.left.x + first.right.x);
    const double b = n.reference ? n.reference->half_width : *n.load_size_half_width;
    return {c - b, c + b, b, b};
  }
  return {first.left.x, last.right.x, 0.5 * (first.right.x - first.left.x), 0.5 * (last.right.x - last.left.x)};
}

// grid.cells rounded up to two significant digits: an advice, not a measurement.
long cells_advice(double cells) {
  const double scale = std::pow(10.0, std::max(0.0, std::floor(std::log10(cells)) - 1.0));
  return std::lround(std::ceil(cells / scale) * scale);
}

// What resolves a feature `width` m wide (a contact, stick or slip zone) with `min_cells` cells, as the advice a
// warning ends with. Cells are h = W / n over the window W, and a window must hold every zone of the contact (one
// that clips it is refused), so the least window is the contact with fretwear's margin (contact_span). A narrower
// grid.window helps only where W is at least kNarrowerWindowGain times that (a given window much wider than the
// contact); where it is not (a window fretwear chose, or zones far apart that any window must span) only more
// grid.cells help, about min_cells W / width.
// The interval [left, right] (m) in as many significant digits as tell its ends apart to three digits of its width:
// a window 0.2 mm wide at x = 50 m needs eight ([49.9999, 50.0001], not [50, 50]).
std::string interval_text(double left, double right) {
  const double scale = std::max(std::abs(left), std::abs(right)), width = right - left;
  const int digits = width > 0.0 && scale > 0.0 ? std::clamp(int(std::ceil(std::log10(scale / width))) + 3, 4, 17) : 4;
  return fmt::format("[{:.{}g}, {:.{}g}]", left, digits, right, digits);
}

std::string resolution_advice(const NormalResult& n, double width, int min_cells) {
  const ContactSpan span = contact_span(n);
  const double left = span.left - kWindowMargin * span.b_first, right = span.right + kWindowMargin * span.b_last;
  const double W = n.grid.width();
  const double cells_here = min_cells * W / width, cells_around = min_cells * (right - left) / width;
  auto cells = [](double needed) {
    return needed > kMaxCells
               ? fmt::format("about {}, more than grid.cells allows ({})", cells_advice(needed), kMaxCells)
               : fmt::format("about {}", cells_advice(needed));
  };
  // A window fretwear widened to hold the worn contact (engine/setup.cpp: its limit's reach, or gross slip's flat)
  // cannot be narrowed without stopping the run at its end.
  const std::string& method = n.window.method;
  if (method.find("+wear_") != std::string::npos || method.find("+worn_flat") != std::string::npos)
    return fmt::format("the window is fretwear's, widened to hold the worn contact ({} m), so a narrower one would "
                       "stop the wear run at its end: give more grid.cells ({})",
                       interval_text(n.grid.x_min, n.grid.x_max), cells(cells_here));
  if (W >= kNarrowerWindowGain * (right - left)) {
    const double spans = n.grid.n * width / (right - left);  // cells over the feature in that window
    if (spans >= min_cells)
      return fmt::format("give a narrower grid.window around the contact, such as {} m (over it the same "
                         "grid.cells give it about {:.0f}), or more grid.cells ({} in this window)",
                         interval_text(left, right), spans, cells(cells_here));
    return fmt::format("give a narrower grid.window around the contact, such as {} m, and more "
                       "grid.cells ({} there; {} in this window)",
                       interval_text(left, right), cells(cells_around), cells(cells_here));
  }
  if (n.zones.size() > 1)
    return fmt::format("the window must span the contact's {} zones, from x = {:.4g} to {:.4g} m, so a narrower "
                       "grid.window cannot make the cells much finer: give more grid.cells ({})",
                       n.zones.size(), span.left, span.right, cells(cells_here));
  return fmt::format("the window is already about as narrow as the contact allows: give more grid.cells ({})",
                     cells(cells_here));
}

// Zone numbers (from 1) as runs: "1–3, 5".
std::string zone_runs(const std::vector<int>& zones) {
  std::string out;
  for (std::size_t i = 0; i < zones.size();) {
    std::size_t j = i;
    while (j + 1 < zones.size() && zones[j + 1] == zones[j] + 1) ++j;
    out += (out.empty() ? "" : ", ") + (j > i ? fmt::format("{}–{}", zones[i], zones[j]) : std::to_string(zones[i]));
    i = j + 1;
  }
  return out;
}

// One warning for all the zones under kMinContactCells (a waviness may touch in dozens), its advice for the
// narrowest.
void contact_resolution(const NormalResult& n, std::vector<Warning>& out) {
  const ContactSpan span = contact_span(n);
  std::vector<int> under;
  std::size_t narrowest = 0;
  double narrowest_width = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < n.zones.size(); ++k) {
    const Zone& z = n.zones[k];
    const int cells = z.last_cell - z.first_cell + 1;
    if (cells >= kMinContactCells) continue;
    under.push_back(int(k) + 1);
    const double located = z.right.x > z.left.x ? z.right.x - z.left.x : cells * n.grid.h();
    const double width = n.zones.size() == 1 ? span.right - span.left : located;
    if (width < narrowest_width) narrowest_width = width, narrowest = k;
  }
  if (under.empty()) return;
  const Zone& z = n.zones[narrowest];
  const int cells = z.last_cell - z.first_cell + 1;
  const std::string which =
      under.size() == 1
          ? fmt::format("contact zone {} of {} spans {} cell(s) of {:.4g} m; at least {} resolve its pressure",
                        narrowest + 1, n.zones.size(), cells, n.grid.h(), kMinContactCells)
          : fmt::format("contact zones {} of {} span fewer than {} cells each (the narrowest, zone {}, {} cell(s) of "
                        "{:.4g} m); at least {} resolve a zone's pressure",
                        zone_runs(under), n.zones.size(), kMinContactCells, narrowest + 1, cells, n.grid.h(),
                        kMinContactCells);
  out.push_back({"contact_under_resolved",
                 which + fmt::format(" (p_max and the extent are grid-dependent): {}",
                                     resolution_advice(n, narrowest_width, kMinContactCells))});
}

void closed_form_missed(const NormalResult& n, std::vector<Warning>& out) {
  if (!n.reference) return;
  const Reference& ref = *n.reference;
  const double error = std::max(ref.p_max_error, ref.extent_error);
  if (error > kClosedFormTolerance)
    out.push_back({"closed_form_missed",
                   fmt::format("the contact misses its closed form ({}) by {:.3g} % (p_max {:.3g} %, extent {:.3g} % of "
                               "the half-width), more than {:.0f} %: give more grid.cells",
                               ref.kind, 100.0 * error, 100.0 * ref.p_max_error, 100.0 * ref.extent_error,
                               100.0 * kClosedFormTolerance)});
}

// contact.p_max against the same solve on half the cells, where no closed form and no singular edge says more. A
// table interpolated linearly bends the profile at each of its points, and under a point inside the contact the
// pressure peaks like ln(1/h): it grows with every refinement, by however little, so that is warned whatever the
// change.
void peak_resolution(const Scene& scene, const NormalResult& n, std::vector<Warning>& out) {
  if (!n.peak_check) return;
  const ProfileSpec& profile = scene.profile;
  int kinks = 0;
  if (profile.type == ProfileType::table && profile.interpolation == Interpolation::linear)
    for (std::size_t k = 1; k + 1 < profile.x.size(); ++k)
      for (const Zone& z : n.zones)
        kinks += profile.x[k] > z.left.x && profile.x[k] < z.right.x;
  if (kinks == 0 && !(n.peak_check->change > kPeakChangeShare)) return;
  const std::string why =
      kinks > 0 ? fmt::format("{} of the table's points lie inside the contact, where its linear interpolation bends "
                              "the profile and the pressure peaks like ln(1/h), growing with every refinement: give "
                              "profile.interpolation \"makima\" or \"pchip\"",
                              kinks)
                : "a feature of the profile there (a rounded corner, an asperity) spans too few cells: give more "
                  "grid.cells, or a narrower grid.window";
  out.push_back({"peak_unconverged",
                 fmt::format("contact.p_max is {:.4g} Pa on {} cells and {:.4g} Pa on {} ({:.1f} % apart), so it is "
                             "the grid's, not a resolved peak (at x = {:.4g} m); {}; the load and the extent converge",
                             n.p_max, n.grid.n, n.peak_check->p_max, n.peak_check->cells,
                             100.0 * n.peak_check->change, n.x_p_max, why)});
}

// A load history whose P moves within the increments (the scene's, or a block's): its dissipated energy converges
// at first order in them, and its change from half the increments is about the error left
// (CycleStage::history_energy).
void history_increments(const Scene& scene, const CycleStage& cycle, std::vector<Warning>& out) {
  for (const CycleStage::HistoryEnergy& h : cycle.history_energy) {
    const double share = std::abs(h.energy - h.energy_half) / h.energy;
    if (!(share > kHistoryEnergyShare)) continue;
    const std::string which =
        h.block < 0 ? "the load history's" : fmt::format("load.blocks[{}]'s history's", h.block);
    out.push_back({"history_increments",
                   fmt::format("{} dissipated energy, {:.4e} J/m per cycle at {} increments, is {:.4e} at {}{}: "
                               "{:.1f} % apart, and where P moves within the increments it converges at first order, "
                               "so about that much error is left{}; raise effects.tangential.increments "
                               "(docs/METHODS.md, \"Load histories\")",
                               which, h.energy, scene.tangential->increments, h.energy_half, h.half_increments,
                               h.block > 0 ? " (on the unworn contact)" : "", 100.0 * share,
                               scene.wear ? " (in the wear rate too, which the energy sets under a history)" : "")});
  }
}

// A load history marched to IncrementalSlipOptions::steady_cycles_max cycles without one ending where it began or
// repeating the one before it: the cycle reported (and worn with) may not be the steady one.
void history_unsteady(const RunResult& result, std::vector<Warning>& out) {
  const long worn = result.wear ? result.wear->unsteady_history_responses : 0;
  if (result.cycle->history_steady && worn == 0) return;
  std::string what;
  if (!result.cycle->history_steady)
    what = fmt::format("the load history's cycle neither ended where it began nor repeated the one before it "
                       "within {} cycles, so the cycle reported may not be the steady one",
                       result.cycle->history_cycles);
  if (worn > 0)
    what += fmt::format("{}{} of the wear run's cycle responses did not either, so its wear rate may be that of a "
                        "cycle still settling",
                        what.empty() ? "" : "; ", worn);
  out.push_back({"history_unsteady",
                 what + " (the traction at its end, or at the top and the bottom of the cycle, within 1e-6 of its "
                        "largest; docs/METHODS.md, \"Load histories\")"});
}

// Each contact zone's slip zones at the top of the cycle: between its ends and the stick zones inside it.
void slip_resolution(const NormalResult& n, const CycleStage& cycle, std::vector<Warning>& out) {
  const CycleResult& c = cycle.result;
  if (c.regime == Regime::gross_slip || c.stick_zones.empty()) return;
  const double h = n.grid.h();
  double narrowest = INFINITY;
  for (const Zone& z : n.zones) {
    double first = INFINITY, last = -INFINITY;
    for (const auto& s : c.stick_zones)
      if (s.second > z.left.x && s.first < z.right.x) first = std::min(first, s.first), last = std::max(last, s.second);
    if (first > last) continue;  // the whole zone slips
    // A stick zone reaching a zone's end at a corner of the pad (a complete contact whose corners stick) leaves no
    // slip zone there. At an incomplete end, where the pressure falls to zero, a slip zone lies whatever Q (Mindlin):
    // one that does not show is narrower than a cell.
    const std::pair<double, bool> ends[] = {{first - z.left.x, z.left.method == EdgeMethod::corner},
                                            {z.right.x - last, z.right.method == EdgeMethod::corner}};
    for (const auto& [width, corner] : ends)
      if (width > 0.0 || !corner) narrowest = std::min(narrowest, std::max(width, 0.0));
  }
  if (narrowest <= 0.0)
    out.push_back({"slip_zone_under_resolved",
                   fmt::format("a stick zone reaches the contact's edge: its slip zone is narrower than a cell of "
                               "{:.4g} m (Q far below f P), so the slip, the dissipated energy and the slip range "
                               "there are below what the grid resolves, and are reported as 0; more grid.cells show "
                               "them once a cell is narrower than the slip zone",
                               h)});
  else if (narrowest < kMinSlipCells * h)
    out.push_back({"slip_zone_under_resolved",
                   fmt::format("the narrowest slip zone spans {:.3g} cell(s) of {:.4g} m; at least {} resolve the slip "
                               "and the dissipated energy: {}",
                               narrowest / h, h, kMinSlipCells, resolution_advice(n, narrowest, kMinSlipCells))});
  // The stick zones (near the stick limit they shrink to a few cells, and their extent, the slip beside them and
  // the wear limit over them are then the grid's).
  double narrowest_stick = INFINITY;
  for (const auto& s : c.stick_zones) narrowest_stick = std::min(narrowest_stick, s.second - s.first);
  if (narrowest_stick < kMinStickCells * h)
    out.push_back({"stick_zone_under_resolved",
                   fmt::format("the narrowest stick zone spans {:.3g} cell(s) of {:.4g} m; at least {} resolve its "
                               "extent, the slip beside it and the wear limit over it (the load is near the stick "
                               "limit, or the contact is narrow): {}",
                               narrowest_stick / h, h, kMinStickCells,
                               resolution_advice(n, narrowest_stick, kMinStickCells))});
}

// The fretting loop's area ∮ Q dδ (loop.csv) is the dissipated energy only as far as δ, taken between reference
// points at a finite depth d, is Q's work-conjugate displacement: to O((a/d)²) (docs/SCENES.md). Measured on Hertz at
// Q/fP = 0.5 (1024 cells, 160 increments): 0.16 % apart at the default d = 10 a, 0.6 % at 5 a, 2.1 % at 2 a, 2.4 % at
// a, 26 % at a/2, all of it at 1e-9 m. The loop's polygon through its increments also cuts a gross-slip loop's corners
// (2.4 % at 40 increments, none at 160), but its points are exact and the energy does not depend on them: that is not
// warned. The two are equal only where Q does all the cycle's net work: a bulk stress that varies works on the
// specimen too (paper001_reverse_slip: the loop is 66 % off the energy), and so does a varying P between dissimilar
// bodies, whose approach depends on the shear; there is no warning then.
void loop_energy(const Scene& scene, const NormalResult& n, const CycleStage& cycle, std::vector<Warning>& out) {
  constexpr double kLoopAgreement = 1e-2, kShallow = 5.0;  // share of the energy; half-widths
  if (scene.bulk_stress != 0.0) return;
  for (const auto& point : scene.history)
    if (point[3] != scene.history.front()[3] || (!scene.similar && point[1] != scene.history.front()[1])) return;
  const std::vector<LoopPoint>& loop = cycle.result.loop;
  const double energy = cycle.result.dissipated_energy;
  if (loop.size() < 3 || !(energy > 0.0) || n.zones.empty()) return;
  const double half_width = 0.5 * (n.zones.back().right.x - n.zones.front().left.x);
  const double depth = cycle.reference_depth / half_width;
  if (!(depth < kShallow)) return;
  double area = 0.0;
  for (std::size_t i = 0; i + 1 < loop.size(); ++i)
    area += 0.5 * (loop[i].Q + loop[i + 1].Q) * (loop[i + 1].delta - loop[i].delta);
  const double apart = std::abs(std::abs(area) / energy - 1.0);
  if (!(apart > kLoopAgreement)) return;
  out.push_back({"loop_energy_apart",
                 fmt::format("the fretting loop's area (loop.csv) is {:.2g} % from the dissipated energy: its "
                             "reference points lie {:.3g} contact half-widths deep (grid.reference_depth {:.4g} m), "
                             "where δ is Q's displacement only to O((a/d)²); give 5 or more (the default is 10)",
                             100.0 * apart, depth, cycle.reference_depth)});
}

// The Mindlin stick zone of a Hertz contact under force control (c/a = √(1 − Q/fP), shifted by a bulk stress;
// PHYSICS.md, "Partial slip"), where it holds: similar bodies, one zone, in phase, partial slip, short of reverse slip.
void mindlin_missed(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const NormalResult& n = r.normal;
  if (!r.cycle || !n.reference || n.reference->kind != "hertz" || scene.control != LoadControl::force ||
      !scene.history.empty() || !scene.similar || !r.cycle->result.stick_zone ||
      r.cycle->result.regime != Regime::partial_slip)
    return;
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  const auto hz = closed_form::hertz(scene.P, pair.A(), scene.profile.R);
  const auto stick = closed_form::hertz_stick(hz, r.cycle->Q_max / (r.cycle->f * scene.P), r.cycle->f, scene.bulk_stress);
  // Nowell and Hills' shifted zone holds short of reverse slip, |e| + c ≤ a; past it the bulk stress makes the
  // leading edge slip backwards (or, resolved, leaves there a slip zone the closed form does not have).
  if (std::abs(stick.centre) + stick.c > hz.a) return;
  const auto [left, right] = *r.cycle->result.stick_zone;
  const double centre = n.reference->centre + stick.centre;
  const double error = std::max(std::abs(left - (centre - stick.c)), std::abs(right - (centre + stick.c))) / hz.a;
  if (error > kClosedFormTolerance)
    out.push_back({"closed_form_missed",
                   fmt::format("the stick zone misses its closed form (Cattaneo–Mindlin, c = {:.4g} m) by {:.3g} % of "
                               "the contact half-width, more than {:.0f} %: give more grid.cells",
                               stick.c, 100.0 * error, 100.0 * kClosedFormTolerance)});
}

// The crack's SIFs against half its quadrature points (QuadratureCheck).
void crack_quadrature(const RunResult& r, std::vector<Warning>& out) {
  if (!r.crack_quadrature) return;
  const QuadratureCheck& c = *r.crack_quadrature;
  if (!c.settled) {
    out.push_back({"crack_quadrature",
                   fmt::format("the stress intensity factors on {} points could not be checked against {}, where the "
                               "crack faces' contact does not settle: compare them with another "
                               "effects.crack.quadrature",
                               c.points, c.other)});
    return;
  }
  if (!(c.change > kCrackQuadratureShare) && !c.opens_or_closes) return;
  out.push_back({"crack_quadrature",
                 fmt::format("the stress intensity factors on {} points differ from those on {} by {:.3g} % of the "
                             "largest (at l = {:.4g} m, {}){}: near a contact's edge they converge at first to second "
                             "order in the points, so up to about that much error is left; raise "
                             "effects.crack.quadrature",
                             c.points, c.other, 100.0 * c.change, c.at_l, c.phase,
                             c.opens_or_closes ? ", and a length opens or closes between the two" : "")});
}

// A length whose faces' frictional contact settled, from another start, on a solution far from the one the passes
// came near (CrackSif::K_II_nearly), by more than kCrackQuadratureShare of the state's largest |K|. Measured on
// examples/inclined_crack.json at 22.5°, the bottom of the cycle, l = 20 µm: the passes settle directly at K_II =
// −61 and −58 kPa√m on 512 and 2048 cells; on 1024 and 4096 cells they cycle near −61 and −59, and the complementarity
// problem's solution settles at −922 and −951 kPa√m. At 45° the restarts land where the passes came (equal K_II).
void crack_branch(const RunResult& r, std::vector<Warning>& out) {
  std::vector<std::string> where;
  std::size_t n = 0;
  for (const SifSet& set : r.sifs) {
    double largest = 0.0;
    for (const CrackSif& s : set.result.sifs) {
      largest = std::max({largest, std::abs(s.K_I), std::abs(s.K_II)});
      if (std::isfinite(s.K_II_nearly)) largest = std::max(largest, std::abs(s.K_II_nearly));
    }
    for (const CrackSif& s : set.result.sifs)
      if (std::isfinite(s.K_II_nearly) && std::abs(s.K_II - s.K_II_nearly) > kCrackQuadratureShare * largest &&
          n++ < 3)
        where.push_back(fmt::format("l = {:.4g} m, {}: K_II = {:.4g} Pa√m, where the passes came near {:.4g}", s.l,
                                    set.phase, s.K_II, s.K_II_nearly));
  }
  if (where.empty()) return;
  out.push_back({"crack_contact_branch",
                 fmt::format("the crack faces' contact with friction settled far from where its passes came, at "
                             "{}{}: the passes from the open crack's overlaps cycled near one state of the faces, and "
                             "another start settled on another, which is reported. With friction, a contact solved for "
                             "one state alone (not along the load's path) can have more than one solution, so K_II "
                             "there may jump between grids and quadratures; compare other grid.cells and "
                             "effects.crack.quadrature",
                             fmt::join(where, "; "), n > where.size() ? fmt::format(" (and {} more)", n - where.size())
                                                                      : "")});
}

void crack_placement(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const Grid& g = r.normal.grid;
  const double width = g.x_max - g.x_min;
  if (r.crack_x < g.x_min || r.crack_x > g.x_max)
    out.push_back({"crack_outside_window",
                   fmt::format("the crack at x = {:.4g} m lies outside the window [{:.4g}, {:.4g}] m, where the "
                               "contact loads nothing: its SIFs are those of the bulk stress alone; place it at the "
                               "contact (\"trailing_edge\", \"leading_edge\") or widen grid.window",
                               r.crack_x, g.x_min, g.x_max)});
  const double longest = *std::max_element(scene.crack->lengths.begin(), scene.crack->lengths.end());
  if (longest > width)
    out.push_back({"crack_longer_than_window",
                   fmt::format("the longest crack, {:.4g} m, is longer than the window is wide ({:.4g} m): the contact "
                               "tractions it sees are cut off at the window's ends; give shorter lengths or a wider "
                               "grid.window",
                               longest, width)});
}

// The run approaches the asymptote from below, to the limit of its own grid: the complete contact over the cells its
// stick zones cover, `cells_worn_area` (WearAsymptote), which it reaches to the stepper's tolerance. That limit and
// the asymptote differ by the grid's share, computed there (the stick zones' ends rounded to cell boundaries, first
// order in h, of either sign); make_model() aligns the cells to the first zone's ends, which leaves at most a few
// tenths of a percent for one zone on the default grid (the located edges' own scatter). Two checks:
//   - the run passes its grid's limit by more than the stepper's tolerance: the approach itself is under-resolved;
//   - the run passes the asymptote by more than kWearAgreement: the grid's share is too large (several zones, whose
//     ends after the first stay within their cells, or a given window), and the message says how large.
void wear_overshoot(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const WearStage& w = *r.wear;
  if (!w.asymptote.unavailable.empty() || !(w.asymptote.worn_area > 0.0)) return;
  const double fraction = w.records.back().fraction;
  const double tolerance = scene.wear->tolerance;
  const double grid = w.asymptote.cells_worn_area / w.asymptote.worn_area;  // the run's limit on this grid
  if (grid > 0.0 && fraction > grid * (1.0 + tolerance))
    out.push_back({"wear_past_asymptote",
                   fmt::format("the worn area is {:.2f} % of the directly computed asymptote, past the limit its own "
                               "grid allows ({:.2f} %: the complete contact over the cells its stick zones cover) by "
                               "more than the stepper's tolerance ({:.2g}); the approach to the limit is "
                               "under-resolved: give a smaller effects.wear.tolerance or more grid.cells",
                               100.0 * fraction, 100.0 * grid, tolerance)});
  else if (fraction > 1.0 + kWearAgreement + tolerance)
    out.push_back({"wear_past_asymptote",
                   fmt::format("the worn area is {:.2f} % of the directly computed asymptote; on this grid of {:.4g} m "
                               "cells the run tends to {:.2f} % of it, because its stick zones end at cell boundaries "
                               "while the asymptote's corners are the located edges (cells are aligned to the "
                               "first zone's ends only, and only in a window fretwear chooses), more than {:.1f} % "
                               "apart: give more grid.cells",
                               100.0 * fraction, r.normal.grid.h(), 100.0 * grid, 100.0 * kWearAgreement)});
}

// The contact's peak pressure, stress and fatigue maxima at a singular edge (engine/stress_stage.hpp, SingularEdges)
// grow with the grid: the summary marks them, and the warning names them with what converges instead.
void singular_maxima(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const SingularEdges edges = singular_edges_of(r);
  if (edges.x.empty()) return;
  std::vector<std::string> names;
  if (p_max_singular(r.normal)) names.push_back("contact.p_max");
  if (!r.stress_maps.empty()) {
    nlohmann::json stress = summarise_stress(scene, r.stress_maps, r.wear ? &*r.wear : nullptr, edges);
    if (r.fatigue) add_fatigue_summary(stress, *r.fatigue, edges);
    for (const auto& [phase, values] : stress["phases"].items())
      for (const char* key : {"von_mises_max", "surface_sxx_trailing_peak"})
        if (values[std::string(key) + "_singular"].get<bool>())
          names.push_back(fmt::format("stress.phases.{}.{}", phase, key));
    if (stress.value("swt_max_singular", false)) names.push_back("stress.swt_max");
  }
  if (r.life && r.life->initiation && r.life->initiation->singular)
    names.push_back(scene.life->initiation->critical_distance > 0.0
                        ? "life.initiation.swt (line method: it grows only like ln(l/h))"
                        : "life.initiation.swt (point method: give effects.life.initiation.critical_distance)");
  if (names.empty()) return;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  out.push_back({"singular_maximum",
                 fmt::format("{} sit{} at an edge where the pressure is square-root singular (a corner of a complete "
                             "contact, or a stick zone's end at the wear limit): {} with the grid by nature; the edge "
                             "intensity that converges is contact.edge_intensity or wear.asymptote.edge_intensity",
                             list, names.size() == 1 ? "s" : "", names.size() == 1 ? "it grows" : "they grow")});
}

// The ends of the contact in every state the stress maps and the life show (the normal contact, the cycle's top and
// bottom where its pressure varies, the last wear record), singular or not, within singular_edges()'s reach.
SingularEdges contact_edges_of(const RunResult& r) {
  SingularEdges e = singular_edges_of(r);
  e.x.clear();
  const Grid& g = r.normal.grid;
  auto ends_of = [&](const std::vector<double>& p) {
    if (int(p.size()) != g.n) return;
    for (int i = 0; i <= g.n; ++i)
      if ((i > 0 && p[i - 1] > 0.0) != (i < g.n && p[i] > 0.0)) e.x.push_back(g.left(i));
  };
  ends_of(r.normal.state.p);
  if (r.cycle) ends_of(r.cycle->p_top), ends_of(r.cycle->p_bottom);
  if (r.wear && !r.wear->records.empty()) ends_of(r.wear->records.back().p);
  return e;
}

// A surface maximum at an end of the contact that is not singular: the surface stresses there have a square-root
// cusp (the pressure and the shear fall to zero as the root of the distance), so the largest of the samples (the
// map's points, or the cells' centres for the life's point method) misses the top of the cusp by an amount that falls
// only as the root of their spacing (Hertz at Q/fP = 0.6: the trailing edge's tension 16 % low at the default 161
// map points, 4 % at 2001; PHYSICS.md's σxx(−a) = 2 f p0 √(Q/fP)).
void edge_cusps(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const SingularEdges singular = singular_edges_of(r), edges = contact_edges_of(r);
  std::vector<std::string> names;
  if (!r.stress_maps.empty()) {
    nlohmann::json at_edge = summarise_stress(scene, r.stress_maps, r.wear ? &*r.wear : nullptr, edges);
    nlohmann::json at_singular = summarise_stress(scene, r.stress_maps, r.wear ? &*r.wear : nullptr, singular);
    if (r.fatigue) {
      add_fatigue_summary(at_edge, *r.fatigue, edges);
      add_fatigue_summary(at_singular, *r.fatigue, singular);
    }
    // Maxima on the surface row only: below it the map's points are a row's depth from the cusp.
    for (const auto& [phase, values] : at_edge["phases"].items())
      if (values["surface_sxx_trailing_peak_singular"].get<bool>() &&
          !at_singular["phases"][phase]["surface_sxx_trailing_peak_singular"].get<bool>())
        names.push_back(fmt::format("stress.phases.{}.surface_sxx_trailing_peak (raise effects.stress.nx)", phase));
    if (at_edge.value("swt_max_singular", false) && !at_singular.value("swt_max_singular", false) &&
        at_edge.value("swt_max_y", 1.0) == 0.0)
      names.push_back("stress.swt_max (raise effects.stress.nx)");
  }
  const auto& site = r.life ? r.life->initiation : std::nullopt;
  if (site && !site->singular && scene.life->initiation->critical_distance == 0.0 && site->y == 0.0 &&
      edges.at(site->x, 0.0))
    names.push_back("life.initiation (point method: it moves with grid.cells; the line method, "
                    "effects.life.initiation.critical_distance, converges)");
  if (names.empty()) return;
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  out.push_back({"edge_cusp",
                 fmt::format("{} sit{} at an end of the contact, where the surface stresses peak in a square-root "
                             "cusp: the largest of the points sampled misses its top by an amount that falls only as "
                             "the root of their spacing (16 % for the trailing edge's tension of Hertz at the default "
                             "161 map points)",
                             list, names.size() == 1 ? "s" : "")});
}

// A worn profile that zigzags from cell to cell: four consecutive second differences of alternating sign, each
// above kZigzagShare of the deepest wear (a step, however sharp, bends once: one change of sign; a worn zone one cell
// wide, a slip zone the grid does not resolve, bends three times, and slip_zone_under_resolved names it). Found beside the
// stick zone of contacts worn near the stick limit (dissimilar bodies at Q/fP = 0.97 to 0.99, 256 to 1024 cells):
// cells there switch between sticking and slipping from step to step, and pits a cell wide open between cells that
// do not wear. The worst record is reported: its cycles, how many places and where. Under a load history it is found
// at the edge of the contact too, and there it is the increments': as P moves, the contact's edge sweeps over several
// cells within one increment, and the energy each cell dissipates steps with it (the out-of-phase history of
// examples/hertz_history_out_of_phase.json worn at 512 cells zigzags at 40 increments a cycle, not at 80;
// docs/METHODS.md, "Load histories").
void worn_zigzag(const Scene& scene, const RunResult& r, std::vector<Warning>& out) {
  const Grid& grid = r.normal.grid;
  int worst = 0;
  double at = 0.0, left = 0.0, right = 0.0;
  for (const WearRecord& rec : r.wear->records) {
    const std::vector<double>& w = rec.w;
    if (int(w.size()) != grid.n) continue;
    const double w_max = *std::max_element(w.begin(), w.end());
    if (!(w_max > 0.0)) continue;
    const auto d2 = [&w](int i) { return w[i - 1] - 2.0 * w[i] + w[i + 1]; };
    const auto large = [&](double d) { return std::abs(d) > kZigzagShare * w_max; };
    int count = 0;
    double first = 0.0, last = 0.0;
    for (int i = 1; i + 4 < grid.n; ++i) {
      const double a = d2(i), b = d2(i + 1), c = d2(i + 2), e = d2(i + 3);
      if (!(large(a) && large(b) && large(c) && large(e) && a * b < 0.0 && b * c < 0.0 && c * e < 0.0)) continue;
      if (count++ == 0) first = grid.x(i);
      last = grid.x(i + 3);
    }
    if (count > worst) worst = count, at = rec.cycles, left = first, right = last;
  }
  if (worst == 0) return;
  const std::string where = fmt::format("the worn depth zigzags from cell to cell ({} places, between x = {:.4g} and "
                                        "{:.4g} m, at {:.4g} cycles): ",
                                        worst, left, right, at);
  const bool history =
      !scene.history.empty() ||
      std::any_of(scene.blocks.begin(), scene.blocks.end(), [](const LoadBlock& b) { return !b.history.empty(); });
  if (history)
    out.push_back({"worn_profile_zigzag",
                   where + fmt::format("under a load history the contact's edge sweeps over cells within an increment "
                                       "as P moves, and the energy each cell dissipates steps with it, so the depth "
                                       "and the pressure there are the increments', not a resolved scar; raise "
                                       "effects.tangential.increments ({} now; docs/METHODS.md, \"Load histories\"). "
                                       "Near the stick limit the cells beside the stick zone may zigzag too, which "
                                       "more increments do not remove (docs/METHODS.md, \"Known to fail\")",
                                       scene.tangential->increments)});
  else
    out.push_back({"worn_profile_zigzag",
                   where + "cells there switch between sticking and slipping from step to step and pits a cell wide "
                           "open between cells that do not wear, so the depth, the pressure and the stick zones there "
                           "are the grid's, not a resolved scar; more grid.cells do not remove it (docs/METHODS.md, "
                           "\"Known to fail\")"});
}

}  // namespace

std::vector<Warning> result_warnings(const Scene& scene, const RunResult& result) {
  std::vector<Warning> out;
  contact_resolution(result.normal, out);
  closed_form_missed(result.normal, out);
  peak_resolution(scene, result.normal, out);
  if (result.cycle) {
    slip_resolution(result.normal, *result.cycle, out);
    loop_energy(scene, result.normal, *result.cycle, out);
    history_increments(scene, *result.cycle, out);
    history_unsteady(result, out);
    mindlin_missed(scene, result, out);
  }
  if (scene.crack && !result.sifs.empty())
    crack_placement(scene, result, out), crack_quadrature(result, out), crack_branch(result, out);
  if (result.wear && !result.wear->records.empty()) {
    wear_overshoot(scene, result, out);
    worn_zigzag(scene, result, out);
  }
  singular_maxima(scene, result, out);
  edge_cusps(scene, result, out);
  return out;
}

}  // namespace fretwear
