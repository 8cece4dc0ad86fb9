#include "engine/wear_stage.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>

#include <fmt/format.h>

#include "common/error.hpp"
#include "contact/displacement_limit.hpp"
#include "contact/reference_datum.hpp"
#include "engine/body_frames.hpp"
#include "engine/checkpoint.hpp"
#include "engine/plot.hpp"
#include "engine/simulation.hpp"
#include "engine/wear_contacts.hpp"
#include "engine/wear_driver.hpp"
#include "wear/implicit_stepper.hpp"
#include "wear/reference_steppers.hpp"
#include "wear/wear_law.hpp"

namespace fretwear {
namespace {

std::string num(double v) { return csv_number(v); }

// One row per wear record (SI); the stick-zone ends are empty when the contact slips everywhere, the fraction when
// there is no asymptote (gross slip, a history, blocks, ...).
// Under load.blocks a last column, block, names the block (from 0) whose load the record is under.
std::string wear_history_csv(const WearStage& w) {
  const bool blocks = !w.records.empty() && w.records.front().block >= 0;
  std::string s = "cycles,worn_area_m2,max_depth_m,fraction_of_asymptote,stick_left_m,stick_right_m,contact_left_m,"
                  "contact_right_m,p_max_Pa";
  s += blocks ? ",block\n" : "\n";
  const bool asymptote = w.asymptote.unavailable.empty();
  for (const WearRecord& r : w.records) {
    s += fmt::format("{},{},{},{},{},{},{},{},{}", num(r.cycles), num(r.worn_area), num(r.max_depth),
                     asymptote ? num(r.fraction) : "", r.stick_zone ? num(r.stick_zone->first) : "",
                     r.stick_zone ? num(r.stick_zone->second) : "", num(r.contact.first), num(r.contact.second),
                     num(r.p_max));
    s += blocks ? fmt::format(",{}\n", r.block) : "\n";
  }
  return s;
}

// The most stick zones any record has.
std::size_t most_stick_zones(const WearStage& w) {
  std::size_t most = 0;
  for (const WearRecord& r : w.records) most = std::max(most, r.stick_zones.size());
  return most;
}

// Several stick zones: one row per zone and record, zone by zone (numbered from 0, left to right in each record),
// so that each zone's rows follow one another.
std::string wear_stick_zones_csv(const WearStage& w) {
  std::string s = "cycles,zone,stick_left_m,stick_right_m\n";
  for (std::size_t k = 0; k < most_stick_zones(w); ++k)
    for (const WearRecord& r : w.records)
      if (k < r.stick_zones.size())
        s += fmt::format("{},{},{},{}\n", num(r.cycles), k, num(r.stick_zones[k].first), num(r.stick_zones[k].second));
  return s;
}

// Long format: one row per record and cell, then the asymptote as rows with cycles = inf (its slip is left empty:
// the asymptote is a limit, not a cycle). Rows of record k are rows k·n ... k·n + n − 1 after the header.
std::string profiles_csv(const Scene& scene, const NormalResult& n, const WearStage& w) {
  const double pad = scene.wear->pad_fraction;
  std::string s = "cycles,x_m,gap0_m,wear_m,wear_pad_m,wear_specimen_m,p_Pa,slip_per_cycle_m\n";
  s.reserve(s.size() + (w.records.size() + 1) * std::size_t(n.grid.n) * 110);
  for (const WearRecord& r : w.records) {
    const std::string c = num(r.cycles);
    const bool frames = !r.w_pad.empty();
    for (int i = 0; i < n.grid.n; ++i)
      s += fmt::format("{},{},{},{},{},{},{},{}\n", c, num(n.grid.x(i)), num(n.g0[i]), num(r.w[i]),
                       num(frames ? r.w_pad[i] : pad * r.w[i]), num(frames ? r.w_specimen[i] : (1.0 - pad) * r.w[i]),
                       num(r.p[i]), num(r.s[i]));
  }
  const WearAsymptote& a = w.asymptote;
  if (a.w.size() != std::size_t(n.grid.n) || a.p.size() != std::size_t(n.grid.n)) return s;
  for (int i = 0; i < n.grid.n; ++i)
    s += fmt::format("inf,{},{},{},{},{},{},\n", num(n.grid.x(i)), num(n.g0[i]), num(a.w[i]), num(pad * a.w[i]),
                     num((1.0 - pad) * a.w[i]), num(a.p[i]));
  return s;
}

// The records the evolution plots show: the initial state and at most 7 more, spread evenly in log cycles, always
// with the last.
std::vector<std::size_t> plotted_records(const WearStage& w) {
  constexpr std::size_t kMore = 7;
  std::vector<std::size_t> out, worn;
  for (std::size_t k = 0; k < w.records.size(); ++k) (w.records[k].cycles > 0.0 ? worn : out).push_back(k);
  if (worn.size() <= kMore) {
    for (std::size_t k : worn) out.push_back(k);
    return out;
  }
  // Each target in turn takes the nearest record not yet taken; targets and records both increase, so the picks do.
  const double lo = std::log(w.records[worn.front()].cycles), hi = std::log(w.records[worn.back()].cycles);
  std::size_t next = 0;  // the first record in `worn` still free
  for (std::size_t j = 0; j < kMore; ++j) {
    const double target = lo + (hi - lo) * double(j) / double(kMore - 1);
    const std::size_t last_free = worn.size() - (kMore - j);  // leave one record for each later target
    std::size_t best = next;
    for (std::size_t i = next; i <= last_free; ++i)
      if (std::abs(std::log(w.records[worn[i]].cycles) - target) <
          std::abs(std::log(w.records[worn[best]].cycles) - target))
        best = i;
    out.push_back(worn[best]);
    next = best + 1;
  }
  return out;
}

// wear.gp: the worn profile and the pressure as they evolve (with the asymptote dashed), the stick zone and the
// worn area against cycles.
std::string wear_plot_script(const Scene& scene, const NormalResult& n, const CycleStage& cycle, const WearStage& w) {
  const int cells = n.grid.n;
  const std::vector<std::size_t> shown = plotted_records(w);
  const WearAsymptote& a = w.asymptote;
  const WearRecord& last = w.records.back();
  // The x range: the region that wears (the asymptote's extent, or the last contact) with a quarter margin.
  double l = std::min(a.extent.first, last.contact.first), r = std::max(a.extent.second, last.contact.second);
  for (const auto& z : n.zones) l = std::min(l, z.left.x), r = std::max(r, z.right.x);
  const double m = 0.25 * (r - l);
  l = std::max(n.grid.x_min, l - m), r = std::min(n.grid.x_max, r + m);

  std::string s = fmt::format(R"(# The wear run. Re-run with: gnuplot wear.gp
# profiles.csv holds {0} rows per record (record k: data rows k*{0} ... k*{0}+{1}, counted from 0 after the header);
# the asymptote (cycles = inf) comes last.
set datafile separator ','
set grid
)", cells, cells - 1);
  const auto series = [&](const std::string& column, const std::string& asymptote_title) {
    std::string plot = "plot ";
    for (std::size_t j = 0; j < shown.size(); ++j) {
      const std::size_t k = shown[j];
      const double t = shown.size() > 1 ? double(j) / double(shown.size() - 1) : 1.0;
      plot += fmt::format("'profiles.csv' skip 1 every ::{}::{} using ($2*1e3):({}) with lines lw 1.5 "
                          "lc rgb '{}' title '{}', ",
                          k * cells, k * cells + cells - 1, column, ramp(t),
                          cycles_label(w.records[k].cycles));
    }
    const std::size_t k = w.records.size();
    if (a.w.size() != std::size_t(cells)) return plot.substr(0, plot.size() - 2) + "\n";  // no asymptote rows
    plot += fmt::format("'profiles.csv' skip 1 every ::{}::{} using ($2*1e3):({}) with lines lw 2 dt 2 "
                        "lc rgb '#000000' title '{}'\n",
                        k * cells, k * cells + cells - 1, column, asymptote_title);
    return plot;
  };
  const std::string law = scene.wear->law == wear::Law::archard ? "Archard k" : "energy α";
  s += fmt::format("set xrange [{}:{}]\nset xlabel 'x (mm)'\nset key outside right top\n", l * 1e3, r * 1e3);
  s += fmt::format("set title \"{}: wear depth, both bodies ({} = {:.3g} 1/Pa; pad share {:.3g})\" noenhanced\n",
                   scene.name, law, scene.wear->coefficient, scene.wear->pad_fraction);
  s += "set ylabel 'wear depth w (µm)'\nset yrange [0:*]\n";
  s += svg_and_png("wear_depth", series("$4*1e6", "asymptote"));
  if (a.unavailable.empty())
    s += fmt::format("set title \"{}: contact pressure as the slip zones wear (the asymptote's is singular at the "
                     "stick-zone ends)\" noenhanced\n", scene.name);
  else  // no asymptote; in gross slip no stick zone, and the whole contact wears
    s += fmt::format("set title \"{}: contact pressure as the contact wears ({})\" noenhanced\n", scene.name,
                     w.records.front().stick_zone ? "no asymptote: see wear.asymptote_note"
                                                  : "gross slip: no stick zone, no asymptote");
  s += "set ylabel 'pressure p (MPa)'\n";
  s += svg_and_png("wear_pressure", series("$7*1e-6", "asymptote"));
  if (!last.w_pad.empty()) {  // gross slip, each body in its own frame: the two scars of the same records
    std::string plot = "plot ";
    for (std::size_t j = 0; j < shown.size(); ++j) {
      const std::size_t k = shown[j];
      const double t = shown.size() > 1 ? double(j) / double(shown.size() - 1) : 1.0;
      for (int body = 0; body < 2; ++body)
        plot += fmt::format("'profiles.csv' skip 1 every ::{}::{} using ($2*1e3):(${}*1e6) with lines lw 1.5 dt {} "
                            "lc rgb '{}' title '{}, {}', ",
                            k * cells, k * cells + cells - 1, body == 0 ? 5 : 6, body == 0 ? 1 : 2, ramp(t),
                            body == 0 ? "pad" : "specimen", cycles_label(w.records[k].cycles));
    }
    // The x range: the specimen's scar, which spreads over the stroke, with a tenth of its width each side.
    double lo = r, hi = l;
    for (int i = 0; i < cells; ++i)
      if (last.w_pad[std::size_t(i)] > 0.0 || last.w_specimen[std::size_t(i)] > 0.0)
        lo = std::min(lo, n.grid.x(i)), hi = std::max(hi, n.grid.x(i));
    const double margin = 0.1 * (hi - lo);
    s += fmt::format("set xrange [{}:{}]\n", std::max(n.grid.x_min, lo - margin) * 1e3,
                     std::min(n.grid.x_max, hi + margin) * 1e3);
    s += fmt::format("set title \"{}: each body's scar in its own frame (pad solid, specimen dashed)\" noenhanced\n",
                     scene.name);
    s += "set ylabel 'wear depth (µm)'\nset yrange [0:*]\n";
    s += svg_and_png("wear_bodies", plot.substr(0, plot.size() - 2) + "\n");
    s += fmt::format("set xrange [{}:{}]\n", l * 1e3, r * 1e3);
  }

  // Against cycles: log axis; the unworn record (cycles = 0) cannot be shown there, and a run stopped before its
  // first record after it has nothing to show.
  if (!(last.cycles > 0.0)) return s;
  double n_lo = last.cycles;
  for (const WearRecord& rec : w.records)
    if (rec.cycles > 0.0) n_lo = std::min(n_lo, rec.cycles);
  s += "\nunset xrange\nunset yrange\nset logscale x\nset format x '10^{%L}'\nset xlabel 'cycles N'\n";
  s += "set key inside right center opaque box\n";
  if (n_lo < last.cycles)
    s += fmt::format("set xrange [{}:{}]\n", std::pow(10.0, std::floor(std::log10(n_lo))),
                     std::pow(10.0, std::ceil(std::log10(last.cycles))));
  const auto& s0 = w.records.front().stick_zone;
  std::string stick;
  if (s0) {
    // Both ends and the contact's ends on one scale: the stick zone standing still inside a growing contact.
    double lo = s0->first, hi = s0->second;
    for (const WearRecord& rec : w.records) {
      lo = std::min(lo, rec.contact.first), hi = std::max(hi, rec.contact.second);
      if (rec.stick_zone) lo = std::min(lo, rec.stick_zone->first), hi = std::max(hi, rec.stick_zone->second);
    }
    if (w.asymptote.unavailable.empty())
      lo = std::min(lo, w.asymptote.extent.first), hi = std::max(hi, w.asymptote.extent.second);
    const double pad = 0.08 * (hi - lo);
    s += fmt::format("set yrange [{}:{}]\n", (lo - pad) * 1e3, (hi + pad) * 1e3);
    s += fmt::format("set title \"{}: stick zone{} and contact extent against cycles\" noenhanced\n", scene.name,
                     most_stick_zones(w) > 1 ? "s" : "");
    s += "set ylabel 'x (mm)'\n";
    const std::size_t zones = most_stick_zones(w);
    if (zones <= 1) {
      stick = fmt::format(
          "plot {0} with lines lw 9 lc rgb '#d9d9d9' title 'initial stick zone', "
          "{1} with lines lw 9 lc rgb '#d9d9d9' notitle, "
          "'wear_history.csv' skip 1 using ($1 > 0 ? $1 : NaN):($5*1e3) with linespoints pt 7 ps 0.7 lw 1.5 "
          "lc rgb '#1f77b4' title 'stick zone, left end', "
          "'' skip 1 using ($1 > 0 ? $1 : NaN):($6*1e3) with linespoints pt 5 ps 0.7 lw 1.5 lc rgb '#d62728' "
          "title 'stick zone, right end', ",
          num(s0->first * 1e3), num(s0->second * 1e3));
    } else {
      // Each zone's ends (wear_stick_zones.csv, zone by zone), the initial zones as grey bands.
      stick = "plot ";
      const auto& first = w.records.front().stick_zones;
      for (std::size_t k = 0; k < first.size(); ++k)
        stick += fmt::format("{0} with lines lw 9 lc rgb '#d9d9d9' {2}, {1} with lines lw 9 lc rgb '#d9d9d9' notitle, ",
                             num(first[k].first * 1e3), num(first[k].second * 1e3),
                             k == 0 ? "title 'initial stick zones'" : "notitle");
      for (std::size_t k = 0; k < zones; ++k)
        stick += fmt::format(
            "'wear_stick_zones.csv' skip 1 using ($2 == {0} && $1 > 0 ? $1 : NaN):($3*1e3) with linespoints pt 7 "
            "ps 0.7 lw 1.5 lc rgb '#1f77b4' {1}, '' skip 1 using ($2 == {0} && $1 > 0 ? $1 : NaN):($4*1e3) with "
            "linespoints pt 5 ps 0.7 lw 1.5 lc rgb '#d62728' {2}, ",
            k, k == 0 ? "title 'stick zones, left ends'" : "notitle",
            k == 0 ? "title 'stick zones, right ends'" : "notitle");
    }
    stick +=
        "'wear_history.csv' skip 1 using ($1 > 0 ? $1 : NaN):($7*1e3) with linespoints pt 6 ps 0.7 lw 1 "
        "lc rgb '#6baed6' title 'contact, left end', "
        "'' skip 1 using ($1 > 0 ? $1 : NaN):($8*1e3) with linespoints pt 4 ps 0.7 lw 1 lc rgb '#fc9272' "
        "title 'contact, right end'";
    // The worn extent of the asymptote, where the contact tends (its worn zones touch at zero pressure there, so
    // near the limit the contact's ends move by a few cells from record to record).
    if (w.asymptote.unavailable.empty())
      stick += fmt::format(", {0} with lines dt 2 lw 1 lc rgb '#555555' title 'worn extent of the asymptote', {1} with "
                           "lines dt 2 lw 1 lc rgb '#555555' notitle",
                           num(w.asymptote.extent.first * 1e3), num(w.asymptote.extent.second * 1e3));
    // Where it exists, the closed form of the unworn stick zone (Cattaneo–Mindlin; the first record's should sit on
    // it to a cell).
    if (const auto cm = mindlin_stick_zone(scene, n, cycle))
      stick += fmt::format(", {0} with lines dt 4 lw 2 lc rgb '#2ca02c' title 'Cattaneo–Mindlin, unworn', {1} with "
                           "lines dt 4 lw 2 lc rgb '#2ca02c' notitle",
                           num((cm->centre - cm->c) * 1e3), num((cm->centre + cm->c) * 1e3));
    s += svg_and_png("wear_stick_zone", stick + "\n");
  }
  const double area_top = 1.12 * std::max(a.worn_area, [&] {
    double v = 0.0;
    for (const WearRecord& rec : w.records) v = std::max(v, rec.worn_area);
    return v;
  }());
  s += fmt::format("set title \"{}: worn area against cycles\" noenhanced\n", scene.name);
  // Log–log: the early growth (∝ N, at the unworn rate) and the approach to the limit, the curve flattening onto the
  // asymptote, both in view (a linear cycle axis squeezes the growth into its first per cent).
  double area_lo = area_top;
  for (const WearRecord& rec : w.records)
    if (rec.cycles > 0.0 && rec.worn_area > 0.0) area_lo = std::min(area_lo, 0.5 * rec.worn_area);
  s += "set key inside right bottom opaque box\nset ylabel 'worn area ∫ w dx (µm²)'\n";
  if (area_top > 0.0 && area_lo < area_top) {  // nothing worn yet: no log axis to draw it on
    s += "set logscale y\nset format y '%h'\n";
    s += fmt::format("set yrange [{}:{}]\n", area_lo * 1e12, area_top * 1e12);
    if (a.worn_area > 0.0)
      s += fmt::format("set logscale y2\nset y2range [{}:{}]\nset y2label 'fraction of the asymptote'\n"
                       "set ytics nomirror\nset y2tics\n", area_lo / a.worn_area, area_top / a.worn_area);
  }
  // Without an asymptote (gross slip, a history, ...) the dashed line is the initial rate c ∫ p s dx carried on: the
  // worn area of uniform wear at the rate of the unworn contact (Archard, for sliding: k P s N).
  double rate0 = 0.0;
  for (std::size_t i = 0; i < w.records.front().p.size(); ++i)
    rate0 += w.rate_coefficient * w.records.front().p[i] * w.records.front().s[i] * n.grid.h();
  const std::string reference = a.unavailable.empty()
                                    ? fmt::format("{} with lines lw 2 dt 2 lc rgb '#000000' title 'asymptote'",
                                                  num(a.worn_area * 1e12))
                                    : fmt::format("{}*x with lines lw 2 dt 2 lc rgb '#000000' title 'initial rate "
                                                  "c ∫ p s dx, times N'",
                                                  num(rate0 * 1e12));
  // Under displacement control the run settles below the asymptote (its stick zone grows over worn points): the
  // limit of the zone it ends with is drawn too.
  const std::string settled =
      w.settled ? fmt::format("{} with lines lw 2 dt 3 lc rgb '#d62728' title 'limit of the final stick zone', ",
                              num(w.settled->worn_area * 1e12))
                : std::string();
  s += svg_and_png("wear_area",
                   fmt::format("plot {} , {}"
                               "'wear_history.csv' skip 1 using ($1 > 0 ? $1 : NaN):($2*1e12) with linespoints pt 7 "
                               "ps 0.7 lw 1.5 lc rgb '#1f77b4' title 'fretwear'\n",
                               reference, settled));
  return s;
}

// Under displacement control below the stick limit (contact/displacement_limit.hpp): the first cycle's Q0 and stick
// zones by the analogy, and Q at the limit over them, δ/C(Z0); or why not (gross slip, a bulk stress).
void displacement_stick_zones(const Scene& scene, const Model& model, InitialStick& st) {
  if (scene.bulk_stress != 0.0) {
    st.unavailable = "under displacement control with a bulk stress the stick zone shifts with the bulk strain, which "
                     "also enters the displacement of the reference points, and the limit (a complete contact over a "
                     "stick zone, fully stuck under the Q the displacement gives) is not established: not computed";
    return;
  }
  const NormalResult normal = solve_normal(scene, model);
  const auto [x_c, d] = reference_point(scene, normal);
  const ReferenceDatum datum(model.grid, model.pair, x_c, d);
  const AnalogyDisplacement analogy(model.grid, *model.kernel, model.g0, scene.P, *scene.friction, datum);
  const double delta = *scene.delta;
  if (!(delta < analogy.stick_limit())) {
    st.unavailable = fmt::format("under displacement control the first cycle slides (gross slip: load.delta = {:.6g} m "
                                 "is past the stick limit {:.6g} m): there is no stick zone, and the wear never stops",
                                 delta, analogy.stick_limit());
    return;
  }
  const DisplacementLimit lim =
      displacement_limit(analogy, model.grid, model.pair, x_c, d, delta, analogy.at_displacement(delta).Q);
  st.zones = lim.stick_zones;
  st.displacement = lim;
}

}  // namespace

InitialStick initial_stick_zones(const Scene& scene, const Model& model) {
  InitialStick st;
  if (!scene.blocks.empty()) {
    st.unavailable = "under load.blocks the load changes from block to block, and paper 002's asymptote (complete "
                     "contact over the initial stick zone of one fixed Q) does not apply: not computed";
    return st;
  }
  if (!scene.history.empty()) {
    st.unavailable = "under load.history P and Q move through the cycle, and paper 002's asymptote (complete contact "
                     "over the initial stick zone of a constant P and a fixed Q) does not apply: not computed";
    return st;
  }
  if (std::abs(model.pair.beta()) > 1e-12) {
    st.unavailable = fmt::format("dissimilar bodies (Dundurs beta = {:.4g}): the shear moves the pressure through "
                                 "the cycle, and paper 002's asymptote (similar bodies) is not established: not "
                                 "computed",
                                 model.pair.beta());
    return st;
  }
  if (scene.control == LoadControl::displacement) {
    displacement_stick_zones(scene, model, st);
    return st;
  }
  AnalogyContactResponse contact(scene, model, cyclic_load(scene, model.pair));
  wear::CycleResponse first;
  try {
    contact.respond(std::vector<double>(std::size_t(model.grid.n), 0.0), first);
  } catch (const UnsupportedError&) {  // reverse slip: the incremental route wears it, with no asymptote here
    st.unavailable = "the first cycle slips backwards at the leading edge (reverse slip), where paper 002's limit, a "
                     "complete contact over a stick zone that stays where it started, is not established: not "
                     "computed";
    return st;
  }
  st.zones = contact.stick_zones();
  return st;
}

WearAsymptote wear_asymptote(const Scene& scene, const Model& model, const NormalResult& /*normal*/) {
  WearAsymptote a;
  InitialStick st = initial_stick_zones(scene, model);
  if (!st.unavailable.empty()) {
    a.unavailable = std::move(st.unavailable);
    return a;
  }
  static_cast<WearLimit&>(a) = wear_limit(model.profile, model.pair.A(), model.grid, scene.P, st.zones);
  // The run's own limit: the same zones ending at the boundaries of the cells the corrective contact loads.
  std::vector<Zone> cells = st.zones;
  for (Zone& z : cells) z.left.x = model.grid.left(z.first_cell), z.right.x = model.grid.left(z.last_cell + 1);
  if (!cells.empty())
    a.cells_worn_area = wear_limit(model.profile, model.pair.A(), model.grid, scene.P, cells).worn_area;
  if (st.displacement) {
    const DisplacementLimit& d = *st.displacement;
    a.Q_max = d.Q;
    a.stuck_compliance = d.compliance;
    const std::string zones = d.stick_zones.size() > 1 ? "zones" : "zone";
    if (!d.shrinks)
      a.note = fmt::format(
          "displacement control below the stick limit: the first cycle (the analogy's steady cycle whose reference "
          "points reach load.delta) has Q0 = {0:.6g} N/m, and its stick {1} never slip{2}. At the limit the slip zones "
          "carry no pressure, and the contact is a complete contact over the stick {1}, fully stuck, of stuck "
          "compliance C = {3:.6g} m²/N by the datum, above the first cycle's delta/Q0 = {4:.6g} m²/N: Q falls as the "
          "slip zones wear, to delta/C = {5:.6g} N/m (asymptote.Q_max), and the asymptote is the complete contact "
          "over the first cycle's stick {1} on the original profile under P (paper 002's limit at Q0). As Q falls "
          "the stick {1} can grow over points beside {6} that slipped, and wore, before {7} reached them; the run then "
          "settles on a slightly wider {1}, worn a little inside, and below this worn area (docs/METHODS.md, \"Wear "
          "under displacement control\")",
          d.Q_initial, zones, d.stick_zones.size() > 1 ? "" : "s", d.compliance, d.initial_compliance, d.Q,
          d.stick_zones.size() > 1 ? "them" : "it", d.stick_zones.size() > 1 ? "they" : "it");
    else
      a.note = fmt::format(
          "displacement control below the stick limit: the first cycle (the analogy's steady cycle whose reference "
          "points reach load.delta) has Q0 = {:.6g} N/m. At the limit the slip zones carry no pressure, and the "
          "contact is a complete contact over the stick {}, fully stuck; over the first cycle's it would be stiffer "
          "than that cycle (delta/Q0 = {:.6g} m²/N), so Q rises and the stick {} shrink{} into the first cycle's, to "
          "those of the Q* = {:.6g} N/m whose complete contact's stuck compliance C = {:.6g} m²/N gives delta = C Q* "
          "(asymptote.Q_max). The asymptote is the complete contact over them on the original profile under P",
          d.Q_initial, zones, d.initial_compliance, zones, d.stick_zones.size() > 1 ? "" : "s", d.Q, d.compliance);
  }
  return a;
}

std::string cycle_by_cycle_problem(double stability_limit) {
  if (stability_limit > wear::kCycle || stability_limit == 0.0) return {};
  return fmt::format("effects.wear.stepper: \"cycle_by_cycle\" wears one cycle at a time, an explicit jump of one "
                     "cycle, which is unstable here: the explicit stability limit 1.5 Δx/(E* c s_max) is {:.3g} "
                     "cycles. Use \"implicit\", or coarser cells or a smaller wear coefficient",
                     stability_limit);
}

namespace {
// The warm cycle solves the estimate times, and the time after which it stops timing more (s).
constexpr int kEstimateSolves = 5;
constexpr double kEstimateSeconds = 1.0;
}  // namespace

WearEstimate estimate_wear(const Scene& scene, const Model& model, const CycleStage& cycle, bool timed) {
  const WearEffect& effect = *scene.wear;
  const wear::WearLaw law{effect.law, effect.coefficient, *scene.friction,
                          effect.pad_fraction};
  std::unique_ptr<WearContact> contact = make_wear_contact(scene, model, cycle);
  const std::vector<double> w(model.grid.n, 0.0);
  wear::CycleResponse response;
  contact->respond(w, response);  // cold: the first cycle's solves start from nothing
  // Warm-started, as the run's are: the least of up to kEstimateSolves timings (within kEstimateSeconds), which
  // a busy machine disturbs far less than one timing, so that `validate` and `run` give the same verdict but within
  // a few per cent of the limit.
  WearEstimate e;
  e.seconds_per_response = std::numeric_limits<double>::infinity();
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; timed && k < kEstimateSolves; ++k) {
    const auto t0 = std::chrono::steady_clock::now();
    contact->respond(w, response);
    const auto t1 = std::chrono::steady_clock::now();
    e.seconds_per_response = std::min(e.seconds_per_response, std::chrono::duration<double>(t1 - t0).count());
    if (std::chrono::duration<double>(t1 - start).count() > kEstimateSeconds) break;
  }
  // FRETWEAR_CYCLE_SOLVE_SECONDS (tests only): the time of a cycle response, so that a test of the estimate's
  // verdicts does not depend on the speed of the machine (or of a sanitizer build).
  if (const char* fixed = std::getenv("FRETWEAR_CYCLE_SOLVE_SECONDS")) e.seconds_per_response = std::atof(fixed);
  double s_max = 0.0;
  for (double s : response.s) s_max = std::max(s_max, s);
  if (s_max == 0.0) return e;  // nothing slips: nothing wears
  for (std::size_t i = 0; i < response.s.size(); ++i)
    e.area_rate += law.rate_coefficient() * response.p[i] * response.s[i] * model.grid.h();
  e.stability_limit = wear::explicit_stability_limit(model.grid.h(), model.pair.E_star(), law.rate_coefficient(), s_max);
  if (effect.stepper == WearStepper::cycle_by_cycle) {
    e.responses = effect.cycles;
  } else if (effect.stepper == WearStepper::explicit_capped) {  // Dormand–Prince: six new stages a step, steps at the cap
    e.responses = 6.0 * std::ceil(effect.cycles / (kExplicitCapFraction * e.stability_limit));
  }
  return e;
}

namespace {

using nlohmann::json;

// Record times: the scene's list, or `count` log-spaced from cycles/10⁴ (at least 1) to cycles; always 0 first.
std::vector<double> record_times(const WearEffect& w) {
  std::vector<double> t{0.0};
  if (!w.record.empty()) {
    t.insert(t.end(), w.record.begin(), w.record.end());
  } else {
    const double first = std::max(1.0, w.cycles * 1e-4);
    const int k = w.record_count;
    for (int i = 0; i < k; ++i) {
      const double x = k == 1 ? w.cycles : first * std::pow(w.cycles / first, double(i) / (k - 1));
      const double rounded = std::round(x);
      if (rounded > t.back()) t.push_back(std::min(rounded, w.cycles));
    }
  }
  if (t.back() < w.cycles) t.push_back(w.cycles);
  return t;
}

// One wear run under way: the worn state w on the contact, driven by a stepper through the record times, recorded
// into the stage, and steered by the control at every step boundary (progress, a stop, checkpoints).
// Where a run under load.blocks stands, for its checkpoints: the block, the records of the blocks before it, and the
// stage's counts and settings so far (run_blocks() says which).
struct BlockProgress {
  int block = 0;
  const std::vector<WearRecord>* earlier = nullptr;
  json values;
};

class WearRun {
 public:
  WearRun(const Scene& scene, const Model& model, const WearControl& control, WearContact& contact, WearStage& stage)
      : WearRun(scene, model, control, contact, stage, record_times(*scene.wear), std::vector<double>(model.grid.n, 0.0),
                nullptr) {}
  // Gross slip with each body in its own frame: the state is [w_pad; w_spec] (engine/body_frames.hpp).
  WearRun(const Scene& scene, const Model& model, const WearControl& control, WearContact& contact, WearStage& stage,
          BodyFrames& frames)
      : WearRun(scene, model, control, contact, stage, record_times(*scene.wear),
                std::vector<double>(2 * std::size_t(model.grid.n), 0.0), nullptr, &frames) {}
  // One block of load.blocks: from the worn state w at times.front() through the record times, under its load;
  // with frames, w is [w_pad; w_spec] and the block is driven by drive_frames().
  WearRun(const Scene& scene, const Model& model, const WearControl& control, WearContact& contact, WearStage& stage,
          std::vector<double> times, std::vector<double> w, const BlockProgress* block, BodyFrames* frames = nullptr)
      : scene_(scene),
        effect_(*scene.wear),
        model_(model),
        control_(control),
        contact_(contact),
        stage_(stage),
        times_(std::move(times)),
        w_(std::move(w)),
        block_(block ? block->block : -1),
        blocks_(block),
        frames_(frames) {
    stage_.cycles_reached = times_.back();  // until a stop says otherwise
    // Under load.blocks the run's cycles are all the blocks': this block's end is not the run's.
    total_ = times_.back();
    if (blocks_) {
      total_ = 0.0;
      for (const LoadBlock& b : scene_.blocks) total_ += b.cycles;
    }
  }
  const std::vector<double>& state() const { return w_; }

  // Nothing slips, nothing wears: every record is of the unworn contact.
  void record_unworn() {
    for (double t : times_) record(w_, t);
  }

  // The three steppers; rate_max = max c p s at the start (m/cycle) sets the first step.
  void drive_explicit(double rate_max);
  void drive_cycle_by_cycle();
  void drive_implicit(double rate_max);
  // The bodies' frames (the second constructor): by the stepper the scene names.
  void drive_frames(double rate_max);

 private:
  // The record of `state` at `cycles`: one response on it.
  void record(const std::vector<double>& state, double cycles);
  // Drives `stepper` from the start, or from control.resume (save/restore carry the stepper's own state, as
  // engine/checkpoint.hpp's schemas), to the last record or a stop; the stage learns where it stopped, and
  // tally(state) puts the stepper's counts in it, also when a solve fails part way (then the error propagates).
  template <class Stepper, class System, class Save, class Restore, class Tally>
  DriveState drive(Stepper& stepper, System system, double dN, Save save, Restore restore, Tally tally);
  // At each step boundary: progress, the stop request, a checkpoint when one is due. False: stop.
  template <class Save>
  bool boundary(const DriveState& at, bool recorded, Save& save);

  using clock = std::chrono::steady_clock;
  const Scene& scene_;
  const WearEffect& effect_;
  const Model& model_;
  const WearControl& control_;
  WearContact& contact_;
  WearStage& stage_;
  const std::vector<double> times_;
  double total_ = 0.0;  // the cycles the progress counts to (WearProgress::total)
  std::vector<double> w_;
  int block_;
  const BlockProgress* blocks_;
  BodyFrames* frames_;
  clock::time_point last_checkpoint_;
};

void WearRun::record(const std::vector<double>& z, double cycles) {
  const int n = model_.grid.n;
  const double h = model_.grid.h();
  WearRecord rec;
  if (frames_) {  // the gap's wear at mid-stroke, and each body's
    rec.w_pad.assign(z.begin(), z.begin() + n);
    rec.w_specimen.assign(z.begin() + n, z.end());
  }
  const std::vector<double> state = frames_ ? mid_stroke(z) : z;
  wear::CycleResponse r;
  contact_.respond(state, r);
  rec.cycles = cycles;
  rec.w = state;
  rec.p = r.p;
  rec.s = r.s;
  rec.q = contact_.shear_top();
  rec.Q_max = contact_.Q_top();
  rec.block = block_;
  for (int i = 0; i < n; ++i) {
    rec.worn_area += state[i] * h;
    rec.max_depth = std::max(rec.max_depth, state[i]);
    rec.p_max = std::max(rec.p_max, r.p[i]);
  }
  if (r.has_stick) {
    rec.stick_zone = Interval{r.stick_left, r.stick_right};
    rec.stick_zones = r.stick_zones.empty() ? std::vector<Interval>{*rec.stick_zone} : r.stick_zones;
  }
  std::vector<double> g0w(n);
  for (int i = 0; i < n; ++i) g0w[i] = model_.g0[i] + state[i];
  const auto zones = locate_zones(model_.grid, r.p, g0w);
  if (!zones.empty()) rec.contact = {zones.front().left.x, zones.back().right.x};
  // The gap of the worn profile under r.p, δ the mean over the loaded cells (as the normal solver balances it), and
  // the extent where the bodies touch, worn flats without load included (contact/contact_zones.hpp).
  std::vector<double> gap(n);
  model_.kernel->apply(r.p, gap);
  double approach = 0.0;
  int loaded = 0;
  for (int i = 0; i < n; ++i) {
    gap[i] += g0w[i];
    if (r.p[i] > 0.0) approach += gap[i], ++loaded;
  }
  if (loaded > 0) approach /= loaded;
  for (double& g : gap) g -= approach;
  const auto touching =
      locate_touching(model_.grid, r.p, gap, g0w, kTouchingGap * model_.pair.A() * scene_.P);
  if (!touching.empty()) rec.touching = {touching.front().left.x, touching.back().right.x};
  rec.fraction = stage_.asymptote.worn_area > 0.0 ? rec.worn_area / stage_.asymptote.worn_area : 0.0;
  stage_.records.push_back(std::move(rec));
}

template <class Stepper, class System, class Save, class Restore, class Tally>
DriveState WearRun::drive(Stepper& stepper, System system, double dN, Save save, Restore restore, Tally tally) {
  DriveState s{times_.front(), dN, 0, 0};
  if (control_.resume) {
    const json& j = *control_.resume;
    s = resume_wear(j, scene_, w_, stage_.records);
    // Where the run stood, among the record times it drives through (drive_times: times[next - 1] <= N <= times[next]).
    const bool placed = s.next >= 1 && s.next <= times_.size() && times_[s.next - 1] <= s.N &&
                        (s.next == times_.size() ? s.N <= times_.back() : s.N <= times_[s.next]);
    if (!placed)
      throw InputError(fmt::format("checkpoint: damaged: it stands at cycle {:.6g} before record {} of {}, which this "
                                   "scene's wear run ({:.6g} to {:.6g} cycles) never does",
                                   s.N, s.next, times_.size(), times_.front(), times_.back()));
    const std::size_t earlier = blocks_ ? j.at("blocks").at("earlier_records").get<std::size_t>() : 0;
    if (earlier > stage_.records.size())
      throw InputError("checkpoint: damaged: it counts more earlier records than it holds");
    if (blocks_)  // the checkpoint holds every record; this block's follow the earlier blocks'
      stage_.records.erase(stage_.records.begin(), stage_.records.begin() + std::ptrdiff_t(earlier));
    else if (stage_.records.size() != s.next)  // one record at each record time reached, the start's included
      throw InputError(fmt::format("checkpoint: damaged: it holds {} records where it has reached {}",
                                   stage_.records.size(), s.next));
    contact_.restore(j.at("contact"));
    restore(j.at("stepper_state"));
    stage_.resumed_from = s.N;
  }
  last_checkpoint_ = clock::now();
  bool completed = false;
  try {
    completed = drive_times(
        stepper, system, w_, times_, s, [this](const std::vector<double>& state, double N) { record(state, N); },
        [this, &save](const DriveState& at, bool recorded) { return boundary(at, recorded, save); });
  } catch (const wear::ImplicitSolveFailure&) {
    stage_.cycles_reached = s.N;
    tally(s);
    throw;  // it names its cycle, and drive_implicit adds the residual
  } catch (const ConvergenceError& e) {  // a cycle's solve on the worn profile: say where the run was
    stage_.cycles_reached = s.N;
    tally(s);
    throw ConvergenceError(fmt::format("{}, in the wear stage at cycle {:.0f} of {:.0f} (step of {:.4g} cycles)",
                                       e.what(), s.N, times_.back(), s.dt));
  }
  stage_.interrupted = !completed;
  stage_.cycles_reached = s.N;
  tally(s);
  return s;
}

template <class Save>
bool WearRun::boundary(const DriveState& at, bool recorded, Save& save) {
  const double h = model_.grid.h();
  double area = 0.0;
  for (double wi : w_) area += wi * h;
  const double fraction = stage_.asymptote.worn_area > 0.0 ? area / stage_.asymptote.worn_area : 0.0;
  const WearProgress progress{at.N, total_, at.dt, fraction, int(at.steps), block_, int(scene_.blocks.size())};
  if (control_.progress) control_.progress(progress);
  const bool stop = control_.stop_requested && control_.stop_requested(progress);
  const bool due =
      std::chrono::duration<double>(clock::now() - last_checkpoint_).count() >= control_.checkpoint_interval;
  if (!control_.checkpoint.empty() && (recorded || stop || due)) {
    json j;
    if (blocks_) {  // every record so far, and where the blocks stand
      std::vector<WearRecord> all = *blocks_->earlier;
      all.insert(all.end(), stage_.records.begin(), stage_.records.end());
      j = wear_checkpoint(scene_, control_.scene_hash, at, times_.back(), w_, all, contact_.save(), save());
      j["blocks"] = blocks_->values;
      j["blocks"]["block"] = blocks_->block;
      j["blocks"]["earlier_records"] = blocks_->earlier->size();
    } else {
      j = wear_checkpoint(scene_, control_.scene_hash, at, times_.back(), w_, stage_.records, contact_.save(), save());
    }
    // A checkpoint is insurance: one that cannot be written (a full disk) leaves the last one in place, and the run
    // goes on; the caller says so where it offers --resume.
    try {
      write_checkpoint(control_.checkpoint, j);
      stage_.checkpoint_failure.clear();
    } catch (const Error& e) {
      stage_.checkpoint_failure = e.what();
    }
    last_checkpoint_ = clock::now();
  }
  return !stop;
}

void WearRun::drive_explicit(double rate_max) {
  // abs: the tolerance on the scale of the depth the run wears toward, as the implicit stepper's max-norm.
  const double depth = stage_.asymptote.max_depth > 0.0 ? stage_.asymptote.max_depth : rate_max * effect_.cycles;
  stage_.explicit_step_cap = kExplicitCapFraction * stage_.stability_limit;
  wear::ExplicitWearStepper stepper(effect_.tolerance * depth, effect_.tolerance, stage_.explicit_step_cap);
  wear::WearRateSystem rate(contact_, stage_.rate_coefficient);
  const double dN = std::min(stage_.explicit_step_cap, std::max(1.0, effect_.tolerance * depth / rate_max));
  drive(
      stepper, std::ref(rate), dN, [&] { return save_explicit(stepper, rate); },
      [&](const json& j) { restore_explicit(j, stepper, rate, w_); },
      [&](const DriveState&) {
        stage_.steps = stepper.stats().accepted;
        stage_.rejected_steps = stepper.stats().rejected;
        stage_.explicit_max_step = stepper.stats().max_step;
        stage_.responses = int(rate.evaluations());
      });
}

void WearRun::drive_cycle_by_cycle() {
  if (const std::string problem = cycle_by_cycle_problem(stage_.stability_limit); !problem.empty())
    throw UnsupportedError(problem);
  wear::WearRateSystem rate(contact_, stage_.rate_coefficient);
  AlwaysAccepted<wear::CycleByCycleStepper> stepper;
  drive(
      stepper, std::ref(rate), wear::kCycle, [&] { return save_cycle_by_cycle(rate); },
      [&](const json& j) { restore_cycle_by_cycle(j, rate); },
      [&](const DriveState& s) {
        stage_.steps = int(s.steps);
        stage_.responses = int(rate.evaluations());
      });
}

void WearRun::drive_implicit(double rate_max) {
  // First jump: a small share of the asymptote's depth at the initial rate, bounded by the first record.
  const double dN = std::max(1.0, effect_.tolerance * stage_.asymptote.max_depth / rate_max);
  wear::ImplicitWearStepper stepper(stage_.rate_coefficient, effect_.tolerance);
  try {
    drive(
        stepper, wear::ResponseRef{&contact_}, dN, [&] { return save_implicit(stepper); },
        [&](const json& j) { restore_implicit(j, stepper, w_.size()); },
        [&](const DriveState&) {
          stage_.steps = stepper.stats().accepted;
          stage_.unconverged_steps = stepper.stats().unconverged;
          stage_.rejected_steps = stepper.stats().rejected;
          stage_.implicit_solves = stepper.stats().implicit_solves;
          stage_.responses = stepper.stats().responses;
        });
  } catch (const wear::ImplicitSolveFailure& e) {
    const SolveSummary& last = contact_.last_unconverged;
    throw ConvergenceError(fmt::format("{} ({}, residual {:.3g})", e.what(), to_string(last.termination),
                                       last.residual));
  }
}

void WearRun::drive_frames(double rate_max) {
  BodyFrames& frames = *frames_;
  // The frames' own counts, whichever stepper drives them.
  const auto frame_counts = [&] {
    stage_.implicit_solves = int(frames.solves());
    stage_.mean_iterations_implicit = double(frames.cg_iterations()) / double(std::max(1L, frames.solves()));
    stage_.frame_iterations = frames.iterations();
    stage_.frame_positions = int(frames.positions().shift.size());
    stage_.frame_directions = frames.directions();
  };
  if (effect_.stepper == WearStepper::explicit_capped) {
    // As drive_explicit(): the tolerance on the scale of the depth the run wears toward, steps capped below the
    // explicit stability limit of the bodies' coefficients together.
    const double depth = stage_.asymptote.max_depth > 0.0 ? stage_.asymptote.max_depth : rate_max * effect_.cycles;
    stage_.explicit_step_cap = kExplicitCapFraction * stage_.stability_limit;
    wear::ExplicitWearStepper stepper(effect_.tolerance * depth, effect_.tolerance, stage_.explicit_step_cap);
    FramesRateSystem rate(frames);
    const double dN = std::min(stage_.explicit_step_cap, std::max(1.0, effect_.tolerance * depth / rate_max));
    drive(
        stepper, std::ref(rate), dN,
        [&] {
          json j = rate.save();
          j["accepted"] = stepper.stats().accepted, j["rejected"] = stepper.stats().rejected;
          j["max_step"] = stepper.stats().max_step;
          return j;
        },
        [&](const json& j) {
          rate.restore(j, std::size_t(model_.grid.n), w_.size());
          const int accepted = j.at("accepted").get<int>();
          stepper.restore({accepted, j.at("rejected").get<int>(), j.at("max_step").get<double>()}, w_,
                          accepted > 0 ? &rate.last_rate() : nullptr);
        },
        [&](const DriveState&) {
          stage_.steps = stepper.stats().accepted;
          stage_.rejected_steps = stepper.stats().rejected;
          stage_.explicit_max_step = stepper.stats().max_step;
          stage_.responses = int(rate.evaluations());
          frame_counts();
        });
  } else if (effect_.stepper == WearStepper::cycle_by_cycle) {
    if (const std::string problem = cycle_by_cycle_problem(stage_.stability_limit); !problem.empty())
      throw UnsupportedError(problem);
    FramesCycleByCycle stepper;
    drive(
        stepper, std::ref(frames), wear::kCycle, [] { return json::object(); }, [](const json&) {},
        [&](const DriveState& s) {
          stage_.steps = int(s.steps);
          stage_.responses = int(stepper.responses);
          frame_counts();
        });
  } else {
    const double dN = std::max(1.0, effect_.tolerance * stage_.asymptote.max_depth / rate_max);
    FramesWearStepper stepper(effect_.tolerance);
    drive(
        stepper, std::ref(frames), dN,
        [&] {
          json j = stepper.save();
          j["solves"] = frames.solves(), j["iterations"] = frames.iterations();
          j["cg_iterations"] = frames.cg_iterations();
          return j;
        },
        [&](const json& j) {
          stepper.restore(j, std::size_t(model_.grid.n));
          frames.count(j.at("solves").get<long>(), j.at("iterations").get<long>(),
                       j.at("cg_iterations").get<long>());
        },
        [&](const DriveState&) {
          stage_.steps = stepper.stats().accepted;
          stage_.rejected_steps = stepper.stats().rejected;
          stage_.unconverged_steps = stepper.stats().unconverged;
          stage_.responses = stepper.stats().responses;
          frame_counts();
        });
  }
}

}  // namespace

namespace {

// The first response on the worn state w: the fastest wear max c p s (m/cycle), which sets the first step, and the
// explicit stability limit 1.5 Δx/(E* c s_max) (cycles; 0 when nothing slips).
struct FirstResponse {
  double rate_max = 0.0, stability_limit = 0.0;
};
FirstResponse first_response(WearContact& contact, const std::vector<double>& w, const Model& model, double c) {
  wear::CycleResponse r;
  contact.respond(w, r);
  double rate_max = 0.0, s_max = 0.0;
  for (int i = 0; i < model.grid.n; ++i) {
    rate_max = std::max(rate_max, c * r.p[i] * r.s[i]);
    s_max = std::max(s_max, r.s[i]);
  }
  return {rate_max, wear::explicit_stability_limit(model.grid.h(), model.pair.E_star(), c, s_max)};
}

// The run by the scene's stepper from the first response's rate; nothing slipping, every record is the unworn one.
void drive_by(WearRun& run, WearStepper stepper, double rate_max) {
  if (rate_max == 0.0)
    run.record_unworn();
  else if (stepper == WearStepper::explicit_capped)
    run.drive_explicit(rate_max);
  else if (stepper == WearStepper::cycle_by_cycle)
    run.drive_cycle_by_cycle();
  else
    run.drive_implicit(rate_max);
}

// load.blocks, run once in order: each block's cycle on the incremental route (one route for all, as the load
// changes between them), solved on the profile the blocks before it wore. Each block is a wear run of its own from
// the state the last one left: a fresh stepper (its step and its cached response belong to the old load) and
// records at the block's start and end and at the scene's record times inside it (a block's start record is the
// same profile as the previous block's end record, under the new load). Its checkpoints hold, beside the block's
// own run, the block, every record before it, the stage's counts so far, and what the block's first response
// set (the first step's rate and, from block 0, the stability limit): a resumed run takes the block up where it
// stopped and the later blocks as the uninterrupted run does, to the bit.
void run_blocks(const Scene& scene, const Model& model, const CycleStage& cycle, const WearControl& control,
                WearStage& stage) {
  const WearEffect& effect = *scene.wear;
  const int n = model.grid.n;
  const std::vector<double> all = record_times(effect);
  std::vector<double> w(std::size_t(n), 0.0);
  // Each body in its own frame (engine/body_frames.hpp) in a block that slides over half a cell with the specimen
  // wearing, as a run of its one load would. From the first such block on the blocks carry z = [w_pad; w_spec],
  // where it starts the shared profile split by pad_fraction (which is what the shared profile stands for), and a
  // later block in partial slip wears the gap's profile w_pad + w_spec, its wear split by pad_fraction. Empty until
  // then.
  const bool frames_allowed = effect.pad_fraction < 1.0;
  std::vector<double> z;
  double start = 0.0;
  stage.route = "incremental (load.blocks)";
  long cycle_solves = 0, cycle_iterations = 0, implicit_solves = 0, implicit_iterations = 0;
  // The stage's running values, as a checkpoint carries them, with the block's frames and z where it starts.
  auto values = [&](double rate_max, bool frames) {
    return json{{"start", start},
                {"rate_max", rate_max},
                {"stability_limit", stage.stability_limit},
                {"steps", stage.steps},
                {"rejected_steps", stage.rejected_steps},
                {"unconverged_steps", stage.unconverged_steps},
                {"implicit_solves", stage.implicit_solves},
                {"responses", stage.responses},
                {"unsteady_history_responses", stage.unsteady_history_responses},
                {"explicit_max_step", stage.explicit_max_step},
                {"cycle_solves", cycle_solves},
                {"cycle_iterations", cycle_iterations},
                {"contact_implicit_solves", implicit_solves},
                {"implicit_iterations", implicit_iterations},
                {"frames", frames},
                {"frame_positions", stage.frame_positions},
                {"frame_directions", stage.frame_directions},
                {"frame_iterations", stage.frame_iterations},
                {"z", blob(z)}};
  };
  std::size_t first = 0;
  const json* resumed = control.resume ? &control.resume->at("blocks") : nullptr;
  if (control.resume && !control.resume->contains("blocks"))
    throw InputError("checkpoint: not written by a run under load.blocks");
  if (resumed) {
    first = resumed->at("block").get<std::size_t>();
    if (first >= scene.blocks.size()) throw InputError("checkpoint: its block is not one of load.blocks");
    start = resumed->at("start").get<double>();
    stage.stability_limit = resumed->at("stability_limit").get<double>();
    stage.steps = resumed->at("steps").get<int>();
    stage.rejected_steps = resumed->at("rejected_steps").get<int>();
    stage.unconverged_steps = resumed->at("unconverged_steps").get<int>();
    stage.implicit_solves = resumed->at("implicit_solves").get<int>();
    stage.responses = resumed->at("responses").get<int>();
    stage.unsteady_history_responses = resumed->value("unsteady_history_responses", 0L);
    stage.explicit_max_step = resumed->at("explicit_max_step").get<double>();
    cycle_solves = resumed->at("cycle_solves").get<long>();
    cycle_iterations = resumed->at("cycle_iterations").get<long>();
    implicit_solves = resumed->at("contact_implicit_solves").get<long>();
    implicit_iterations = resumed->at("implicit_iterations").get<long>();
    stage.frame_positions = resumed->at("frame_positions").get<int>();
    stage.frame_directions = resumed->at("frame_directions").get<int>();
    stage.frame_iterations = resumed->at("frame_iterations").get<long>();
    z = unblob(resumed->at("z"));
    const json& records = control.resume->at("records");
    for (std::size_t k = 0; k < resumed->at("earlier_records").get<std::size_t>(); ++k)
      stage.records.push_back(record_from(records.at(k)));
  }
  // A solve that did not converge part way through a block: that block's records so far join the stage's, then the
  // error propagates.
  std::exception_ptr failure;
  for (std::size_t b = first; b < scene.blocks.size(); ++b) {
    const double end = start + scene.blocks[b].cycles;
    std::vector<double> times{start};
    for (double t : all)
      if (t > start && t < end) times.push_back(t);
    times.push_back(end);
    IncrementalContactResponse contact(scene, model, cycle, block_load(scene, model.pair, scene.blocks[b]));
    const bool resuming = resumed && b == first;
    WearControl block_control = control;
    if (!resuming) block_control.resume.reset();
    const std::vector<double> w_start = z.empty() ? w : mid_stroke(z);
    double rate_max = 0.0;
    bool frames = false;
    if (resuming) {
      rate_max = resumed->at("rate_max").get<double>();
      frames = resumed->at("frames").get<bool>();
    } else {
      const FirstResponse response = first_response(contact, w_start, model, stage.rate_coefficient);
      rate_max = response.rate_max;
      if (b == 0) stage.stability_limit = response.stability_limit;
      const CycleResult& c = contact.last_cycle();
      frames = frames_allowed && rate_max > 0.0 && c.regime == Regime::gross_slip &&
               c.sliding_amplitude > 0.5 * model.grid.h();
      if (frames && z.empty()) {
        z.assign(std::size_t(2 * n), 0.0);
        for (int i = 0; i < n; ++i)
          z[std::size_t(i)] = effect.pad_fraction * w[std::size_t(i)],
          z[std::size_t(n + i)] = (1.0 - effect.pad_fraction) * w[std::size_t(i)];
      }
    }
    WearStage part;  // the block's run; its records and counts join the stage's
    part.rate_coefficient = stage.rate_coefficient;
    part.asymptote = stage.asymptote;
    part.stability_limit = stage.stability_limit;
    const BlockProgress progress{int(b), &stage.records, values(rate_max, frames)};
    if (frames) {
      contact.give_slip_travelled();  // the frames weigh it by their own pressures
      const double c = stage.rate_coefficient, pad = effect.pad_fraction;
      BodyFrames body_frames(
          model, scene.P, *scene.friction, c * pad, c * (1.0 - pad),
          [&contact](std::span<const double> state, wear::CycleResponse& out) { contact.respond(state, out); },
          [&contact] { return contact.last_cycle().sliding_amplitude; });
      WearRun run(scene, model, block_control, contact, part, times, z, &progress, &body_frames);
      try {
        run.drive_frames(rate_max);
      } catch (const ConvergenceError&) {
        failure = std::current_exception();
      }
      implicit_solves += body_frames.solves(), implicit_iterations += body_frames.cg_iterations();
      z = run.state();
      w = mid_stroke(z);
    } else {
      WearRun run(scene, model, block_control, contact, part, times, w_start, &progress);
      try {
        drive_by(run, effect.stepper, rate_max);
      } catch (const ConvergenceError&) {
        failure = std::current_exception();
      }
      w = run.state();
      if (!z.empty()) {  // the bodies in their own frames so far: this block's wear split by pad_fraction
        const double pad = effect.pad_fraction;
        const auto split = [&](const std::vector<double>& state, std::vector<double>& w_pad,
                               std::vector<double>& w_specimen) {
          w_pad.assign(z.begin(), z.begin() + n);
          w_specimen.assign(z.begin() + n, z.end());
          for (int i = 0; i < n; ++i) {
            const double worn = state[std::size_t(i)] - w_start[std::size_t(i)];
            w_pad[std::size_t(i)] += pad * worn, w_specimen[std::size_t(i)] += (1.0 - pad) * worn;
          }
        };
        for (WearRecord& r : part.records) split(r.w, r.w_pad, r.w_specimen);
        std::vector<double> w_pad, w_specimen;
        split(w, w_pad, w_specimen);
        std::copy(w_pad.begin(), w_pad.end(), z.begin());
        std::copy(w_specimen.begin(), w_specimen.end(), z.begin() + n);
      }
    }
    for (WearRecord& r : part.records) stage.records.push_back(std::move(r));
    stage.steps += part.steps, stage.rejected_steps += part.rejected_steps;
    stage.unconverged_steps += part.unconverged_steps, stage.implicit_solves += part.implicit_solves;
    stage.responses += part.responses;
    stage.explicit_step_cap = part.explicit_step_cap;
    stage.explicit_max_step = std::max(stage.explicit_max_step, part.explicit_max_step);
    stage.frame_positions = std::max(stage.frame_positions, part.frame_positions);
    stage.frame_directions = std::max(stage.frame_directions, part.frame_directions);
    stage.frame_iterations += part.frame_iterations;
    stage.cycles_reached = part.cycles_reached;
    if (part.resumed_from) stage.resumed_from = part.resumed_from;
    cycle_solves += contact.cycle_solves, cycle_iterations += contact.cycle_iterations;
    stage.unsteady_history_responses += contact.unsteady_responses();
    implicit_solves += contact.implicit_solves, implicit_iterations += contact.implicit_iterations;
    if (failure || part.interrupted) {
      stage.interrupted = part.interrupted;
      break;
    }
    start = end;
  }
  stage.mean_iterations_cycle = double(cycle_iterations) / double(std::max(1L, cycle_solves));
  stage.mean_iterations_implicit = double(implicit_iterations) / double(std::max(1L, implicit_solves));
  if (failure) std::rethrow_exception(failure);
}

// Under displacement control, with an asymptote: the limit of the last record's stick zones (WearStage::settled),
// with the cycle stage's datum.
void settle(const Scene& scene, const Model& model, const CycleStage& cycle, WearStage& stage) {
  if (!stage.asymptote.Q_max || stage.records.empty() || stage.records.back().stick_zones.empty()) return;
  const WearRecord& last = stage.records.back();
  std::vector<Zone> zones(last.stick_zones.size());
  for (std::size_t k = 0; k < zones.size(); ++k)
    zones[k].left.x = last.stick_zones[k].first, zones[k].right.x = last.stick_zones[k].second;
  WearStage::Settled settled;
  settled.worn_area = settled_worn_area(model.grid, *model.kernel, model.g0, last.w, scene.P, zones);
  settled.Q_max = *scene.delta / stuck_compliance(model.grid, model.pair, cycle.reference_x, cycle.reference_depth,
                                                  zones);
  stage.settled = settled;
}

}  // namespace

namespace {

WearStage::Scar scar(const Grid& grid, const std::vector<double>& w) {
  WearStage::Scar s;
  for (double wi : w) s.max_depth = std::max(s.max_depth, wi), s.worn_area += wi * grid.h();
  int left = -1, right = -1;
  for (int i = 0; i < grid.n; ++i)
    if (s.max_depth > 0.0 && w[std::size_t(i)] > kScarEdge * s.max_depth) right = i, left = left < 0 ? i : left;
  if (left >= 0) s.extent = {grid.x(left) - 0.5 * grid.h(), grid.x(right) + 0.5 * grid.h()};
  return s;
}

// Each body's scar at the last record: its own frame's, or its share of the shared profile.
void scars(const Model& model, const WearEffect& effect, WearStage& stage) {
  if (stage.records.empty()) return;
  const WearRecord& last = stage.records.back();
  std::vector<double> pad = last.w_pad, specimen = last.w_specimen;
  if (pad.empty()) {
    pad = specimen = last.w;
    for (double& w : pad) w *= effect.pad_fraction;
    for (double& w : specimen) w *= 1.0 - effect.pad_fraction;
  }
  stage.pad = scar(model.grid, pad);
  stage.specimen = scar(model.grid, specimen);
}

}  // namespace

bool bodies_in_own_frames(const Scene& scene, const Model& model, const CycleStage& cycle) {
  const CycleResult& c = cycle.result;
  return scene.wear && c.regime == Regime::gross_slip && scene.wear->pad_fraction < 1.0 &&
         c.sliding_amplitude > 0.5 * model.grid.h() && scene.blocks.empty();
}

namespace {

WearStage wear_stage(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                     const WearControl& control) {
  const WearEffect& effect = *scene.wear;
  const wear::WearLaw law{effect.law, effect.coefficient, *scene.friction,
                          effect.pad_fraction};
  WearStage stage;
  stage.rate_coefficient = law.rate_coefficient();
  stage.asymptote = wear_asymptote(scene, model, normal);
  // A solve that fails once records were taken: the stage as far as it got goes with the error.
  const auto not_converged = [&stage](const ConvergenceError& e) {
    if (stage.records.empty()) throw;
    throw WearNotConverged(e.what(), std::make_shared<const WearStage>(std::move(stage)));
  };
  if (!scene.blocks.empty()) {
    try {
      run_blocks(scene, model, cycle, control, stage);
    } catch (const ConvergenceError& e) {
      scars(model, effect, stage);
      not_converged(e);
    }
    scars(model, effect, stage);
    return stage;
  }

  const std::unique_ptr<WearContact> contact = make_wear_contact(scene, model, cycle);
  stage.route = to_string(cycle.ran);
  const FirstResponse first =
      first_response(*contact, std::vector<double>(std::size_t(model.grid.n), 0.0), model, stage.rate_coefficient);
  stage.stability_limit = first.stability_limit;

  auto* incremental = dynamic_cast<IncrementalContactResponse*>(contact.get());
  // What the run says of itself once driven, to its end or to a solve that failed part way.
  const auto tally = [&] {
    if (incremental && incremental->analogy_responses() > 0) {
      stage.route = "analogy (displacement control: each cycle's Q solved for load.delta)";
      if (!incremental->analogy_gave_up().empty())
        stage.route += fmt::format(", then incremental after {} responses: {}", incremental->analogy_responses(),
                                   incremental->analogy_gave_up());
    }
    if (incremental && incremental->beta() != 0.0) {
      const long coupled = incremental->coupled_responses(), lagged = incremental->lagged_responses();
      stage.coupling = WearStage::Coupling{coupled + lagged, coupled, incremental->mirrored_responses(), lagged};
    }
    if (incremental) stage.unsteady_history_responses = incremental->unsteady_responses();
    if (first.rate_max == 0.0) return;  // nothing slips: nothing wears
    scars(model, effect, stage);
    stage.mean_iterations_cycle = double(contact->cycle_iterations) / double(std::max(1L, contact->cycle_solves));
    if (stage.frame_positions == 0)  // with frames, drive_frames() counted its own solves
      stage.mean_iterations_implicit =
          double(contact->implicit_iterations) / double(std::max(1L, contact->implicit_solves));
  };
  try {
    if (incremental && first.rate_max > 0.0 && bodies_in_own_frames(scene, model, cycle)) {
      const double c = stage.rate_coefficient, pad = effect.pad_fraction;
      incremental->give_slip_travelled();  // the frames weigh it by their own pressures
      BodyFrames frames(
          model, scene.P, *scene.friction, c * pad, c * (1.0 - pad),
          [incremental](std::span<const double> w, wear::CycleResponse& out) { incremental->respond(w, out); },
          [incremental] { return incremental->last_cycle().sliding_amplitude; });
      WearRun run(scene, model, control, *contact, stage, frames);
      run.drive_frames(first.rate_max);
    } else {
      WearRun run(scene, model, control, *contact, stage);
      drive_by(run, effect.stepper, first.rate_max);
    }
  } catch (const ConvergenceError& e) {
    tally();
    not_converged(e);
  }
  tally();
  if (first.rate_max == 0.0) return stage;
  settle(scene, model, cycle, stage);
  return stage;
}

}  // namespace

WearStage run_wear(const Scene& scene, const Model& model, const NormalResult& normal, const CycleStage& cycle,
                   const WearControl& control) {
  if (!control.resume) return wear_stage(scene, model, normal, cycle, control);
  // A checkpoint whose checksum holds but whose content is not a checkpoint of this scene's (anyone can write a
  // checksum): a key missing or of another type is the checkpoint's fault, not fretwear's.
  try {
    return wear_stage(scene, model, normal, cycle, control);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: damaged: it does not hold what a checkpoint of this scene holds ({}); delete it "
                                 "and run without --resume",
                                 control.checkpoint.string(), e.what()));
  }
}

namespace {

nlohmann::json intensity(const std::optional<double>& k) { return k ? nlohmann::json(*k) : nlohmann::json(nullptr); }

// K_N at the outer ends of the asymptote's stick zones: the left end of the first, the right end of the last.
nlohmann::json asymptote_edge_intensity(const WearAsymptote& a) {
  if (a.edge_intensities.empty()) return nullptr;
  return {intensity(a.edge_intensities.front().left), intensity(a.edge_intensities.back().right)};
}

// One pair [K_left, K_right] per stick zone, left to right.
nlohmann::json asymptote_edge_intensities(const WearAsymptote& a) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const EdgeIntensities& k : a.edge_intensities) pairs.push_back({intensity(k.left), intensity(k.right)});
  return pairs;
}

}  // namespace

nlohmann::json summarise_wear(const Scene& scene, const WearStage& w) {
  using nlohmann::json;
  const WearEffect& e = *scene.wear;
  auto interval = [](const std::optional<Interval>& i) { return i ? json{i->first, i->second} : json(nullptr); };
  const WearRecord& last = w.records.back();
  json out = {
      {"law", to_string(e.law)},
      {"coefficient", e.coefficient},
      {"rate_coefficient", w.rate_coefficient},
      {"pad_fraction", e.pad_fraction},
      {"coefficient_pad", e.per_body ? e.coefficient_pad : e.pad_fraction * e.coefficient},
      {"coefficient_specimen", e.per_body ? e.coefficient_specimen : (1.0 - e.pad_fraction) * e.coefficient},
      {"stepper", to_string(e.stepper)},
      {"tolerance", e.tolerance},
      {"cycles", last.cycles},
      {"worn_area", last.worn_area},
      {"max_depth", last.max_depth},
      {"fraction_of_asymptote", w.asymptote.unavailable.empty() ? json(last.fraction) : json(nullptr)},
      {"stick_zone_initial", interval(w.records.front().stick_zone)},
      {"stick_zone_final", interval(last.stick_zone)},
      {"stick_zones_initial", w.records.front().stick_zones},
      {"stick_zones_final", last.stick_zones},
      {"contact_final", {last.contact.first, last.contact.second}},
      {"touching_final", {last.touching.first, last.touching.second}},
      {"steps", w.steps},
      {"rejected_steps", w.rejected_steps},
      {"implicit_solves", w.implicit_solves},
      {"cycle_solves", w.responses},
      {"mean_iterations_cycle", w.mean_iterations_cycle},
      {"mean_iterations_implicit", w.mean_iterations_implicit},
      {"explicit_stability_limit", w.stability_limit},
      {"records", w.records.size()},
      {"asymptote",
       {{"worn_area", w.asymptote.worn_area},
        {"max_depth", w.asymptote.max_depth},
        {"x_max_depth", w.asymptote.x_max_depth},
        {"extent", {w.asymptote.extent.first, w.asymptote.extent.second}},
        {"edge_intensity", asymptote_edge_intensity(w.asymptote)},
        {"edge_intensities", asymptote_edge_intensities(w.asymptote)}}}};
  // Where the run got to (the last record is wear.cycles); an interrupted run stops short of cycles_target.
  // The cycle's route on the worn profile; without an asymptote, null and the reason.
  out["route"] = w.route;
  out["Q_max_initial"] = w.records.front().Q_max;
  out["Q_max_final"] = last.Q_max;
  if (!w.asymptote.unavailable.empty()) {
    out["asymptote"] = nullptr;
    out["asymptote_note"] = w.asymptote.unavailable;
  } else if (w.asymptote.Q_max) {  // displacement control: the limit's Q, its compliance, and how it was found
    out["asymptote"]["Q_max"] = *w.asymptote.Q_max;
    out["asymptote"]["stuck_compliance"] = *w.asymptote.stuck_compliance;
    out["asymptote_note"] = w.asymptote.note;
  }
  if (w.settled) {  // displacement control: the limit of the last record's stick zones, were they to stand still
    out["settled_limit"] = {{"worn_area", w.settled->worn_area},
                            {"Q_max", w.settled->Q_max},
                            {"fraction", w.settled->worn_area > 0.0 ? json(last.worn_area / w.settled->worn_area)
                                                                     : json(nullptr)}};
  }
  // Each body's scar, in its own frame where the run tracked the frames (gross slip), else its share of w.
  auto body = [](const WearStage::Scar& b) {
    return json{{"max_depth", b.max_depth},
                {"worn_area", b.worn_area},
                {"extent", {b.extent.first, b.extent.second}},
                {"width", b.extent.second - b.extent.first}};
  };
  out["bodies"] = {{"frames", w.frame_positions > 0 ? "own" : "shared"},
                   {"positions", w.frame_positions},
                   {"directions", w.frame_directions},
                   {"pad", body(w.pad)},
                   {"specimen", body(w.specimen)}};
  if (w.frame_positions > 0) out["frame_iterations"] = w.frame_iterations;
  if (w.coupling)
    out["coupling"] = {{"responses", w.coupling->responses},
                       {"coupled", w.coupling->coupled},
                       {"mirrored", w.coupling->mirrored},
                       {"lagged", w.coupling->lagged}};
  out["cycles_target"] = e.cycles;
  out["cycles_reached"] = w.cycles_reached;
  if (w.resumed_from) out["resumed_from"] = *w.resumed_from;
  if (!scene.blocks.empty()) {  // per block of load.blocks: its cycles and the wear at its end
    json blocks = json::array();
    double start = 0.0;
    for (std::size_t b = 0; b < scene.blocks.size(); ++b) {
      const WearRecord* end = nullptr;
      for (const WearRecord& r : w.records)
        if (r.block == int(b)) end = &r;
      json one = {{"block", b}, {"cycles_start", start}, {"cycles_end", start + scene.blocks[b].cycles}};
      one["worn_area_end"] = end ? json(end->worn_area) : json(nullptr);
      one["max_depth_end"] = end ? json(end->max_depth) : json(nullptr);
      one["Q_max_end"] = end ? json(end->Q_max) : json(nullptr);
      blocks.push_back(std::move(one));
      start += scene.blocks[b].cycles;
    }
    out["blocks"] = std::move(blocks);
  }
  if (e.stepper == WearStepper::explicit_capped) {  // the cap on ΔN below the stability limit, and the longest step taken (cycles)
    out["explicit_step_cap"] = w.explicit_step_cap;
    out["explicit_max_step"] = w.explicit_max_step;
  }
  return out;
}

void write_wear(const Scene& scene, const NormalResult& normal, const CycleStage& cycle, const WearStage& w,
                OutputFolder& out, Written& written) {
  out.write("wear_history.csv", wear_history_csv(w));
  out.write("profiles.csv", profiles_csv(scene, normal, w));
  written.tables.insert(written.tables.end(), {"wear_history.csv", "profiles.csv"});
  if (most_stick_zones(w) > 1) {
    out.write("wear_stick_zones.csv", wear_stick_zones_csv(w));
    written.tables.push_back("wear_stick_zones.csv");
  }
  if (!scene.plots) return;
  out.write("wear.gp", wear_plot_script(scene, normal, cycle, w));
  if (!run_gnuplot(out.path(""), "wear.gp")) return;
  auto& plots = written.plots;
  plots.insert(plots.end(), {"wear_depth.svg", "wear_depth.png", "wear_pressure.svg", "wear_pressure.png"});
  if (w.records.back().cycles > 0.0) {  // against cycles, on a log axis
    if (w.records.front().stick_zone) plots.insert(plots.end(), {"wear_stick_zone.svg", "wear_stick_zone.png"});
    plots.insert(plots.end(), {"wear_area.svg", "wear_area.png"});
  }
}

}  // namespace fretwear
