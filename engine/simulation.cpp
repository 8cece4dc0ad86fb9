#include "engine/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string_view>

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

RunResult Simulation::run(const WearControl* control, const SolvedStages* solved) const {
  const auto t0 = std::chrono::steady_clock::now();
  RunResult r;
  const char* stage = "normal";  // the stage solving, named when its solve does not converge
  double reused = 0.0;  // the time of the stages taken from `solved`, spent before this call (s)
  const auto seconds_so_far = [&] { return seconds_since(t0) + reused; };
  try {
    const bool reuse_setup = solved && solved->setup;
    const std::shared_ptr<const Setup> made =
        reuse_setup ? solved->setup : std::make_shared<const Setup>(make_setup(scene_));
    if (reuse_setup) reused += solved->setup_seconds;
    const Setup& setup = *made;
    const Model& model = setup.model;
    const StopCheck stop = control ? control->stop_now : StopCheck{};
    const bool reuse = solved && solved->normal;
    r.normal = reuse ? *solved->normal : solve_normal(scene_, model);
    r.normal.peak_check = check_peak(scene_, r.normal);
    if (reuse) reused += solved->normal_seconds;
    r.timings.normal = seconds_since(t0) + reused;
    if (setup.effects.cycle) {
      stage = "tangential";
      stop_point(stop, "tangential");
      if (reuse && solved->cycle) {
        r.cycle = *solved->cycle;
        r.timings.tangential = solved->cycle_seconds;
        reused += solved->cycle_seconds;
      } else {
        r.cycle = timed(r.timings.tangential, [&] { return solve_cycle(scene_, model, *setup.cycle, r.normal, stop); });
      }
    }
    if (setup.effects.wear) {
      stage = "wear";
      const auto wear_t0 = std::chrono::steady_clock::now();
      try {
        r.wear = timed(r.timings.wear, [&] {
          return run_wear(scene_, model, r.normal, *r.cycle, control ? *control : WearControl{});
        });
      } catch (const WearNotConverged& e) {  // its records before the failure, and its time up to it
        r.wear = e.partial();
        r.timings.wear = seconds_since(wear_t0);
        throw;
      }
    }
    // A wear run stopped on request ends the run there: stress and crack would show a state it did not reach.
    const bool reached = !(r.wear && r.wear->interrupted);
    const CycleStage* cycle = r.cycle ? &*r.cycle : nullptr;
    const WearStage* wear = r.wear ? &*r.wear : nullptr;
    if (setup.effects.stress && reached) {
      stage = "stress";
      r.stress_maps = timed(r.timings.stress, [&] {
        auto maps = run_stress(scene_, model, r.normal, cycle, wear, stop);
        if (setup.effects.fatigue)  // the fatigue measures from each state's top and bottom maps
          r.fatigue =
              run_fatigue(scene_, model.grid, record_phases(scene_, r.normal, cycle, wear), maps, *cycle, wear,
                          stop);
        return maps;
      });
    }
    if (setup.effects.crack && reached) {
      stage = "crack";
      r.crack_x = crack_position(*scene_.crack, r.normal);
      r.sifs = timed(r.timings.crack, [&] {
        auto sifs = run_crack(scene_, model, r.normal, cycle, wear, stop);
        stop_point(stop, "crack");
        r.crack_quadrature = quadrature_check(scene_, model, r.normal, cycle, wear, sifs);
        return sifs;
      });
    }
    if (setup.effects.life && reached) {
      stage = "life";
      r.life = timed(r.timings.life, [&] {
        stop_point(stop, "life");
        auto life = run_life(scene_, model, r.normal, *cycle, wear, stop);
        stop_point(stop, {"life", 2.0, 2.0, "parts (initiation, growth)"});
        return life;
      });
    }
  } catch (const ConvergenceError& e) {
    // Each stage's result (and its time) is kept only once the stage completes, when timed() returns it: r holds
    // those of the stages before `stage`, and of a wear stage that failed part way what it recorded.
    std::shared_ptr<RunResult> partial;
    if (std::string_view(stage) != "normal") {
      r.timings.total = seconds_so_far();
      r.warnings = result_warnings(scene_, r);
      partial = std::make_shared<RunResult>(std::move(r));
    }
    throw StageNotConverged(e.what(), stage, std::move(partial));
  }
  r.timings.total = seconds_so_far();
  r.warnings = result_warnings(scene_, r);
  return r;
}

SingularEdges singular_edges_of(const RunResult& r) {
  return singular_edges(r.normal, r.cycle ? &*r.cycle : nullptr, r.wear ? &*r.wear : nullptr, r.stress_maps);
}

const std::vector<StageOutputs>& stage_outputs() {
  using nlohmann::json;
  static const std::vector<StageOutputs> stages = {
      {"tangential", &Timings::tangential, [](const RunResult& r) { return r.cycle.has_value(); },
       [](const Scene& s, const RunResult& r, json& j) { j["cycle"] = summarise_cycle(s, *r.cycle); },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) {
         write_cycle(s, r.normal, *r.cycle, out, w);
       }},
      {"wear", &Timings::wear, [](const RunResult& r) { return r.wear.has_value(); },
       [](const Scene& s, const RunResult& r, json& j) { j["wear"] = summarise_wear(s, *r.wear); },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) {
         write_wear(s, r.normal, *r.cycle, *r.wear, out, w);
       }},
      {"stress", &Timings::stress, [](const RunResult& r) { return !r.stress_maps.empty(); },
       [](const Scene& s, const RunResult& r, json& j) {
         j["stress"] = summarise_stress(s, r.stress_maps, r.wear ? &*r.wear : nullptr, singular_edges_of(r));
       },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) {
         write_stress(s, r.stress_maps, out, w);
       }},
      {nullptr, nullptr, [](const RunResult& r) { return r.fatigue.has_value(); },  // SWT and Ruiz, within stress
       [](const Scene&, const RunResult& r, json& j) {
         add_fatigue_summary(j["stress"], *r.fatigue, singular_edges_of(r));
       },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) {
         write_fatigue(s, r.normal, *r.cycle, *r.fatigue, out, w);
       }},
      {"crack", &Timings::crack, [](const RunResult& r) { return !r.sifs.empty(); },
       [](const Scene& s, const RunResult& r, json& j) { j["crack"] = summarise_crack(s, r.sifs, r.crack_x); },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) {
         write_crack(s, r.sifs, r.crack_x, r.wear.has_value(), out, w);
       }},
      {"life", &Timings::life, [](const RunResult& r) { return r.life.has_value(); },
       [](const Scene& s, const RunResult& r, json& j) { j["life"] = summarise_life(s, *r.life); },
       [](const Scene& s, const RunResult& r, OutputFolder& out, Written& w) { write_life(s, *r.life, out, w); }},
  };
  return stages;
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
  for (const StageOutputs& stage : stage_outputs()) {
    if (!stage.ran(result)) continue;
    if (stage.effect) {
      summary["effects_run"].push_back(stage.effect);
      timings[stage.effect] = *(result.timings.*stage.seconds);
    }
    stage.summarise(scene, result, summary);
  }
  return summary;
}

}  // namespace fretwear
