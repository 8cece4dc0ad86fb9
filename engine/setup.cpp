#include "engine/setup.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "contact/wear_limit.hpp"
#include "contact/worn_flat.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/normal_stage.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace {

Model model_on(const Scene& scene, const Grid& grid, const WindowChoice& window) {
  Model m{ElasticPair(scene.pad, scene.specimen, scene.plane), Profile(scene.profile), grid, window, {}, nullptr};
  m.g0.resize(m.grid.n);
  for (int i = 0; i < m.grid.n; ++i) m.g0[i] = m.profile.gap(m.grid.x(i));
  m.kernel = std::make_unique<HalfPlaneKernel>(m.grid, m.pair.A());
  return m;
}

// The constant loads on similar bodies whose asymptotes stand for the worn extent of the scene's run. Paper 002's
// limit (wear_asymptote) is that of similar bodies under one constant load; a scene outside it still wears its slip
// zones towards some limit, so its window is sized from these stand-ins:
//  - each loading of the scene (its own, or each block of load.blocks) held constant: load.Q as given, load.delta
//    with its bulk stress (whose limit is not established: worn_reach takes both δ's asymptote without it and the
//    limit over the stick zones of its marched first cycle); a history at its largest ratio |Q|/(fP) under its
//    largest P (the smallest stick zone it reaches, so the widest slip zones), with the bulk stress of the point
//    where that ratio is reached, in phase;
//  - dissimilar bodies (Dundurs β ≠ 0) as the similar pair of the same compliance A = 2/E*, the pad's material with
//    its modulus scaled: the same contact under P, and the uncoupled pressure's limit, which the lagged coupled run
//    tends to (engine/wear_contacts.hpp).
// The scene itself when it is already one such load (`itself`).
struct StandIns {
  std::vector<Scene> scenes;
  bool itself = true;
};
StandIns window_stand_ins(const Scene& scene) {
  StandIns out;
  out.itself = scene.blocks.empty() && scene.history.empty();
  Scene base = scene;
  base.blocks.clear();
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  if (std::abs(pair.beta()) > 1e-12) {
    Material m = scene.pad;
    m.E *= ElasticPair(m, m, scene.plane).A() / pair.A();
    base.pad = base.specimen = m;
    out.itself = false;
  }
  const auto held = [&base, &out](std::optional<double> Q_amplitude, std::optional<double> Q_ratio,
                                  std::optional<double> delta, const std::vector<std::array<double, 4>>& history) {
    Scene s = base;
    s.Q_amplitude = Q_amplitude, s.Q_ratio = Q_ratio, s.delta = delta, s.history.clear();
    s.control = delta ? LoadControl::displacement : LoadControl::force;
    if (delta && s.bulk_stress != 0.0) out.itself = false;  // δ's limit with a bulk stress is not established
    if (history.empty()) return s;
    double ratio = 0.0;
    for (const auto& pt : history) {
      s.P = std::max(s.P, pt[1]);
      const double r = std::abs(pt[2]) / (*s.friction * pt[1]);
      if (r > ratio) ratio = r, s.bulk_stress = pt[2] < 0.0 ? -pt[3] : pt[3];
    }
    s.Q_amplitude.reset();
    s.Q_ratio = ratio;
    return s;
  };
  if (scene.blocks.empty())
    out.scenes.push_back(held(scene.Q_amplitude, scene.Q_ratio, scene.delta, scene.history));
  for (const LoadBlock& b : scene.blocks) out.scenes.push_back(held(b.Q_amplitude, b.Q_ratio, b.delta, b.history));
  return out;
}

}  // namespace

// A wearing contact grows past its original edges up to the asymptote's worn extent (PHYSICS.md, "Wear": x_e > a):
// the asymptotes of the stand-ins above, computed on a coarse, wide grid, and the widest of them taken. A stand-in
// without a limit adds nothing (a gross-slip run's widening is checked against the window before it starts,
// engine/preflight.cpp), except with a bulk stress: under force control in reverse slip (the leading edge slips
// backwards, e + c > a, Nowell and Hills 1987), and under displacement control, the limit is not established, and
// the worn contact still settles. There the stand-in's limit is taken as paper 002's is, over the stick zones of its
// first steady cycle (marched by the incremental route, CycleResult::stick_zones): a complete contact over them
// under P (contact/wear_limit.hpp); under δ it is also taken without the bulk stress (δ's asymptote), and the wider
// of the two covered. The stick zones are shorter than those of the same load without the bulk stress, and shifted,
// so the limit sits deeper and reaches further than that load's. The worn contacts of cylinders, flats with rounded
// corners and rounded wedges at f = 0.3, Q/fP = 0.6 and σ = 200–400 MPa, similar and dissimilar, of two asperities,
// and of a rounded flat under δ between dissimilar bodies end within 0.1 of its half-width of it
// (tests/regression/regression_worn_contact_outgrows_window.cpp). Where the bulk stress dwarfs the friction the
// stick zones are a few cells at the trailing edge and the contact wears on like one in gross slip, past any such
// limit: the run stops at the window's end, saying so.
std::optional<WornReach> worn_reach(const Scene& scene, const Profile& profile, double centre, double half_width) {
  constexpr int kTrialCells = 1024;
  const StandIns stand_ins = window_stand_ins(scene);
  // The stand-in's worn extent (its asymptote's and its contact zones'), or why it has none.
  const auto worn_extent = [&](const Scene& s, std::string& unavailable) -> std::optional<Interval> {
    double half = half_width;
    for (int attempt = 0;; ++attempt, half *= 2.0) {
      if (attempt == 6)
        throw InputError("grid: the asymptotic worn zone keeps reaching the end of a trial window 64 times the "
                         "contact; give grid.window");
      const double lo = centre - 2.5 * half, hi = centre + 2.5 * half;
      const Model trial = model_on(s, align_to_support(profile, lo, hi, kTrialCells), {lo, hi, "trial", 0.0});
      NormalResult normal;
      WearAsymptote a;
      try {
        normal = solve_normal(s, trial);
        a = wear_asymptote(s, trial, normal);
        unavailable = a.unavailable;
        if (a.worn_area <= 0.0 && !unavailable.empty() && s.bulk_stress != 0.0) {
          const CycleStage cycle = solve_cycle(s, trial, normal);  // over the first cycle's stick zones
          std::vector<Zone> stick(cycle.result.stick_zones.size());
          for (std::size_t k = 0; k < stick.size(); ++k)
            stick[k].left.x = cycle.result.stick_zones[k].first, stick[k].right.x = cycle.result.stick_zones[k].second;
          if (stick.empty()) return std::nullopt;
          static_cast<WearLimit&>(a) = wear_limit(trial.profile, trial.pair.A(), trial.grid, s.P, stick);
        }
      } catch (const ConvergenceError& e) {  // on a grid the user never asked for: say which, and how to skip it
        throw ConvergenceError(fmt::format("grid.window: sizing the default window for the worn contact on a trial "
                                           "grid of {} cells over [{:.6g}, {:.6g}] m: {}; give grid.window to skip "
                                           "this trial",
                                           kTrialCells, lo, hi, e.what()));
      }
      if (a.worn_area <= 0.0) return std::nullopt;
      if (a.extent.first <= trial.grid.x_min + trial.grid.h() || a.extent.second >= trial.grid.x_max - trial.grid.h())
        continue;
      return Interval{std::min(a.extent.first, normal.zones.front().left.x),
                      std::max(a.extent.second, normal.zones.back().right.x)};
    }
  };
  WornReach reach{{std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()},
                  stand_ins.itself};
  for (const Scene& s : stand_ins.scenes) {
    std::vector<Scene> tried{s};
    if (s.delta && s.bulk_stress != 0.0) {  // and δ's own asymptote without the bulk stress
      tried.push_back(s);
      tried.back().bulk_stress = 0.0;
    }
    bool limited = false;
    for (const Scene& t : tried) {
      std::string unavailable;
      const std::optional<Interval> e = worn_extent(t, unavailable);
      if (!e) continue;
      limited = true;
      reach.itself = reach.itself && unavailable.empty();
      reach.extent.first = std::min(reach.extent.first, e->first);
      reach.extent.second = std::max(reach.extent.second, e->second);
    }
    reach.every_load = reach.every_load && limited;
  }
  if (!(reach.extent.first < reach.extent.second)) return std::nullopt;
  return reach;
}

namespace {

// The window that holds a run wearing in gross slip, which has no limit: the flat that holds what the run wears,
// kFlatMargin more, with U each side where each body wears in its own frame, and 20 % to spare (contact/worn_flat.hpp,
// the same window engine/preflight.cpp advises for a given one). Each load (the scene's, or each block of load.blocks)
// is solved for one cycle on a trial grid of kTrialCells, first over the unworn contact's window w; the loads in
// partial slip wear towards a limit and add nothing here. Empty when no load slides.
// The first cycle's rate c ∫ p s dx is about c P times the slip travelled, which under δ is what the stick limit
// leaves of δ; as the contact wears flat and widens its tangential compliance falls, more of δ slides, and the wear
// speeds up (a wedge of steel on aluminium at δ = 2.34 µm, whose first cycle slides 0.96 µm each way, wore 1.9 times
// faster on average over 1.09e6 cycles: tests/regression/regression_gross_slip_default_window.cpp). So the rates are
// taken again on the original profile cut flat at the depth that holds the area (a trial grid over the window that
// holds it, and the run's displacement datum, the unworn contact's), each load at the larger of its rates, until the
// area grows by less than kSettled (at most kPasses).
std::optional<Interval> sliding_reach(const Scene& scene, const Profile& profile, const WindowChoice& w) {
  constexpr int kTrialCells = 1024, kPasses = 4;
  constexpr double kSettled = 0.05;
  // Under force control the scene is refused where Q reaches f P (the slip would not be determined), so only a load
  // under displacement control can slide.
  bool displacement = scene.blocks.empty() && scene.control == LoadControl::displacement;
  for (const LoadBlock& b : scene.blocks) displacement = displacement || b.delta.has_value();
  if (!displacement) return std::nullopt;
  std::vector<Scene> loads;
  if (scene.blocks.empty()) loads.push_back(scene);
  for (const LoadBlock& b : scene.blocks) loads.push_back(block_scene(scene, b));
  std::vector<double> rate(loads.size(), 0.0);
  double U = 0.0, reference_depth = 0.0;
  Interval contact{0.0, 0.0};  // the widest contact of the trials, unworn and worn flat (m)
  // Each load's rate on the trial grid over [lo, hi], where it slides, the profile cut flat at the gap `depth` (none:
  // the original); U from the original. False where the worn flat's contact reaches the trial grid's end.
  const auto take_rates = [&](double lo, double hi, std::optional<double> depth) {
    Model trial = model_on(scene, align_to_support(profile, lo, hi, kTrialCells), {lo, hi, "trial", 0.0});
    if (depth)
      for (double& g : trial.g0) g = std::max(g, *depth);
    try {
      const NormalResult normal = solve_normal(scene, trial);
      if (normal.zones.empty()) return false;
      const Interval here{normal.zones.front().left.x, normal.zones.back().right.x};
      contact = depth ? Interval{std::min(contact.first, here.first), std::max(contact.second, here.second)} : here;
      for (std::size_t k = 0; k < loads.size(); ++k) {
        // The run keeps the unworn contact's datum (10 of its half-widths deep unless given), whose depth sets the
        // tangential compliance, hence what of δ sticks: the flat's must not be put 10 of its own half-widths deep.
        Scene one = loads[k];
        if (depth && !one.reference_depth) one.reference_depth = reference_depth;
        const CycleStage cycle = solve_cycle(one, trial, normal);
        if (!depth) reference_depth = cycle.reference_depth;
        if (cycle.result.regime != Regime::gross_slip) continue;
        rate[k] = std::max(rate[k], estimate_wear(one, trial, cycle, /*timed=*/false).area_rate);
        if (!depth && bodies_in_own_frames(one, trial, cycle)) U = std::max(U, cycle.result.sliding_amplitude);
      }
    } catch (const ConvergenceError& e) {  // on a grid the user never asked for: say which, and how to skip it
      throw ConvergenceError(fmt::format("grid.window: sizing the default window for gross slip's worn flat on a "
                                         "trial grid of {} cells over [{:.6g}, {:.6g}] m: {}; give grid.window to "
                                         "skip this trial",
                                         kTrialCells, lo, hi, e.what()));
    } catch (const InputError&) {
      if (!depth) throw;  // the unworn contact's window is the run's too
      return false;
    }
    return true;
  };
  const auto worn = [&] {
    double area = 0.0;
    for (std::size_t k = 0; k < loads.size(); ++k) area += rate[k] * loads[k].wear->cycles;
    return (1.0 + kFlatMargin) * area;
  };
  take_rates(w.x_min, w.x_max, std::nullopt);
  double area = worn();
  if (!(area > 0.0)) return std::nullopt;
  const double h = (w.x_max - w.x_min) / kTrialCells;
  const auto holding = [&] { return window_holding(profile, area, h, U, contact.first, contact.second); };
  Interval window = holding();
  for (int pass = 1; pass < kPasses; ++pass) {
    // The flat's contact reaches past the flat's ends (a cut wedge's past its unworn contact, by more than the 20 %):
    // a trial grid 2.5 times the window's half-width each side of its centre holds it.
    const double c = 0.5 * (window.first + window.second), half = 1.25 * (window.second - window.first);
    if (!take_rates(c - half, c + half, flat_holding(profile, area, h).depth)) break;
    const double grown = worn();
    const bool settled = !(grown > (1.0 + kSettled) * area);
    if (!settled) area = grown;
    window = holding();  // and the flat's contact
    if (settled) break;
  }
  return window;
}

// The default window covers the worn contact's reach with the same margin as the contact (WornReach::covered), and
// in gross slip the flat the run wears (sliding_reach).
WindowChoice widen_for_wear(const Scene& scene, const Profile& profile, WindowChoice w) {
  const std::optional<WornReach> reach =
      worn_reach(scene, profile, 0.5 * (w.x_min + w.x_max), 0.5 * (w.x_max - w.x_min));
  std::optional<Interval> sliding;  // a load without a limit may wear in gross slip
  if (!reach || !reach->every_load) sliding = sliding_reach(scene, profile, w);
  if (!reach && !sliding) return w;
  WindowChoice out = w;
  if (reach) {
    const auto [lo, hi] = reach->covered();
    out.x_min = std::min(out.x_min, lo), out.x_max = std::max(out.x_max, hi);
    out.method += reach->itself ? "+wear_asymptote" : "+wear_stand_in";
  }
  if (sliding && (sliding->first < out.x_min || sliding->second > out.x_max)) {
    out.x_min = std::min(out.x_min, sliding->first), out.x_max = std::max(out.x_max, sliding->second);
    out.method += "+worn_flat";
  }
  return out;
}

// The wear run's stick zones are whole cells: those the first cycle's corrective contact loads, which it never wears
// (engine/wear_contacts.hpp). Its limit is a complete contact whose corners are those cells' ends, while the direct
// limit's are the located edges (contact/wear_limit.hpp); the worn area is sensitive to them (WearAsymptote, 1 % for
// a third of a cell at 1024 cells on Hertz). So a wearing scene's window is shifted and stretched by less than a cell
// to put cell boundaries on the first zone's located ends, as wear_limit() does for its own grid: the run's stick
// cells then end where the limit's corners are. Other zones' ends stay within their cells, and a window that is
// given, or aligned to the pad's corners, is kept (the warnings then say how far the run's limit is from the
// asymptote: WearAsymptote::cells_worn_area).
// Dissimilar bodies under one load have no asymptote of their own (initial_stick_zones), and their stick zone moves
// with β; as β → 0 it tends to that of the similar pair of the same compliance. Nearly similar bodies (|β| up to
// kAlignBeta, moduli a few tenths of a percent apart) have the cells aligned to its ends, so that the run tends to
// the similar one's at the limit too (β = 1.4e-7: 1.1 % apart in worn area at 10^7 cycles on 1024 cells with the
// cells where they fell, 6e-7 with them aligned). Beyond it the coupled stick zone lies elsewhere, and its cells
// where they fall.
Model align_to_stick(const Scene& scene, Model m) {
  const auto [s0, s1] = m.profile.support();
  const auto inside = [&m](double s) { return std::isfinite(s) && s > m.grid.x_min && s < m.grid.x_max; };
  if (inside(s0) || inside(s1)) return m;
  constexpr double kAlignBeta = 1e-3;
  const double beta = std::abs(m.pair.beta());
  if (beta > kAlignBeta) return m;
  const bool dissimilar = beta > 1e-12 && scene.blocks.empty() && scene.history.empty();
  InitialStick st;
  if (dissimilar) {
    Scene similar = window_stand_ins(scene).scenes.front();  // the similar pair of the same compliance
    if (similar.delta) similar.bulk_stress = 0.0;              // δ's stick zone, as its asymptote's
    st = initial_stick_zones(similar, model_on(similar, m.grid, m.window));
  } else {
    st = initial_stick_zones(scene, m);
  }
  if (st.zones.empty()) return m;
  const double l = st.zones.front().left.x, r = st.zones.front().right.x;
  const double h = (r - l) / std::max(1.0, std::round((r - l) / m.grid.h()));
  const double lo = l - std::round((l - m.grid.x_min) / h) * h;
  WindowChoice w = m.window;
  w.method += "+stick_edges";
  return model_on(scene, Grid{lo, lo + m.grid.n * h, m.grid.n}, w);
}

}  // namespace

Model make_model(const Scene& scene, int cells) {
  if (cells <= 0) cells = scene.cells;
  const Profile profile(scene.profile);
  const ElasticPair pair(scene.pad, scene.specimen, scene.plane);
  if (scene.window) {
    return model_on(scene, Grid{scene.window->first, scene.window->second, cells},
                    {scene.window->first, scene.window->second, "given", 0.0});
  }
  WindowChoice w;
  try {
    w = choose_window(profile, pair.A(), scene.P_max(), cells);  // a history's largest P too
  } catch (const InputError& e) {
    throw InputError(fmt::format("grid.window: cannot be chosen for this profile and load ({}); give grid.window, "
                                 "or check load.P and the profile's size",
                                 e.what()));
  }
  if (!scene.wear) return model_on(scene, align_to_support(profile, w.x_min, w.x_max, cells), w);
  w = widen_for_wear(scene, profile, w);
  return align_to_stick(scene, model_on(scene, align_to_support(profile, w.x_min, w.x_max, cells), w));
}

CyclicLoad cyclic_load(const Scene& scene, const ElasticPair& pair) {
  const bool displacement = scene.control == LoadControl::displacement;
  CyclicLoad load{scene.P, scene.Q_max(), *scene.friction, pair.bulk_strain(scene.bulk_stress),
                  displacement ? *scene.delta : 0.0};
  for (const auto& pt : scene.history) load.history.push_back({pt[0], pt[1], pt[2], pair.bulk_strain(pt[3])});
  return load;
}

Scene block_scene(const Scene& scene, const LoadBlock& b) {
  Scene one = scene;
  one.blocks.clear();
  one.Q_amplitude = b.Q_amplitude, one.Q_ratio = b.Q_ratio, one.delta = b.delta, one.history = b.history;
  one.control = b.delta ? LoadControl::displacement : LoadControl::force;
  if (one.wear) one.wear->cycles = b.cycles;
  return one;
}

CyclicLoad block_load(const Scene& scene, const ElasticPair& pair, const LoadBlock& b) {
  return cyclic_load(block_scene(scene, b), pair);
}

CyclePlan plan_cycle(const Scene& scene, const ElasticPair& pair) {
  CyclePlan plan;
  const bool displacement = scene.control == LoadControl::displacement;
  plan.load = cyclic_load(scene, pair);
  const bool history = !plan.load.history.empty();
  plan.asked = scene.tangential->route;
  // Dissimilar bodies (Dundurs β ≠ 0): normal and tangential problems coupled, the incremental route only.
  plan.beta = std::abs(pair.beta()) > 1e-12 ? pair.beta() : 0.0;
  if (plan.asked == TangentialRoute::analogy) {
    if (displacement || history)
      throw UnsupportedError("effects.tangential: route \"analogy\" cannot run load.control \"displacement\" or "
                             "load.history; use \"auto\" or \"incremental\"");
    if (plan.dissimilar())
      throw UnsupportedError(fmt::format("effects.tangential: route \"analogy\" needs similar bodies, and Dundurs "
                                         "beta = {:.4g}; use \"auto\" or \"incremental\"",
                                         pair.beta()));
  }
  plan.incremental_because = plan.asked == TangentialRoute::incremental ? "incremental"
                             : displacement ? "incremental (auto: displacement control)"
                             : history      ? "incremental (auto: load history)"
                             : plan.dissimilar() ? "incremental (auto: dissimilar bodies)"
                                                 : "";
  return plan;
}

Setup make_setup(const Scene& scene) {
  Setup setup{make_model(scene), std::nullopt, {}};
  if (scene.tangential) setup.cycle = plan_cycle(scene, setup.model.pair);
  setup.effects = {scene.tangential.has_value(), scene.wear.has_value(), scene.stress.has_value(),
                   scene.stress.has_value() && scene.tangential.has_value(), scene.crack.has_value(),
                   scene.life.has_value()};
  return setup;
}

}  // namespace fretwear
