// `fretwear sweep`: the product of variations of a scene, one output folder per run, a table of every run's summary,
// a regime map over the first two varied keys and colour maps of the main results. The runs are spread over the
// local cores (threads) or, under an MPI launcher, over the ranks (sweep_mpi.hpp); a killed sweep is finished by
// --resume, which keeps every run whose folder is complete and whose resolved scene is its variant's.
#pragma once

#include <cstddef>
#include <filesystem>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fretwear {

// One --vary: a dotted key path into the scene ("load.Q.ratio") and its values.
struct Variation {
  std::string key;
  std::vector<nlohmann::json> values;
};

// Parses "key=v1,v2,..." (values as JSON numbers, booleans or bare words taken as strings), or "key=[v1, v2, ...]", a
// JSON array of the values, which may be lists and objects themselves. Throws InputError.
Variation parse_variation(const std::string& text);

// The most runs one sweep may hold: the product of the variations' counts past it is refused (exit 2) before any
// run's scene is built.
inline constexpr std::size_t kMaxSweepRuns = 100000;

// What one run came to, wherever it ran.
struct SweepOutcome {
  int status = 0;        // 0 done, 1 internal error, 2 invalid, 3 not converged
  std::string message;   // why, unless done
  nlohmann::json summary;  // its summary.json; empty unless done
  int rank = -1;           // the MPI rank that ran it; −1 without MPI
};
nlohmann::json to_json(const SweepOutcome& o);
SweepOutcome outcome_from_json(const nlohmann::json& j);

// A run's status in sweep.csv and sweep.json, in the words of its summary.json: 0 "completed", 3 "not_converged";
// a variant refused while solving (2, a worn contact grown to the window's end) and an internal error (1), which
// write no summary, "refused" and "internal_error".
std::string status_word(int status);

struct SweepRun {
  std::vector<nlohmann::json> values;  // one per variation
  std::string name;                    // the run's scene name (its output folder)
  int status = 0;                      // as SweepOutcome::status
  std::string message;
  nlohmann::json summary;              // empty unless done
  bool kept = false;                   // taken over by --resume from a killed or the last finished sweep, not run again
};

struct SweepResult {
  std::vector<Variation> variations;
  std::vector<SweepRun> runs;
  std::filesystem::path dir;  // the sweep's folder, <output.dir>/sweep
  bool root = true;           // false in an MPI rank other than 0, which writes no table and reports nothing
};

// How the runs of a sweep are spread. Every process of a sweep builds the same list of runs; the root (the only
// process without MPI, rank 0 with it) owns the sweep's folder and tables.
class SweepDispatch {
 public:
  virtual ~SweepDispatch() = default;
  // Set by run_sweep once every process has validated the sweep alike: from then on a failure in one process must
  // end the others, which would wait for it.
  bool parted = false;
  virtual bool root() const = 0;
  // The root's `text`, in every process.
  virtual std::string share(const std::string& text) = 0;
  // Runs each index of the root's `todo` exactly once, in some process, by run(k) (which never throws); the root
  // learns each outcome by done(k, outcome), on one thread at a time and in the order they finish.
  virtual void run_all(const std::vector<std::size_t>& todo, const std::function<SweepOutcome(std::size_t)>& run,
                       const std::function<void(std::size_t, const SweepOutcome&)>& done) = 0;
  // Calls check(k) once for each k < n, spread over the processes and their threads (a variant's checks solve its
  // normal contact and first cycle), and returns in every process what each returned, indexed by k. An exception
  // check throws is rethrown, in the process it was thrown in, once the others are done.
  virtual std::vector<std::vector<std::string>> check_all(
      std::size_t n, const std::function<std::vector<std::string>(std::size_t)>& check) = 0;
};

// The runs on `jobs` threads of this process, each taking the next run as soon as it is free.
std::unique_ptr<SweepDispatch> thread_dispatch(int jobs);

struct SweepOptions {
  int jobs = 1;                        // threads, when `dispatch` is null
  bool resume = false;                 // keep the complete runs of the same variants from killed or finished sweeps
  std::ostream* progress = nullptr;    // progress and a line per finished run; null: silent
  bool terminal = false;               // progress is a terminal: one line, rewritten in place, with the time left
  SweepDispatch* dispatch = nullptr;   // null: thread_dispatch(jobs)
};

// Validates every variant before running any (all problems at once, SceneError); then runs the runs not kept, each
// into <dir>/runs/<name>/, and writes <dir>/sweep.csv, <dir>/sweep.json, the maps' data and, with plots, the maps
// (sweep_plots.hpp). A run that fails writes no folder: its row says why (status and message).
SweepResult run_sweep(const std::filesystem::path& scene_file, const std::vector<Variation>& variations,
                      const SweepOptions& options);
inline SweepResult run_sweep(const std::filesystem::path& scene_file, const std::vector<Variation>& variations,
                             int jobs, std::ostream* progress) {
  SweepOptions o;
  o.jobs = jobs;
  o.progress = progress;
  return run_sweep(scene_file, variations, o);
}

// The environment variable that kills a sweep (SIGKILL, as a crash or a scheduler would) once it has finished that
// many runs in this process: how the tests interrupt a sweep at a chosen point to resume it.
inline constexpr const char* kKillAfterRunsVariable = "FRETWEAR_SWEEP_KILL_AFTER_RUNS";

}  // namespace fretwear
