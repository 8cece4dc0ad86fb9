#include "engine/preflight.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <optional>

#include <fmt/format.h>

#include "contact/worn_flat.hpp"
#include "engine/checkpoint.hpp"
#include "engine/setup.hpp"
#include "engine/simulation.hpp"
#include "engine/stress_stage.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

std::string duration_words(double seconds) {
  if (seconds < 90.0) return fmt::format("{:.0f} s", seconds);
  if (seconds < 5400.0) return fmt::format("{:.0f} min", seconds / 60.0);
  if (seconds < 2.0 * 86400.0) return fmt::format("{:.1f} h", seconds / 3600.0);
  if (seconds < 730.0 * 86400.0) return fmt::format("{:.0f} days", seconds / 86400.0);
  return fmt::format("{:.3g} years", seconds / (365.25 * 86400.0));
}

namespace {

// The mean contact strain p_mean / E*, p_mean the load over the zones' total width.
void check_strain(const Scene& scene, const Model& model, const NormalResult& normal,
                  std::vector<std::string>& problems) {
  double width = 0.0;
  for (const Zone& z : normal.zones) width += z.right.x - z.left.x;
  const double p_mean = scene.P / width, strain = p_mean / model.pair.E_star();
  if (!(strain <= kMaxContactStrain))
    problems.push_back(fmt::format("load.P: the mean contact pressure P / (contact width) = {:.4g} Pa is {:.3g} times "
                                   "the composite modulus E* = {:.4g} Pa; half-plane linear elasticity needs strains "
                                   "well below one (at most {}): lower load.P, or give a larger profile",
                                   p_mean, strain, model.pair.E_star(), kMaxContactStrain));
  // The bulk stress strains the specimen by σ / E: as much beyond linear elasticity past the same bound (a GPa given
  // for a MPa, 3e11 Pa on steel, would slide the contact by a third of a millimetre).
  const double E = scene.specimen.E;
  auto check_bulk = [&](const std::string& key, double sigma) {
    if (!(std::abs(sigma) / E <= kMaxContactStrain))
      problems.push_back(fmt::format("{}: the bulk stress {:.4g} Pa is {:.3g} times the specimen's modulus E = {:.4g} "
                                     "Pa; linear elasticity needs strains well below one (at most {}): is it in Pa?",
                                     key, sigma, std::abs(sigma) / E, E, kMaxContactStrain));
  };
  check_bulk("load.bulk_stress.amplitude", scene.bulk_stress);
  auto check_history = [&](const std::string& key, const std::vector<std::array<double, 4>>& history) {
    for (std::size_t k = 0; k < history.size(); ++k)
      if (!(std::abs(history[k][3]) / E <= kMaxContactStrain)) {
        check_bulk(fmt::format("{}[{}][3]", key, k), history[k][3]);
        return;  // the first such point: the others are the same slip of units
      }
  };
  check_history("load.history", scene.history);
  for (std::size_t b = 0; b < scene.blocks.size(); ++b)
    check_history(fmt::format("load.blocks[{}].history", b), scene.blocks[b].history);
}

// A load that wears in gross slip, for the window check below: the area worn before it (m²), its first cycle's
// rate c ∫ p s dx (m²/cycle), its cycles, how far the specimen's scar reaches beyond the contact (U with each body in
// its own frame, else 0), and what names it in the message ("" for the scene's own load).
struct SlidingWear {
  double area_before = 0.0, rate = 0.0, cycles = 0.0, U = 0.0;
  std::string which;
  double left = 0.0, right = 0.0;  // the unworn contact's ends (m)
};

// In gross slip the contact wears flat without limit (contact/worn_flat.hpp), until the run's contact reaches the
// window's end and the run stops with an error (engine/wear_contacts.cpp): refused when the flat holding the worn
// area (the original profile cut flat, and U beyond it) reaches the window's end within the cycles, and warned when
// it does with kFlatMargin more wear. A window fretwear chooses holds it (engine/setup.cpp, sliding_reach), so this
// refuses given windows, and chosen ones only where the run's grid puts the rate higher than the trial's did.
void check_sliding_window(const Model& model, const SlidingWear& load, std::vector<std::string>& problems,
                          Preflight* preflight) {
  const Grid& grid = model.grid;
  const double U = load.U, area = load.area_before + load.rate * load.cycles;
  const Flat margin = flat_holding(model.profile, load.area_before + (1.0 + kFlatMargin) * load.rate * load.cycles,
                                   grid.h());
  const auto [advised_lo, advised_hi] = window_holding(model.profile, area, grid.h(), U, load.left, load.right);
  if (U > 0.0 && (load.left - U <= grid.x_min || load.right + U >= grid.x_max)) {
    // The contact and the stroke alone span past the window's end: the scar reaches it from the first cycle.
    problems.push_back(fmt::format(
        "grid.window: in gross slip{} the pad slides {:.3g} m each way over the specimen, whose scar then spans "
        "[{:.3g}, {:.3g}] m from the first cycle (the contact and the stroke each side), past the window [{:.3g}, "
        "{:.3g}] m{}. Give grid.window as about [{:.3g}, {:.3g}] m (the flat the {:.4g} cycles wear, the stroke each "
        "side, and 20 %)",
        load.which, U, load.left - U, load.right + U, grid.x_min, grid.x_max,
        model.window.method == "given" ? "" : " (fretwear's choice for the unworn contact)", advised_lo, advised_hi,
        load.cycles));
    return;
  }
  if (margin.left - U > grid.x_min && margin.right + U < grid.x_max) return;  // with the margin it fits: so does `end`
  // The cycles at which the flat (and U) reaches the nearer end of the window.
  const double d_window = std::min(model.profile.gap(grid.x_min + U), model.profile.gap(grid.x_max - U));
  const double reached = (flat_at(model.profile, d_window, grid.h()).area - load.area_before) / load.rate;
  const std::string scar =
      U > 0.0 ? fmt::format(" (with the specimen's scar, which spreads {:.3g} m further each side)", U) : "";
  const std::string what = fmt::format(
      "in gross slip{} the contact wears flat and keeps widening: at the first cycle's rate (c ∫ p s dx = {:.3g} m² a "
      "cycle{}) it{} reaches the window's end after about {:.3g} of the {:.4g} cycles (the original profile cut flat "
      "to hold the worn area; docs/SCENES.md, \"Wear\"). Widen grid.window to about [{:.3g}, {:.3g}] m (that flat "
      "after the last cycle, and 20 %), or wear fewer cycles",
      load.which, load.rate,
      load.area_before > 0.0 ? fmt::format(", after the {:.3g} m² the sliding blocks before it wear", load.area_before)
                             : "",
      scar, std::max(0.0, reached), load.cycles, advised_lo, advised_hi);
  if (reached < load.cycles)
    problems.push_back((load.which.empty() ? "effects.wear.cycles: " : "load.blocks: ") + what);
  else if (preflight)
    preflight->warnings.push_back({"window_reached", "the worn contact may reach the window's end: " + what});
}

void check_gross_slip_window(const Scene& scene, const Model& model, const NormalResult& normal,
                             const CycleStage& cycle, const WearEstimate& e, std::vector<std::string>& problems,
                             Preflight* preflight) {
  if (cycle.result.regime != Regime::gross_slip || !scene.blocks.empty() || !(e.area_rate > 0.0)) return;
  const double left = normal.zones.front().left.x, right = normal.zones.back().right.x;
  // With each body in its own frame the specimen's scar reaches the sliding amplitude U beyond the contact.
  const double U = bodies_in_own_frames(scene, model, cycle) ? cycle.result.sliding_amplitude : 0.0;
  check_sliding_window(model, {0.0, e.area_rate, scene.wear->cycles, U, "", left, right}, problems, preflight);
}

// A given window that the worn contact's reach (worn_reach, engine/setup.hpp: its asymptote, or a stand-in's) passes
// is warned: the run stops with exit status 2 if its worn contact gets to the window's end, which depends on how
// near the limit its cycles take it. Gross slip has no limit and is checked above. Where the trial cannot place the
// limit (it does not converge, or keeps reaching the trial grid's end) nothing is said: a given window skips the
// trial that sizes a default one, and its scene is not refused for it; the run says what it meets.
void check_worn_reach_window(const Scene& scene, const Model& model, Preflight* preflight) {
  if (!preflight || !scene.window) return;
  const Grid& g = model.grid;
  std::optional<WornReach> reach;
  try {
    reach = worn_reach(scene, model.profile, 0.5 * (g.x_min + g.x_max), 0.5 * (g.x_max - g.x_min));
  } catch (const ConvergenceError&) {
    return;
  } catch (const InputError&) {
    return;
  }
  if (!reach) return;
  const auto [l, r] = reach->extent;
  if (l > g.x_min + g.h() && r < g.x_max - g.h()) return;
  const auto [lo, hi] = reach->covered();
  preflight->warnings.push_back(
      {"window_reached",
       fmt::format("the worn contact may reach the window's end: it tends to [{:.6g}, {:.6g}] m ({}; docs/SCENES.md, "
                   "\"Wear\"), past grid.window [{:.6g}, {:.6g}] m, and the run stops with exit status 2 if it gets "
                   "there before its last cycle: give grid.window about [{:.3g}, {:.3g}] m (that extent with half its "
                   "half-width to spare), or leave it out to have it chosen",
                   l, r,
                   reach->itself ? "the worn extent of its asymptote" : "the worn extent of a stand-in's asymptote",
                   g.x_min, g.x_max, std::min(g.x_min, lo), std::max(g.x_max, hi))});
}

// One cycle's wear against the contact's elastic depth: the cycle-averaged wear model holds the contact fixed
// through a cycle and wears it between cycles (paper 002, §3), which needs a cycle's wear to move the pressure
// little. A smooth change δw of the worn profile over a contact of width W moves its pressure by about E* δw / (W/2),
// so the ratio of the first cycle's mean wear depth (c ∫ p s dx) / W to the contact's elastic depth
// (W/2) p_mean / E* = P / (2 E*) is the fraction of the pressure one cycle's wear changes. Past kMaxWearPerCycle the
// contact would be reshaped within one cycle (the wear run would reach its limit, or wear flat, in a fraction of a
// cycle): refused, naming the coefficient; past kWarnWearPerCycle, the warning wear_per_cycle. The mean over the
// whole contact is the lenient measure (partial slip concentrates the wear in the slip zones), so a refused scene is
// beyond doubt.
void check_wear_per_cycle(const Scene& scene, const Model& model, const NormalResult& normal, const WearEstimate& e,
                          const std::string& block, std::vector<std::string>& problems, Preflight* preflight) {
  double width = 0.0, P = 0.0;
  for (const Zone& z : normal.zones) width += z.right.x - z.left.x;
  for (double p : normal.state.p) P += p * normal.grid.h();  // the normal contact's load (a history's at its start)
  if (!(width > 0.0) || !(P > 0.0) || !(e.area_rate > 0.0)) return;
  const double depth = e.area_rate / width, elastic = P / (2.0 * model.pair.E_star()), ratio = depth / elastic;
  const WearEffect& effect = *scene.wear;
  const double c = wear::WearLaw{effect.law, effect.coefficient, *scene.friction}.rate_coefficient();
  const std::string worn =
      fmt::format("one cycle{} wears the contact {:.3g} m deep on average (c ∫ p s dx / width, c = {:.3g} 1/Pa), "
                  "{:.3g} times its elastic depth P / (2 E*) = {:.3g} m",
                  block, depth, c, ratio, elastic);
  if (ratio <= kWarnWearPerCycle) return;
  if (ratio <= kMaxWearPerCycle) {
    if (preflight)
      preflight->warnings.push_back(
          {"wear_per_cycle", worn + ": the pressure moves by about that fraction within a cycle, which the "
                             "cycle-averaged wear model holds fixed, so the first cycles' wear is approximate"});
    return;
  }
  const std::string coefficient = effect.law == wear::Law::archard ? "k" : "alpha";
  const std::string key = effect.per_body ? fmt::format("effects.wear.{0}_pad and {0}_specimen", coefficient)
                                          : "effects.wear." + coefficient;
  problems.push_back(fmt::format(
      "{}: {}: the contact would be reshaped within a single cycle, and the cycle-averaged wear model (the contact "
      "held through a cycle, worn between cycles) needs a cycle's wear to be small beside that depth. Is the "
      "coefficient in 1/Pa? (measured ones are about 1e-20 to 1e-12 1/Pa)",
      key, worn));
}

// Under load.blocks, each block, in order: its own cycle and first rate on the unworn contact, checked as the scene's
// first cycle is (check_wear_per_cycle); and each block that slides, after the area the sliding blocks before it
// wear at theirs. Blocks in partial slip wear towards a limit and are left out
// (the check may then pass a window they narrow; the run says so when the scar reaches the window's end).
void check_blocks_window(const Scene& scene, const Model& model, const NormalResult& normal,
                         std::vector<std::string>& problems, Preflight* preflight) {
  double area = 0.0;
  for (std::size_t b = 0; b < scene.blocks.size(); ++b) {
    const LoadBlock& block = scene.blocks[b];
    const Scene one = block_scene(scene, block);
    const CycleStage cycle = solve_cycle(one, model, normal);
    if (cycle.result.slip_travelled.empty()) continue;
    const WearEstimate e = estimate_wear(one, model, cycle, /*timed=*/false);
    if (b > 0) {  // the first block's cycle is the scene's, checked already
      const std::size_t before = problems.size();
      check_wear_per_cycle(one, model, normal, e, fmt::format(" of load.blocks[{}]", b), problems, preflight);
      if (problems.size() > before) return;
    }
    if (cycle.result.regime != Regime::gross_slip || !(e.area_rate > 0.0)) continue;
    const double U = bodies_in_own_frames(one, model, cycle) ? cycle.result.sliding_amplitude : 0.0;
    const std::size_t before = problems.size();
    check_sliding_window(model,
                         {area, e.area_rate, block.cycles, U, fmt::format(" (load.blocks[{}])", b),
                          normal.zones.front().left.x, normal.zones.back().right.x},
                         problems,
                         preflight);
    if (problems.size() > before) return;  // the later blocks start beyond the window
    area += e.area_rate * block.cycles;
  }
}

// The wear run's cost from its first cycle: refused past kMaxRunSeconds, a warning past kLongRunSeconds.
void check_wear(const Scene& scene, const Setup& setup, const NormalResult& normal, const CycleStage& cycle,
                std::vector<std::string>& problems, Preflight* preflight) {
  const WearEffect& effect = *scene.wear;
  const WearEstimate e = estimate_wear(scene, setup.model, cycle);
  const std::size_t before = problems.size();
  check_wear_per_cycle(scene, setup.model, normal, e, scene.blocks.empty() ? "" : " of load.blocks[0]", problems,
                       preflight);
  if (problems.size() > before) return;  // the window and the cost follow from a rate that is not the model's
  check_gross_slip_window(scene, setup.model, normal, cycle, e, problems, preflight);
  if (!scene.blocks.empty()) check_blocks_window(scene, setup.model, normal, problems, preflight);
  check_worn_reach_window(scene, setup.model, preflight);
  if (effect.stepper == WearStepper::cycle_by_cycle) {
    if (const std::string problem = cycle_by_cycle_problem(e.stability_limit); !problem.empty()) {
      problems.push_back(problem);
      return;
    }
  }
  const double t = e.seconds();
  const std::string estimate =
      fmt::format("{:.4g} cycles with stepper \"{}\" take about {} ({:.4g} cycle solves of {:.3g} ms each{})",
                  effect.cycles, to_string(effect.stepper), duration_words(t), e.responses, 1e3 * e.seconds_per_response,
                  effect.stepper == WearStepper::explicit_capped
                      ? fmt::format(", steps capped below the stability limit of {:.4g} cycles", e.stability_limit)
                      : std::string());
  if (t > kMaxRunSeconds) {
    problems.push_back(fmt::format("effects.wear.cycles: {}; fretwear refuses a run estimated past a day: use stepper "
                                   "\"implicit\" (a few hundred solves for any number of cycles), or fewer cycles",
                                   estimate));
    return;
  }
  if (!preflight) return;
  preflight->wear_seconds = t;
  if (t > kLongRunSeconds)
    preflight->warnings.push_back({"long_run", estimate + "; stepper \"implicit\" takes a few hundred solves"});
}

// The stress stage's cost (Preflight::stress_seconds): a column of the map timed on the unworn contact, under each
// phase's tractions, times the columns of every state's maps (the earlier records' at every kRecordStride-th point
// across and in depth). A worn contact is wider, its columns dearer: the estimate is a lower bound of the order.
void estimate_stress(const Scene& scene, const NormalResult& normal, Preflight& preflight) {
  const StressEffect& effect = *scene.stress;
  const std::vector<Phase> phases = cycle_phases(scene, normal.state.p, nullptr);
  std::vector<double> y;
  for (int j = 0; j <= effect.ny; ++j) y.push_back(j * 1e-6);
  const double x = 0.5 * (normal.zones.front().left.x + normal.zones.back().right.x);
  const auto t0 = std::chrono::steady_clock::now();
  int columns = 0;
  do {  // at least a few milliseconds, so that the clock resolves the column
    for (const Phase& ph : phases) (void)stress_along_depth({normal.grid, ph.p, ph.q, ph.sigma_bulk}, x, y);
    ++columns;
  } while (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < 5e-3 && columns < 64);
  const double per_column = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / columns;
  const double records = scene.wear ? double(std::max<std::size_t>(scene.wear->record.size(), 1)) : 0.0;
  const double full = double(effect.nx), earlier = records * std::ceil(full / kRecordStride) *
                                                   std::ceil((effect.ny + 1.0) / kRecordStride) / (effect.ny + 1.0);
  preflight.stress_seconds = per_column * (full + earlier);
}

}  // namespace

std::vector<std::string> physics_problems(const Scene& scene, Preflight* preflight) {
  std::vector<std::string> problems;
  try {
    SolvedStages solved;
    auto t0 = std::chrono::steady_clock::now();
    solved.setup = std::make_shared<const Setup>(make_setup(scene));
    const Setup& setup = *solved.setup;
    solved.setup_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    t0 = std::chrono::steady_clock::now();
    const auto normal = std::make_shared<const NormalResult>(solve_normal(scene, setup.model));
    solved.normal_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    solved.normal = normal;
    if (setup.model.window.method.find("+worn_flat") == std::string::npos) {
      check_strain(scene, setup.model, *normal, problems);
    } else {
      // A window widened for gross slip's worn flat may leave the unworn contact a few cells, whose width, and so its
      // strain, is then the grid's: the strain is that of the unworn contact on its own window, as without wear.
      Scene unworn = scene;
      unworn.wear.reset();
      const Model own = make_model(unworn, setup.model.grid.n);
      check_strain(scene, own, solve_normal(scene, own), problems);
    }
    if (!problems.empty()) return problems;
    // The analogy route refuses a cycle it cannot follow (reverse slip) only once it has solved it; the wear run's
    // cost is estimated from the first cycle.
    if (setup.cycle && (setup.cycle->asked == TangentialRoute::analogy || setup.effects.wear)) {
      t0 = std::chrono::steady_clock::now();
      solved.cycle = std::make_shared<const CycleStage>(solve_cycle(scene, setup.model, *setup.cycle, *normal,
                                                                         preflight ? preflight->stop : StopCheck{}));
      solved.cycle_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    if (setup.effects.wear) check_wear(scene, setup, *normal, *solved.cycle, problems, preflight);
    if (setup.effects.stress && preflight && !normal->zones.empty()) estimate_stress(scene, *normal, *preflight);
    if (preflight && problems.empty()) preflight->solved = std::move(solved);
  } catch (const ConvergenceError&) {
    // Not the scene's problem: the run reports it, with what it solved, and exits with status 3.
  } catch (const InputError& e) {
    problems.push_back(e.what());
  }
  return problems;
}

Scene load_scene_for(const std::filesystem::path& scene_file, OutputCommand command) {
  try {
    return load_scene(scene_file);
  } catch (const SceneError& e) {
    if (!e.output_dir) throw;
    std::vector<std::string> problems = e.problems();
    const std::vector<std::string> more = output_dir_problems(*e.output_dir, scene_file, command);
    if (more.empty()) throw;
    problems.insert(problems.end(), more.begin(), more.end());
    throw SceneError(std::move(problems));
  }
}

Preflight preflight(const Scene& scene, const std::filesystem::path& scene_file, OutputCommand command,
                    StopCheck stop) {
  Preflight result;
  result.stop = std::move(stop);
  std::vector<std::string> problems = output_dir_problems(scene, scene_file, command);
  if (problems.empty() && command == OutputCommand::run) problems = checkpoint_problems(scene);
  const std::vector<std::string> physics =
      physics_problems(scene, command == OutputCommand::run ? &result : nullptr);
  problems.insert(problems.end(), physics.begin(), physics.end());
  if (!problems.empty()) throw SceneError(std::move(problems));
  return result;
}

}  // namespace fretwear
