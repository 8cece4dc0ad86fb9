// fretwear: the command line. Exit status 0 done, 2 invalid scene (nothing written), 3 a solver did not converge,
// 130 / 143 a run stopped by SIGINT (Ctrl-C) / SIGTERM (a wear run: what was recorded is written, and a checkpoint;
// another stage: nothing written; while the results were written: they are written whole first).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string_view>
#include <thread>
#include <utility>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/api.hpp"
#include "engine/checkpoint.hpp"
#include "engine/convergence.hpp"
#include "engine/deferred_signals.hpp"
#include "engine/folder.hpp"
#include "engine/output.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/sweep.hpp"
#include "engine/sweep_mpi.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"

namespace {

using namespace fretwear;

constexpr int kExitInvalid = 2;
constexpr int kExitNoConvergence = 3;
constexpr int kExitSignal = 128;  // + the signal's number: 130 SIGINT, 143 SIGTERM
// Stress maps of more points than this, all maps of all records together, are announced before they are written.
constexpr std::size_t kLargeMapPoints = 500000;

volatile std::sig_atomic_t g_signal = 0;

extern "C" void on_signal(int sig) { g_signal = sig; }

// SIGINT and SIGTERM ask the run to stop: a wear run at its next step boundary, with what it reached written; any
// other stage at its next part (WearControl::stop_now), with nothing written; once the stages are done, after their
// results are written whole. A second one ends the program at once (SA_RESETHAND: the default action), the last
// checkpoint kept, except while results are put in place, which it waits for (DeferredStopSignals).
void catch_stop_signals() {
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = SA_RESETHAND;
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

// A stop that arrived once the stages were done, while their results were written (or just before): it waited for
// them, so they are whole in output.dir; the run ends as stopped all the same, with 128 + the signal's number.
int stopped_after_writing(const Scene& scene) {
  std::cerr << fmt::format("fretwear: {}: stopped by signal {} after the results were written; they are complete in "
                           "{}/\n",
                           scene.name, int(g_signal), scene.output_dir.string());
  return kExitSignal + int(g_signal);
}

std::string clock_time(double seconds) {
  if (!(seconds < 1e7)) return "--";  // past 100 days (or not a number): no estimate worth printing
  const long s = std::lround(std::max(0.0, seconds));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60) : fmt::format("{}:{:02}", s / 60, s % 60);
}

// Progress of a run on stderr: the wear stage's cycles, and the parts of the stress, crack and life stages that run
// longer than a few seconds. On a terminal one line, rewritten in place at most four times a second; elsewhere (a log,
// a batch job) a line each time another tenth of the stage is done, or a minute has passed.
class ProgressLine {
 public:
  // quiet_stage: how long a stage runs before its parts are shown (s).
  ProgressLine(bool enabled, bool terminal, double quiet_stage = 2.0)
      : enabled_(enabled), terminal_(terminal), quiet_stage_(quiet_stage) {}
  ~ProgressLine() { finish(); }
  bool enabled() const { return enabled_; }

  void update(const WearProgress& p) {
    const auto now = clock::now();
    if (!first_) first_ = std::pair{now, p.cycles};
    if (!due(now, p.cycles / p.total, p.cycles >= p.total)) return;
    const double elapsed = std::chrono::duration<double>(now - first_->first).count();
    const double done = p.cycles - first_->second;  // in this process (a resumed run started part way)
    std::string left = "--";
    if (done > 0.0 && elapsed > 0.0) left = clock_time((p.total - p.cycles) * elapsed / done);
    // The share of the asymptote's worn area, where there is one (0 without: displacement control, dissimilar
    // bodies, histories).
    const std::string limit = p.fraction > 0.0 ? fmt::format(", {:.1f}% of the limit", 100.0 * p.fraction) : "";
    const std::string block = p.block >= 0 ? fmt::format(" (load.blocks[{}] of {})", p.block, p.blocks) : "";
    const std::string line = fmt::format("wear: {:.0f} / {:.0f} cycles{}, ΔN {:.3g}{}, {} elapsed, ~{} left", p.cycles,
                                         p.total, block, p.dN, limit, clock_time(elapsed), left);
    show(line);
  }

  // A stage's parts (StagePart), once it has run for quiet_stage_: a short stage says nothing.
  void update(const StagePart& p) {
    if (p.total <= 0.0) return;
    const auto now = clock::now();
    if (stage_ != p.stage || unit_ != p.unit) {  // a new stage or part of one: its own line, its own clock
      finish();
      stage_ = p.stage;
      unit_ = p.unit;
      stage_start_ = now;
      tenth_ = -1;
    }
    const double elapsed = std::chrono::duration<double>(now - stage_start_).count();
    if (elapsed < quiet_stage_ || !due(now, p.done / p.total, p.done >= p.total)) return;
    const std::string left = p.done > 0.0 ? clock_time((p.total - p.done) * elapsed / p.done) : "--";
    show(fmt::format("{}: {:.0f} / {:.0f} {}, {} elapsed, ~{} left", p.stage, p.done, p.total, p.unit,
                     clock_time(elapsed), left));
  }

  void finish() {
    if (shown_ && terminal_) std::cerr << "\n" << std::flush;
    shown_ = false;
  }

 private:
  using clock = std::chrono::steady_clock;

  // Whether to show the line now, at `share` of the stage done (`last`: all of it).
  bool due(clock::time_point now, double share, bool last) {
    const int tenth = int(std::floor(10.0 * share));
    if (terminal_) {
      if (shown_ && now - last_ < std::chrono::milliseconds(250) && !last) return false;
    } else if (shown_ && tenth <= tenth_ && now - last_ < std::chrono::minutes(1)) {
      return false;
    }
    last_ = now;
    tenth_ = tenth;
    return true;
  }
  void show(const std::string& line) {
    shown_ = true;
    std::cerr << (terminal_ ? "\r\033[K" + line : line + "\n") << std::flush;
  }

  bool enabled_, terminal_, shown_ = false;
  double quiet_stage_;
  int tenth_ = -1;
  clock::time_point last_{};
  std::optional<std::pair<clock::time_point, double>> first_;
  std::string stage_, unit_;  // the stage whose parts are shown, and what they count ("": the wear stage or none)
  clock::time_point stage_start_{};
};

// Each warning on its own line on stderr (also with --quiet: a result the grid cannot resolve is never silent).
void print_warnings(const std::vector<Warning>& warnings) {
  for (const Warning& w : warnings) std::cerr << "warning: " << w.code << ": " << w.message << "\n";
}

// What a run found, on stdout: one line per stage that ran; --verbose adds how each stage was solved (against the
// closed form, window, iterations, timings) and where the results are.
void print_report(const Scene& scene, const RunResult& result, const nlohmann::json& summary, bool verbose) {
  auto v = [](const nlohmann::json& j) { return j.get<double>(); };
  const auto& c = summary["contact"];
  // Intervals [l, r] in m, each zone of a list on its own.
  auto zones = [&v](const nlohmann::json& list) {
    std::string out;
    for (const auto& z : list) out += fmt::format("{}[{:.6e}, {:.6e}]", out.empty() ? "" : ", ", v(z[0]), v(z[1]));
    return out + " m";
  };
  // At a singular edge p_max is its cell's share of an unbounded pressure, which grows with the grid: said so.
  const std::string p_max = fmt::format("p_max {:.6e} Pa{}", v(c["p_max"]),
                                        c.value("p_max_singular", false) ? " at a singular edge (a grid measure)" : "");
  if (c["zones"].size() > 1)
    std::cout << fmt::format("{}: contact in {} zones {}, {} ({})\n", scene.name, c["zones"].size(),
                             zones(c["zones"]), p_max, result.normal.summary.brief());
  else
    std::cout << fmt::format("{}: contact [{:.6e}, {:.6e}] m in 1 zone, {} ({})\n", scene.name, v(c["extent"][0]),
                             v(c["extent"][1]), p_max, result.normal.summary.brief());
  if (verbose) {
    const auto& g = summary["grid"];
    std::cout << fmt::format("  grid: {} cells of {:.4e} m over [{:.6e}, {:.6e}] m (window from {})\n",
                             g["cells"].get<int>(), v(g["h"]), v(g["window"][0]), v(g["window"][1]),
                             g["window_method"].get<std::string>());
    if (c.contains("closed_form"))
      std::cout << fmt::format("  against the closed form ({}): extent {:.2e}, p_max {:.2e}, rms {:.2e}\n",
                               c["closed_form"]["kind"].get<std::string>(), v(c["closed_form"]["extent_error"]),
                               v(c["closed_form"]["p_max_error"]), v(c["closed_form"]["rms_error"]));
  }
  if (summary.contains("cycle")) {
    const auto& cy = summary["cycle"];
    std::cout << fmt::format("  cycle ({}, {} route): Q/fP = {:.4g}", cy["regime"].get<std::string>(),
                             cy["route"].get<std::string>(), v(cy["Q_over_fP"]));
    if (!cy["stick_zone"].is_null())
      std::cout << fmt::format(", stick zone{} {}, slip range {:.4e} m, energy {:.4e} J/m",
                               cy["stick_zones"].size() > 1 ? "s" : "", zones(cy["stick_zones"]), v(cy["slip_max"]),
                               v(cy["dissipated_energy"]));
    if (cy.contains("message")) std::cout << "\n  " << cy["message"].get<std::string>();
    std::cout << "\n";
  }
  if (summary.contains("wear")) {
    const auto& w = summary["wear"];
    const std::string share = w["fraction_of_asymptote"].is_number()
                                  ? fmt::format(" ({:.1f} % of the asymptote)", 100.0 * v(w["fraction_of_asymptote"]))
                                  : std::string(" (no asymptote: see wear.asymptote_note)");
    std::cout << fmt::format("  wear ({}, {} stepper, {} route): {:.4g} cycles in {} steps; worn area {:.4e} m²{}, "
                             "max depth {:.4e} m",
                             w["law"].get<std::string>(), w["stepper"].get<std::string>(),
                             w["route"].get<std::string>(), v(w["cycles_reached"]),
                             w["steps"].get<long>(), v(w["worn_area"]), share, v(w["max_depth"]));
    if (w["stick_zones_initial"].size() > 1 || w["stick_zones_final"].size() > 1)
      std::cout << fmt::format("; stick zones {} at the first record, {} at the last", zones(w["stick_zones_initial"]),
                               zones(w["stick_zones_final"]));
    else if (!w["stick_zone_initial"].is_null() && !w["stick_zone_final"].is_null())
      std::cout << fmt::format("; stick zone [{:.6e}, {:.6e}] m at the first record, [{:.6e}, {:.6e}] m at the last",
                               v(w["stick_zone_initial"][0]), v(w["stick_zone_initial"][1]),
                               v(w["stick_zone_final"][0]), v(w["stick_zone_final"][1]));
    std::cout << "\n";
    // In its own frame each body's scar has its own depth and extent (gross slip): the one line above cannot say both.
    if (w.contains("bodies") && w["bodies"]["frames"] == "own") {
      const auto& b = w["bodies"];
      std::cout << fmt::format("  each body in its own frame ({} positions over the stroke{}): pad {:.4e} m deep over "
                               "[{:.6e}, {:.6e}] m, specimen {:.4e} m deep over [{:.6e}, {:.6e}] m\n",
                               b["positions"].get<int>(),
                               b["directions"].get<int>() == 2 ? ", each way: the shear moves the pressure" : "",
                               v(b["pad"]["max_depth"]), v(b["pad"]["extent"][0]),
                               v(b["pad"]["extent"][1]), v(b["specimen"]["max_depth"]), v(b["specimen"]["extent"][0]),
                               v(b["specimen"]["extent"][1]));
    }
    if (verbose) {
      const auto& as = w["asymptote"];
      if (as.is_object())
        std::cout << fmt::format("  wear asymptote (computed directly): worn area {:.4e} m², max depth {:.4e} m at "
                                 "x = {:.4e} m, worn extent [{:.6e}, {:.6e}] m\n",
                                 v(as["worn_area"]), v(as["max_depth"]), v(as["x_max_depth"]), v(as["extent"][0]),
                                 v(as["extent"][1]));
      else
        std::cout << "  wear asymptote: none; " << w["asymptote_note"].get<std::string>() << "\n";
      if (w.contains("implicit_solves"))
        std::cout << fmt::format("  wear steps: {} accepted, {} rejected; {} implicit and {} cycle solves ({:.1f} and "
                                 "{:.1f} iterations each); explicit stability limit {:.4g} cycles per step\n",
                                 w["steps"].get<long>(), w["rejected_steps"].get<long>(),
                                 w["implicit_solves"].get<long>(), w["cycle_solves"].get<long>(),
                                 v(w["mean_iterations_implicit"]), v(w["mean_iterations_cycle"]),
                                 v(w["explicit_stability_limit"]));
      if (w.contains("coupling")) {
        const auto& cp = w["coupling"];
        std::cout << fmt::format("  wear coupling (dissimilar bodies): {} cycle responses, {} coupled ({} of them "
                                 "half a cycle mirrored), {} by the lagged correction\n",
                                 cp["responses"].get<long>(), cp["coupled"].get<long>(), cp["mirrored"].get<long>(),
                                 cp["lagged"].get<long>());
      }
    }
  }
  if (summary.contains("stress") && summary["stress"].contains("phases") &&
      summary["stress"]["phases"].contains("top")) {
    const auto& top = summary["stress"]["phases"]["top"];
    std::cout << fmt::format("  stress at the top of the cycle: surface σxx peaks at {:.4e} Pa at x = {:.4e} m on the "
                             "trailing side; von Mises max {:.4e} Pa\n",
                             v(top["surface_sxx_trailing_peak"]), v(top["surface_sxx_trailing_peak_x"]),
                             v(top["von_mises_max"]));
  }
  if (summary.contains("crack")) {
    const auto& k = summary["crack"];
    const auto& lengths = k["lengths"];
    const std::size_t last = lengths.size() - 1;
    std::cout << fmt::format("  crack at x = {:.4e} m: {} lengths; at l = {:.4e} m K_I {:.4e} (top) / {:.4e} "
                             "(bottom) Pa·m^0.5, K_II {:.4e} / {:.4e}\n",
                             v(k["x"]), lengths.size(), v(lengths[last]), v(k["K_I_max"][last]), v(k["K_I_min"][last]),
                             v(k["K_II_max"][last]), v(k["K_II_min"][last]));
  }
  if (summary.contains("life")) {
    const auto& l = summary["life"];
    auto count = [&v](const nlohmann::json& n) { return n.is_null() ? std::string("never") : fmt::format("{:.4g}", v(n)); };
    // A run out has no total: it lasts beyond the cycles the scene looks at.
    std::string line = l["total_cycles"].is_null()
                           ? fmt::format("  life ({}): beyond {:.4g} cycles (effects.life.cycles_max)",
                                         l["fate"].get<std::string>(), v(l["cycles_max"]))
                           : fmt::format("  life ({}): total {} cycles", l["fate"].get<std::string>(),
                                         count(l["total_cycles"]));
    if (l.contains("initiation"))
      line += fmt::format("; initiation after {} cycles at x = {:.4e} m (SWT {:.4g} Pa, {} method)",
                          count(l["initiation"]["cycles"]), v(l["initiation"]["x"]), v(l["initiation"]["swt"]),
                          l["initiation"]["method"].get<std::string>());
    if (l.contains("propagation"))
      line += fmt::format("; growth {} cycles to {:.4e} m", count(l["propagation"]["cycles"]), v(l["final_length"]));
    std::cout << line << "\n";
  }
  if (verbose && summary.contains("timings")) {
    std::cout << "  timings (s):";
    for (const auto& [stage, t] : summary["timings"].items()) std::cout << fmt::format(" {} {:.3g}", stage, v(t));
    std::cout << "\n";
  }
  if (verbose && summary.contains("plots")) {
    std::cout << "  plots:";
    for (const auto& f : summary["plots"]) std::cout << " " << f.get<std::string>();
    std::cout << "\n";
  }
  std::cout << "results in " << scene.output_dir.string() << "/ (index.html shows them)\n";
}

int run(const std::string& path, bool quiet, bool verbose, bool resume, double checkpoint_every) {
  const Scene scene = load_scene_for(path, OutputCommand::run);
  // The scene as `fretwear run --resume` is given it again.
  const std::string again = path == kStdinScene ? "- (the same scene on standard input)" : path;
  // Tests only: FRETWEAR_STAGE_QUIET_S, how long a stage runs before its parts are shown (s; 2 by default), so that a
  // test sees the lines of stages that take milliseconds.
  const char* quiet_stage = std::getenv("FRETWEAR_STAGE_QUIET_S");
  ProgressLine progress(!quiet, ::isatty(STDERR_FILENO) != 0, quiet_stage ? std::atof(quiet_stage) : 2.0);
  // From here a signal stops the run where it next asks, the checks before solving included: they march the first
  // cycle of a wear run (seconds, at many increments a cycle), shown as the cycle stage shows it.
  catch_stop_signals();
  Preflight checked;
  try {
    checked = preflight(scene, path, OutputCommand::run, [&progress](const StagePart& part) {
      if (progress.enabled()) progress.update(part);
      return g_signal != 0;
    });  // refuses before anything is written
  } catch (const StopRequested& e) {
    progress.finish();
    std::cerr << fmt::format("fretwear: {}: {} (the checks before solving) by signal {}; nothing written\n",
                             scene.name, e.what(), int(g_signal));
    return kExitSignal + int(g_signal);
  }
  progress.finish();
  print_warnings(checked.warnings);
  if (!quiet && checked.wear_seconds > 60.0)
    std::cerr << fmt::format("fretwear: {}: the wear stage will take about {}\n", scene.name,
                             duration_words(checked.wear_seconds));
  if (!quiet && checked.stress_seconds > 60.0)
    std::cerr << fmt::format("fretwear: {}: the stress maps ({} x {} points{}) will take about {}\n", scene.name,
                             scene.stress->nx, scene.stress->ny + 1, scene.wear ? ", at every record" : "",
                             duration_words(checked.stress_seconds));
  WearControl control;
  if (scene.wear) {
    control.checkpoint = checkpoint_path(scene);
    control.scene_hash = scene_hash(scene);
    control.checkpoint_interval = checkpoint_every;
    if (resume) {
      control.resume = read_checkpoint(control.checkpoint, scene);  // refuses another scene's, writes nothing
      if (!quiet)
        std::cerr << (control.resume
                          ? fmt::format("fretwear: {}: resuming at cycle {:.0f} of {:.0f} from {}\n", scene.name,
                                        control.resume->at("cycles").get<double>(),
                                        control.resume->at("cycles_total").get<double>(), control.checkpoint.string())
                          : fmt::format("fretwear: {}: no checkpoint ({}): running from the start\n", scene.name,
                                        control.checkpoint.string()));
    } else if (!quiet) {
      // A checkpoint this run will replace: said before it is, in case --resume was meant.
      std::error_code ec;
      if (std::filesystem::is_regular_file(control.checkpoint, ec)) {
        std::string held;
        try {
          if (const auto j = read_checkpoint(control.checkpoint, scene))
            held = fmt::format("this scene's wear run stopped at cycle {:.0f} of {:.0f}", j->at("cycles").get<double>(),
                               j->at("cycles_total").get<double>());
        } catch (const InputError&) {
          held = "a checkpoint this scene cannot resume (fretwear run --resume says why)";
        }
        std::cerr << fmt::format("fretwear: {}: {} holds {}; this run starts from cycle 0 and replaces it (to "
                                 "continue it instead, stop now and run: fretwear run --resume {})\n",
                                 scene.name, control.checkpoint.string(), held, again);
      }
    }
  } else if (resume && !quiet) {
    std::cerr << fmt::format("fretwear: {}: the scene does not wear, nothing to resume: running it\n", scene.name);
  }
  OutputFolder out(scene.output_dir, OutputCommand::run);
  if (!quiet) std::cerr << fmt::format("fretwear: {}: normal contact on {} cells\n", scene.name, scene.cells);
  if (scene.wear) {
    // Tests only, at each step boundary: FRETWEAR_STEP_PAUSE_MS, a pause, so that a test's signal lands mid-run;
    // FRETWEAR_STOP_AT_STEP=N, SIGINT raised at the first boundary after N accepted steps (a Ctrl-C there, exactly);
    // FRETWEAR_KILL_AT_STEP=N, the end SIGKILL would give there (status 137, nothing written after the checkpoint of
    // the boundary before); FRETWEAR_NOT_CONVERGED_AT_STEP=N, the ConvergenceError of a cycle's solve that stopped
    // short there, so that a test sees what a wear stage that fails part way leaves.
    auto env_int = [](const char* name) {
      const char* v = std::getenv(name);
      return v ? std::atoi(v) : 0;
    };
    const int pause_ms = env_int("FRETWEAR_STEP_PAUSE_MS");
    const int stop_at = env_int("FRETWEAR_STOP_AT_STEP"), kill_at = env_int("FRETWEAR_KILL_AT_STEP");
    const int fail_at = env_int("FRETWEAR_NOT_CONVERGED_AT_STEP");
    control.stop_requested = [pause_ms, stop_at, kill_at, fail_at](const WearProgress& p) {
      if (pause_ms > 0) std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms));
      if (kill_at > 0 && p.steps >= kill_at) ::_exit(kExitSignal + SIGKILL);
      if (fail_at > 0 && p.steps >= fail_at)
        throw ConvergenceError("a cycle's solve stopped short of its tolerance (FRETWEAR_NOT_CONVERGED_AT_STEP, a "
                               "test hook)");
      if (stop_at > 0 && p.steps >= stop_at && g_signal == 0) std::raise(SIGINT);
      return g_signal != 0;
    };
    if (progress.enabled()) control.progress = [&progress](const WearProgress& p) { progress.update(p); };
  }
  // Outside the wear stage's step boundaries a stop ends the run with nothing written. Tests only, where a stage
  // first asks (tangential, stress, crack, life): FRETWEAR_STOP_IN_STAGE=<stage> raises SIGINT (a Ctrl-C there,
  // exactly); FRETWEAR_NOT_CONVERGED_IN_STAGE=<stage> throws the ConvergenceError of a solve there that stopped
  // short, so that a test sees what a run that fails after its first stages writes.
  const char* stop_in = std::getenv("FRETWEAR_STOP_IN_STAGE");
  const char* fail_in = std::getenv("FRETWEAR_NOT_CONVERGED_IN_STAGE");
  control.stop_now = [stop_in, fail_in, &progress](const StagePart& part) {
    const char* stage = part.stage;
    if (progress.enabled()) progress.update(part);
    if (fail_in && std::string_view(fail_in) == stage)
      throw ConvergenceError(fmt::format("{}: the solve stopped short of its tolerance "
                                         "(FRETWEAR_NOT_CONVERGED_IN_STAGE, a test hook)",
                                         stage));
    if (stop_in && std::string_view(stop_in) == stage && g_signal == 0) std::raise(SIGINT);
    return g_signal != 0;
  };
  // A scene refused while solving (a worn contact grown to the window's end) leaves nothing behind: not the
  // checkpoint, nor the folder made for it.
  std::error_code ec;
  const bool checkpoint_folder_existed =
      control.checkpoint.empty() || std::filesystem::exists(control.checkpoint.parent_path().empty()
                                                                ? std::filesystem::path(".")
                                                                : control.checkpoint.parent_path(),
                                                            ec);
  auto forget_checkpoint = [&] {
    if (control.checkpoint.empty()) return;
    std::filesystem::remove(control.checkpoint, ec);
    if (!checkpoint_folder_existed) std::filesystem::remove(control.checkpoint.parent_path(), ec);  // when empty
  };
  try {
    RunResult result = Simulation(scene).run(&control, &checked.solved);
    progress.finish();
    print_warnings(result.warnings);  // those of the results; the preflight's were printed before the run
    result.warnings.insert(result.warnings.begin(), checked.warnings.begin(), checked.warnings.end());
    // Large stress maps take seconds to write and draw after the last stage (a row of stress.csv and of
    // fatigue.csv per point: 6 maps of 601 x 301 points, 90 MB and about 5 s): said before, so that the wait is not
    // taken for a hang.
    std::size_t map_points = 0;
    for (const StressMap& m : result.stress_maps) map_points += m.x.size() * m.y.size();
    if (!quiet && map_points > kLargeMapPoints)
      std::cerr << fmt::format("fretwear: {}: writing the results ({} points of stress maps{}) to {}/\n", scene.name,
                               map_points, scene.plots ? ", and their plots" : "", scene.output_dir.string());
    nlohmann::json summary;
    {
      // The results are written whole, or not at all: a signal that arrives meanwhile (gnuplot drawing included)
      // waits for them, and reaches on_signal as the hold ends.
      const DeferredStopSignals hold;
      summary = write_results(scene, result, out);
      out.commit();
    }
    if (result.wear && result.wear->interrupted) {
      const std::string& failure = result.wear->checkpoint_failure;
      std::cerr << fmt::format("fretwear: {}: stopped by signal {} at cycle {:.0f} of {:.0f} (recorded up to cycle "
                               "{:.0f}); results so far in {}/; continue with: fretwear run --resume {}{}\n",
                               scene.name, int(g_signal), result.wear->cycles_reached, scene.wear->cycles,
                               result.wear->records.back().cycles, scene.output_dir.string(), again,
                               failure.empty() ? ""
                                               : fmt::format(" (but the checkpoint of this stop could not be "
                                                             "written: {}; --resume starts from the last one that "
                                                             "was, or from the start)",
                                                             failure));
      return kExitSignal + int(g_signal);
    }
    if (scene.wear) std::filesystem::remove(control.checkpoint, ec);  // done: the checkpoint has served
    if (g_signal != 0) return stopped_after_writing(scene);
    if (!quiet) print_report(scene, result, summary, verbose);
  } catch (const ConvergenceError& e) {
    progress.finish();
    // What the stages before the failure found is in the summary, and said on stderr as a completed run says it.
    if (const auto* failed = dynamic_cast<const StageNotConverged*>(&e); failed && failed->partial())
      print_warnings(failed->partial()->warnings);
    {
      const DeferredStopSignals hold;
      write_not_converged(scene, e, checked.warnings, out);
      out.commit();
    }
    if (g_signal == 0) throw;
    std::cerr << fmt::format("fretwear: {}\n", e.what());
    return stopped_after_writing(scene);
  } catch (const ResultsNotWritten& e) {
    progress.finish();
    // The wear stage is done, and its last checkpoint holds what it reached: kept, it spares solving again once
    // there is room.
    std::optional<double> at;
    try {
      if (!control.checkpoint.empty())
        if (const auto j = read_checkpoint(control.checkpoint, scene)) at = j->at("cycles").get<double>();
    } catch (const std::exception&) {  // damaged or of another scene: not one to offer
    }
    if (!at) {
      out.discard();
      if (!control.resume) forget_checkpoint();  // and the folder made for one, now empty
      throw;
    }
    std::cerr << fmt::format("fretwear: {}\n  (the wear stage's checkpoint is kept: once the results can be written, "
                             "fretwear run --resume {} takes the run up from cycle {:.0f})\n",
                             e.what(), again, *at);
    return kExitInvalid;
  } catch (const InputError&) {
    progress.finish();
    if (!control.resume) forget_checkpoint();
    throw;
  } catch (const StopRequested& e) {
    progress.finish();
    const bool checkpoint = !control.checkpoint.empty() && std::filesystem::exists(control.checkpoint, ec);
    std::cerr << fmt::format("fretwear: {}: {} by signal {}; nothing written{}\n", scene.name, e.what(),
                             int(g_signal),
                             checkpoint ? fmt::format(" (the wear stage's checkpoint is kept: fretwear run --resume {} "
                                                      "takes it up)",
                                                      again)
                                        : "");
    return kExitSignal + int(g_signal);
  }
  return 0;
}

int validate(const std::string& path, bool quiet, bool verbose) {
  const Scene scene = load_scene_for(path, OutputCommand::run);
  const Preflight checked = preflight(scene, path, OutputCommand::run);
  print_warnings(checked.warnings);
  if (!quiet) {
    std::cout << (path == kStdinScene ? "standard input" : path) << ": valid scene \"" << scene.name << "\"";
    if (checked.wear_seconds > 60.0) std::cout << "; its wear stage will take about " << duration_words(checked.wear_seconds);
    if (checked.stress_seconds > 60.0)
      std::cout << "; its stress maps will take about " << duration_words(checked.stress_seconds);
    std::cout << "\n";
  }
  if (verbose) std::cout << scene.to_json().dump(2) << "\n";
  return 0;
}

int convergence(const std::string& path, int from, int to, bool quiet) {
  if (const std::string problem = grid_range_problem(from, to); !problem.empty()) throw InputError(problem);
  const Scene scene = load_scene_for(path, OutputCommand::convergence);
  preflight(scene, path, OutputCommand::convergence);
  const std::filesystem::path dir = output_folder(scene, OutputCommand::convergence);
  OutputFolder out(dir, OutputCommand::convergence);
  const ConvergenceStudy study = run_convergence(scene, from, to, quiet ? nullptr : &std::cerr);
  if (!quiet) std::cout << study.table();
  const DeferredStopSignals hold;
  out.write("convergence.csv", study.csv());
  out.write_json("scene.resolved.json", scene.to_json());
  out.commit();
  if (!quiet) std::cout << "table in " << (dir / "convergence.csv").string() << "\n";
  return 0;
}

// `fretwear sweep`: on the local cores, or over the ranks of `mpi`, whose rank 0 alone reports.
int sweep(const std::string& scene_path, const std::vector<std::string>& vary, int jobs, bool resume, bool quiet,
          const std::unique_ptr<MpiSweep>& mpi) {
  std::vector<Variation> variations;
  for (const auto& v : vary) variations.push_back(parse_variation(v));
  SweepOptions options;
  options.jobs = jobs;
  options.resume = resume;
  options.dispatch = mpi.get();
  const bool root = !mpi || mpi->root();
  options.progress = quiet || !root ? nullptr : &std::cerr;
  options.terminal = ::isatty(STDERR_FILENO) == 1;
  const SweepResult r = run_sweep(scene_path, variations, options);
  if (!r.root) return 0;
  int failed = 0;
  for (const auto& run : r.runs) failed += run.status != 0;
  if (!quiet)
    std::cout << fmt::format("{} runs, {} failed; table in {}\n", r.runs.size(), failed,
                             (r.dir / "sweep.csv").string());
  return failed == 0 ? 0 : kExitNoConvergence;
}

// An error that ends the program with `code`: said once, by rank 0 under MPI (every rank finds the same invalid
// scene); past the point where the ranks part ways, the others are ended with it.
int failed(MpiSweep* mpi, const std::string& message, int code) {
  if (!mpi || mpi->root()) std::cerr << message;
  if (mpi && mpi->parted) mpi->abandon(code);
  return code;
}

// The subcommands, and the options before them; a word before the subcommand that is neither is named in the error.
const std::vector<std::string> kCommands{"run", "validate", "defaults", "convergence", "sweep"};
const std::vector<std::string> kTopOptions{"-q", "--quiet", "-v", "--verbose", "--version", "-h", "--help"};

std::optional<std::string> unknown_command(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string word = argv[i];
    if (std::find(kCommands.begin(), kCommands.end(), word) != kCommands.end()) return std::nullopt;
    if (std::find(kTopOptions.begin(), kTopOptions.end(), word) == kTopOptions.end()) return word;
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fretwear: fretting in plane elastic contacts, from one JSON scene.\n"
               "Exit status: 0 done, 2 invalid scene (nothing written), 3 a solver did not converge, 130 / 143 a run "
               "stopped by Ctrl-C / SIGTERM (a wear run: what was recorded is written; continue with run --resume)."};
  app.set_version_flag("--version", std::string("fretwear ") + kVersion);
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");
  app.add_flag("-v,--verbose", verbose, "print more detail");

  std::string scene_path;
  auto* run_cmd = app.add_subcommand("run", "run a scene and write its results into output.dir");
  run_cmd->add_option("scene", scene_path, "scene file (JSON), or - for standard input")->required();
  bool resume = false;
  double checkpoint_every = 60.0;
  run_cmd->add_flag("--resume", resume,
                    "continue a stopped or killed wear run from its checkpoint (<output.dir>.checkpoint), if there "
                    "is one for this scene; else run from the start");
  run_cmd->add_option("--checkpoint-every", checkpoint_every,
                      "seconds between wear checkpoints between records (default 60; 0: after every step)")
      ->check(CLI::Range(0.0, 1e9));
  auto* validate_cmd = app.add_subcommand("validate", "check a scene and report every problem; writes nothing");
  validate_cmd->add_option("scene", scene_path, "scene file (JSON), or - for standard input")->required();
  std::string effect;
  auto* defaults_cmd =
      app.add_subcommand("defaults", "print a scene with every effect and every default filled in");
  defaults_cmd->add_option("--effect", effect,
                           "only this effect (with the load cycle it needs): normal, tangential, wear, stress, "
                           "crack or life");
  int from = 128, to = 65536;
  auto* conv_cmd = app.add_subcommand("convergence", "solve the scene's normal problem on grids of doubling size");
  conv_cmd->add_option("scene", scene_path, "scene file (JSON), or - for standard input")->required();
  conv_cmd->add_option("--from", from, "coarsest grid (cells)")->check(CLI::Range(16, 1 << 20));
  conv_cmd->add_option("--to", to, "finest grid (cells)")->check(CLI::Range(16, 1 << 20));
  std::vector<std::string> vary;
  int jobs = int(std::max(1u, std::thread::hardware_concurrency()));
  auto* sweep_cmd = app.add_subcommand("sweep", "run the product of variations of a scene on the local cores, or "
                                                "over the ranks of mpirun or srun");
  sweep_cmd->add_option("scene", scene_path, "scene file (JSON)")->required();
  sweep_cmd->add_option("--vary", vary,
                         "key=v1,v2,... (a dotted scene key, e.g. load.Q.ratio=0.2,0.4,0.6), or key=[JSON values] "
                         "(e.g. grid.window=[[-2e-4,2e-4],[-3e-4,3e-4]]); repeat")
      ->required();
  sweep_cmd->add_option("--jobs", jobs, "runs at once (default: the number of cores; under mpirun or srun each rank "
                                     "runs one at a time)")
      ->check(CLI::Range(1, 256));
  bool sweep_resume = false;
  sweep_cmd->add_flag("--resume", sweep_resume,
                      "finish a sweep that was stopped or killed: keep its complete runs, run the others, write the "
                      "tables and maps");
  for (auto* sub : {run_cmd, validate_cmd, conv_cmd, sweep_cmd}) {
    sub->add_flag("-q,--quiet", quiet, "print nothing but errors");
    sub->add_flag("-v,--verbose", verbose, "print more detail");
  }

  if (const auto word = unknown_command(argc, argv)) {
    std::cerr << fmt::format("fretwear: \"{}\" is not a {}; the commands are run, validate, defaults, "
                             "convergence and sweep (fretwear --help)\n",
                             *word, word->starts_with("-") ? "command or an option before one" : "command");
    return kExitInvalid;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version, or the usage error
    return code == 0 ? 0 : kExitInvalid;
  }
  if (!std::isfinite(checkpoint_every)) {  // CLI::Range lets NaN through: it compares false both ways
    std::cerr << "fretwear: --checkpoint-every: not a number; give seconds from 0 to 1e9\n";
    return kExitInvalid;
  }
  std::unique_ptr<MpiSweep> mpi;  // under mpirun or srun: MPI, started here and ended (after every rank) at return
  try {
    if (*sweep_cmd) mpi = start_mpi_if_launched(jobs);
    if (*run_cmd) return run(scene_path, quiet, verbose, resume, checkpoint_every);
    if (*validate_cmd) return validate(scene_path, quiet, verbose);
    if (app.got_subcommand("defaults")) {
      std::cout << default_scene_json(effect).dump(2) << "\n";
      return 0;
    }
    if (*conv_cmd) return convergence(scene_path, from, to, quiet);
    if (*sweep_cmd) return sweep(scene_path, vary, jobs, sweep_resume, quiet, mpi);
  } catch (const InputError& e) {
    return failed(mpi.get(), fmt::format("fretwear: {}\n", e.what()), kExitInvalid);
  } catch (const ConvergenceError& e) {
    return failed(mpi.get(), fmt::format("fretwear: {}\n", e.what()), kExitNoConvergence);
  } catch (const std::exception& e) {
    return failed(mpi.get(), fmt::format("fretwear: internal error: {}\n", e.what()), 1);
  }
  return 0;
}
