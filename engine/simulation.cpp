#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include <fmt/format.h>

#include "engine/fatigue_stage.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

namespace {

// Runs `stage` and adds its wall time to `seconds`.
template <typename Stage>
auto timed(std::optional<double>& seconds, Stage stage) {
  const auto t0 = std::chrono::steady_clock::now();
  auto result = stage();
  seconds = seconds_since(t0);
  return result;
}

}  // namespace

RunResult Simulation::run(const WearControl* control) const {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult r;
  const Model model = make_model(scene_);
  r.normal = solve_normal(scene_, model);
  r.timings.normal = seconds_since(t0);
  if (scene_.tangential)
    r.cycle = timed(r.timings.tangential, [&] { return solve_cycle(scene_, model, r.normal); });
  if (scene_.wear)
    r.wear = timed(r.timings.wear,
                   [&] { return run_wear(scene_, model, r.normal, *r.cycle, control ? *control : WearControl{}); });
  // A wear run stopped on request ends the run there: stress and crack would show a state it did not reach.
  const bool reached = !(r.wear && r.wear->interrupted);
  const CycleStage* cycle = r.cycle ? &*r.cycle : nullptr;
  const WearStage* wear = r.wear ? &*r.wear : nullptr;
  if (scene_.stress && reached)
    r.stress_maps = timed(r.timings.stress, [&] {
      auto maps = run_stress(scene_, model, r.normal, cycle, wear);
      if (cycle)  // the fatigue measures from the maps' top and bottom
        r.fatigue = run_fatigue(scene_, model.grid, final_phases(scene_, r.normal, cycle, wear).front(), maps,
                                *cycle, wear);
      return maps;
    });
  if (scene_.crack && reached) {
    r.crack_x = crack_position(*scene_.crack, r.normal);
    r.sifs = timed(r.timings.crack, [&] { return run_crack(scene_, model, r.normal, cycle, wear); });
  }
  r.timings.total = seconds_since(t0);
  r.warnings = result_warnings(scene_, r);
  return r;
}

nlohmann::json make_summary(const Scene& scene, const RunResult& result) {
  using nlohmann::json;
  json summary = summarise_normal(scene, result.normal);
  summary["scene"] = scene.name;
  summary["version"] = kVersion;
  summary["status"] = result.wear && result.wear->interrupted ? "interrupted" : "completed";
  summary["effects_run"] = {"normal"};
  json& timings = summary["timings"] = {{"total", result.timings.total}, {"normal", result.timings.normal}};
  summary["warnings"] = json::array();
  for (const Warning& w : result.warnings) summary["warnings"].push_back({{"code", w.code}, {"message", w.message}});
  if (scene.tangential_implied) summary["effects_implied"] = {{"tangential", "needed by wear"}};
  // Each stage that ran: its name in effects_run, its time, its part.
  auto add = [&](const char* effect, const std::optional<double>& seconds, const char* key, json part) {
    summary["effects_run"].push_back(effect);
    timings[effect] = *seconds;
    summary[key] = std::move(part);
  };
  const WearStage* wear = result.wear ? &*result.wear : nullptr;
  if (result.cycle) add("tangential", result.timings.tangential, "cycle", summarise_cycle(scene, *result.cycle));
  if (!result.stress_maps.empty()) {
    add("stress", result.timings.stress, "stress", summarise_stress(scene, result.stress_maps, wear));
    if (result.fatigue) add_fatigue_summary(summary["stress"], *result.fatigue);
  }
  if (!result.sifs.empty())
    add("crack", result.timings.crack, "crack", summarise_crack(scene, result.sifs, result.crack_x));
  if (wear) add("wear", result.timings.wear, "wear", summarise_wear(scene, *wear));
  return summary;
}

}  // namespace fretwear
