#include "engine/preflight.hpp"

#include <cmath>

#include <fmt/format.h>

#include "engine/simulation.hpp"
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
}

// The wear run's cost from its first cycle: refused past kMaxRunSeconds, a warning past kLongRunSeconds.
void check_wear(const Scene& scene, const Setup& setup, const NormalResult& normal, std::vector<std::string>& problems,
                Preflight* preflight) {
  const WearEffect& effect = *scene.wear;
  const WearEstimate e =
      estimate_wear(scene, setup.model, solve_cycle(scene, setup.model, *setup.cycle, normal));
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

}  // namespace

std::vector<std::string> physics_problems(const Scene& scene, Preflight* preflight) {
  std::vector<std::string> problems;
  try {
    const Setup setup = make_setup(scene);
    const NormalResult normal = solve_normal(scene, setup.model);
    check_strain(scene, setup.model, normal, problems);
    if (!problems.empty()) return problems;
    // The analogy route refuses a cycle it cannot follow (reverse slip) only once it has solved it.
    if (setup.cycle && setup.cycle->asked == TangentialRoute::analogy)
      solve_cycle(scene, setup.model, *setup.cycle, normal);
    if (setup.effects.wear) check_wear(scene, setup, normal, problems, preflight);
  } catch (const ConvergenceError&) {
    // Not the scene's problem: the run reports it, with what it solved, and exits with status 3.
  } catch (const InputError& e) {
    problems.push_back(e.what());
  }
  return problems;
}

Preflight preflight(const Scene& scene, const std::filesystem::path& scene_file, OutputCommand command) {
  Preflight result;
  std::vector<std::string> problems = output_dir_problems(scene, scene_file, command);
  const std::vector<std::string> physics =
      physics_problems(scene, command == OutputCommand::run ? &result : nullptr);
  problems.insert(problems.end(), physics.begin(), physics.end());
  if (!problems.empty()) throw SceneError(std::move(problems));
  return result;
}

}  // namespace fretwear
