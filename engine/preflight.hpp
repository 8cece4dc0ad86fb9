// What a command can know of a scene before it solves anything, checked by `fretwear validate` too, so that a scene
// `validate` passes is not refused by `run` (docs/SCENES.md, "Output folders" and "Warnings"): the output folder;
// the window and the contact (a contact the given window clips, a window in which no cell can touch, the load–size
// integral of the default window); the strains linear elasticity allows; the route the cycle needs; the first wear
// cycle (a regime the wear stage cannot follow, a cycle that wears the contact past its elastic depth); and the wear
// run's time, refused past a day.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/warnings.hpp"

namespace fretwear {

// The largest mean contact strain p_mean / E* accepted: half-plane linear elasticity needs strains well below one
// (a contact small against the radii of the bodies: for Hertz p_mean / E* = π a / (8 R)).
inline constexpr double kMaxContactStrain = 0.05;
// The largest first-cycle wear accepted, as a fraction of the contact's elastic depth P / (2 E*) (mean depth worn
// in one cycle over it; check_wear_per_cycle in preflight.cpp): past it the contact is reshaped within a cycle.
inline constexpr double kMaxWearPerCycle = 1.0;
// Past this fraction the run goes ahead with the warning wear_per_cycle (the examples: at most 0.015).
inline constexpr double kWarnWearPerCycle = 0.1;
// Wear runs estimated to take longer than this (s) are refused, naming the stepper and what to use instead.
inline constexpr double kMaxRunSeconds = 86400.0;

// What the checks made and solved: the setup (the window, whose choice may solve trials, and the model on it), the
// normal contact, and the first cycle where the route or the wear stage needs it, with their wall times (s).
// Simulation::run takes them for the same scene rather than make and solve them again.
struct SolvedStages {
  std::shared_ptr<const Setup> setup;
  double setup_seconds = 0.0;
  std::shared_ptr<const NormalResult> normal;
  double normal_seconds = 0.0;
  std::shared_ptr<const CycleStage> cycle;  // null where the checks did not solve it
  double cycle_seconds = 0.0;
};

struct Preflight {
  std::vector<Warning> warnings;  // long_run, window_reached, wear_per_cycle
  double wear_seconds = 0.0;      // estimated wall time of the wear stage (s); 0 when short or not estimated
  double stress_seconds = 0.0;    // of the stress stage's maps, from a column timed (s); 0 without stress maps
  SolvedStages solved;            // empty when a check failed or a solve did not converge
  // Asked by the first cycle's march at each increment (a stop ends it with StopRequested); set by the caller.
  StopCheck stop;
};

// The problems of the scene's physics that show before solving (every one, as "key: what is wrong; what to do").
// Solves the normal contact, and the first cycle where the route or the wear stage needs it (kept in
// preflight->solved when the scene passes). A solve that does not
// converge is no problem of the scene's: the run reports it (exit status 3).
std::vector<std::string> physics_problems(const Scene& scene, Preflight* preflight = nullptr);

// Every check of the scene before `command` solves it: output_dir_problems(), for `run` checkpoint_problems() (the
// wear checkpoint's place beside output.dir), and physics_problems(). Throws
// SceneError listing every problem. scene_file: where the scene was read ("" for a scene built in memory). `stop`
// (Preflight::stop) is asked at each increment of a first cycle marched for `run`; a stop throws StopRequested.
Preflight preflight(const Scene& scene, const std::filesystem::path& scene_file, OutputCommand command,
                    StopCheck stop = {});

// load_scene(), and when the scene is invalid, its output folder's problems for `command` with the rest, where the
// folder could be read: every problem at once.
Scene load_scene_for(const std::filesystem::path& scene_file, OutputCommand command);

// A duration in the unit a person reads it in: "45 s", "12 min", "3.2 h", "41 days", "3.1e+04 years".
std::string duration_words(double seconds);

}  // namespace fretwear
