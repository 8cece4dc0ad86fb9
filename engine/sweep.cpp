#include "engine/sweep.hpp"

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <thread>

#include <unistd.h>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "engine/deferred_signals.hpp"
#include "engine/folder.hpp"
#include "engine/output.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/sweep_plots.hpp"

namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

Variation parse_variation(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw InputError(fmt::format("--vary \"{}\": give key=v1,v2,... (a dotted scene key such as load.Q.ratio)", text));
  Variation v{text.substr(0, eq), {}};
  // A JSON array lists values of any kind, lists and objects too: grid.window=[[-2e-4,2e-4],[-3e-4,3e-4]].
  // One that opens with [ and is no JSON is refused as such, not split at its commas into words.
  if (text[eq + 1] == '[') {
    json list;
    try {
      list = json::parse(text.substr(eq + 1));
    } catch (const json::exception& e) {
      std::string why = e.what();
      if (const auto bracket = why.find("] "); why.starts_with("[json.exception.") && bracket != std::string::npos)
        why = why.substr(bracket + 2);
      throw InputError(fmt::format("--vary \"{}\": the values open with [ but are not a JSON list ({}); give a JSON "
                                   "list of finite numbers, lists or strings, or v1,v2,...",
                                   text, why));
    }
    if (list.empty()) throw InputError(fmt::format("--vary \"{}\": an empty list of values", text));
    v.values.assign(list.begin(), list.end());
    return v;
  }
  std::stringstream values(text.substr(eq + 1));
  for (std::string item; std::getline(values, item, ',');) {
    if (item.empty()) throw InputError(fmt::format("--vary \"{}\": an empty value", text));
    const json parsed = json::parse(item, nullptr, false);
    if (parsed.is_discarded()) {  // a bare word is a string; what reads as a number that JSON cannot hold is refused
      const std::string lower = [&] {
        std::string l = item;
        for (char& c : l) c = char(std::tolower(static_cast<unsigned char>(c)));
        return l;
      }();
      const std::string bare = lower.substr(lower.find_first_not_of("+-") == std::string::npos
                                                ? lower.size()
                                                : lower.find_first_not_of("+-"));
      if (bare == "nan" || bare == "inf" || bare == "infinity")
        throw InputError(fmt::format("--vary \"{}\": {} is not a JSON number; give finite numbers", text, item));
      char* end = nullptr;
      errno = 0;
      const double number = std::strtod(item.c_str(), &end);
      if (end == item.c_str() + item.size())
        throw InputError(
            std::isinf(number) && errno == ERANGE
                ? fmt::format("--vary \"{}\": {} overflows a double; give a number between -1.8e308 and 1.8e308 (and "
                              "within the key's range)",
                              text, item)
                : fmt::format("--vary \"{}\": {} is a number JSON does not write (no leading + or point, no "
                              "hexadecimal); give it as {}",
                              text, item, json(number).dump()));
    }
    v.values.push_back(parsed.is_discarded() ? json(item) : parsed);
  }
  return v;
}

namespace {

// Sets the value at a dotted key path: each part an object's key, or, where the scene holds a list, a decimal index
// into it (profile.terms.1.R: the second term's R). An object missing on the way is made; an index past the list's
// end is a problem, returned (empty when set).
std::string set_path(json& j, const std::string& dotted, const json& value) {
  json* node = &j;
  std::stringstream parts(dotted);
  std::vector<std::string> keys;
  for (std::string k; std::getline(parts, k, '.');) keys.push_back(k);
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const bool last = i + 1 == keys.size();
    if (node->is_array()) {
      std::size_t index = 0;
      const auto [end, ec] = std::from_chars(keys[i].data(), keys[i].data() + keys[i].size(), index);
      std::string at;
      for (std::size_t k = 0; k < i; ++k) at += (k ? "." : "") + keys[k];
      if (ec != std::errc() || end != keys[i].data() + keys[i].size())
        return fmt::format("--vary {}: {} is a list, and \"{}\" is no index into it; give its entries by number from "
                           "0 ({}.0, {}.1, ...)",
                           dotted, at, keys[i], at, at);
      if (index >= node->size())
        return fmt::format("--vary {}: {} holds {} entr{} (0 to {}), so {} is past its end", dotted, at, node->size(),
                           node->size() == 1 ? "y" : "ies", node->size() - 1, index);
      node = &(*node)[index];
    } else {
      if (!node->is_object()) *node = json::object();
      if (!last && (!node->contains(keys[i]) || !(*node)[keys[i]].is_structured()))
        (*node)[keys[i]] = json::object();
      node = &(*node)[keys[i]];
    }
    if (last) *node = value;
  }
  return {};
}

// The longest name a scene may have (valid_name, engine/scene.cpp): a run's name is its scene's.
constexpr std::size_t kMaxName = 128;

// A value as the user reads it: a string bare, anything else as JSON.
std::string text(const json& v) { return v.is_string() ? v.get<std::string>() : v.dump(); }

// A field of sweep.csv (RFC 4180): in double quotes, each of its own doubled, when it holds a comma, a quote or a
// line break, or when `quoted` (an array, always quoted); as it is otherwise.
std::string csv_field(const std::string& s, bool quoted = false) {
  if (!quoted && s.find_first_of(",\"\r\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) {
    if (c == '"') q += '"';
    q += c;
  }
  return q + '"';
}

// A value in one form for every way of writing it: each number, at any depth, as the double it is (1e5, 100000
// and 100000.0 are all 100000.0; −0 is 0.0), which JSON then writes in the shortest form that reads back to it
// (100000.0, 0.2, 3e-07, 1e+20).
json canonical(const json& v) {
  if (v.is_number()) return json(v.get<double>() + 0.0);
  if (!v.is_structured()) return v;
  json c = v;
  for (auto& item : c) item = canonical(item);
  return c;
}

// A value as a run's name holds it: canonical, each character a name cannot hold made '_'.
std::string word(const json& v) {
  std::string s = text(canonical(v));
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

// True when `inner` is a key inside `outer` (load.Q.ratio inside load.Q).
bool inside(const std::string& inner, const std::string& outer) {
  return inner.size() > outer.size() && inner.compare(0, outer.size(), outer) == 0 && inner[outer.size()] == '.';
}

// What the variations get wrong whatever the scene: the keys the sweep sets itself, a key varied twice or inside
// another varied key (one would overwrite the other's values), and a value given twice (its two runs would be one
// variant, written into one folder at once).
std::vector<std::string> variation_problems(const std::vector<Variation>& variations) {
  std::vector<std::string> problems;
  for (std::size_t i = 0; i < variations.size(); ++i) {
    const Variation& v = variations[i];
    if (v.key == "name")
      problems.push_back("--vary name: the sweep names every run itself (<scene name>__<key>_<value>, its folder "
                         "under runs/); set name in the scene, and vary other keys");
    if (v.key == "output" || inside(v.key, "output"))
      problems.push_back(fmt::format("--vary {}: the sweep places every run itself, in <output.dir>/sweep/runs/<run "
                                     "name>/, with the scene's output.plots; set output in the scene, and vary "
                                     "other keys",
                                     v.key));
    for (std::size_t j = 0; j < i; ++j) {
      const std::string& other = variations[j].key;
      if (other == v.key) {
        problems.push_back(fmt::format("--vary {} is given twice; give each key once, with all its values (--vary "
                                       "{}=v1,v2,...)",
                                       v.key, v.key));
        break;
      }
      if (inside(v.key, other) || inside(other, v.key)) {
        const auto& [in, out] = inside(v.key, other) ? std::pair(v.key, other) : std::pair(other, v.key);
        problems.push_back(fmt::format("--vary {} and --vary {}: {} is part of {}, and one would overwrite the "
                                       "other's values; vary one of them",
                                       other, v.key, in, out));
        break;
      }
    }
    for (std::size_t b = 1; b < v.values.size(); ++b)
      for (std::size_t a = 0; a < b; ++a)
        if (v.values[a] == v.values[b]) {
          problems.push_back(fmt::format("--vary {}: values {} and {} are both {}; give each value once", v.key,
                                         a + 1, b + 1, text(v.values[a])));
          break;
        }
  }
  return problems;
}

// Names the runs, each its folder's under runs/: the scene's name and every varied key with its value in canonical
// form (sw__load.P_200000.0 for 2e5, 200000 or 200000.0), each character a name cannot hold made '_', so that a
// number names one folder however it is written (and --resume finds it). A name longer than kMaxName, or one that
// runs of different values would share (a/p.csv and a_p.csv both give a_p.csv), is <scene name>__run<k> instead, k
// the run's index in the product, the scene's name cut short as far as kMaxName needs. Any name two runs still share
// is a problem.
std::vector<std::string> name_runs(const std::string& scene_name, const std::vector<Variation>& variations,
                                   std::vector<SweepRun>& runs) {
  std::map<std::string, std::size_t> uses;
  for (SweepRun& run : runs) {
    run.name = scene_name;
    for (std::size_t i = 0; i < variations.size(); ++i)
      run.name += "__" + variations[i].key + "_" + word(run.values[i]);
    ++uses[run.name];
  }
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (runs[k].name.size() > kMaxName || uses[runs[k].name] > 1) {
      const std::string index = fmt::format("__run{}", k);
      runs[k].name = scene_name.substr(0, kMaxName - index.size()) + index;
    }
  std::vector<std::string> problems;
  std::map<std::string, std::size_t> first;
  for (std::size_t k = 0; k < runs.size(); ++k)
    if (const auto [at, fresh] = first.emplace(runs[k].name, k); !fresh)
      problems.push_back(fmt::format("runs {} and {} would both be named {}; rename the scene", at->second, k,
                                     runs[k].name));
  return problems;
}

// The summary's scalars worth a column, each with its unit as the column names it (empty: a count, a word or a
// ratio). Several contact or stick zones appear one pair each in contact.zones and cycle.stick_zones.
struct Column {
  const char* key;
  const char* unit;
};
constexpr Column kColumns[] = {{"contact.p_max", "Pa"},
                               {"contact.extent", "m"},
                               {"contact.zones", "m"},
                               {"cycle.regime", ""},
                               {"cycle.stick_zone", "m"},
                               {"cycle.stick_zones", "m"},
                               {"cycle.dissipated_energy", "J_m"},
                               {"cycle.slip_max", "m"},
                               {"wear.worn_area", "m2"},
                               {"wear.max_depth", "m"},
                               {"wear.fraction_of_asymptote", ""},
                               {"crack.K_I_max", "Pa_sqrt_m"},
                               {"life.initiation.cycles", ""},
                               {"life.propagation.cycles", ""},
                               {"life.total_cycles", ""},
                               {"life.fate", ""},
                               {"timings.total", "s"}};

json get(const json& j, const std::string& dotted) {
  const json* node = &j;
  std::stringstream parts(dotted);
  for (std::string k; std::getline(parts, k, '.');) {
    if (!node->is_object() || !node->contains(k)) return nullptr;
    node = &(*node)[k];
  }
  return *node;
}

std::string clock_time(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  return s >= 3600 ? fmt::format("{}:{:02}:{:02}", s / 3600, s / 60 % 60, s % 60)
                   : fmt::format("{}:{:02}", s / 60, s % 60);
}

// The sweep folders a killed sweep of this scene left beside `dir` (<output.dir>/sweep): its staging folder
// sweep.partial-<pid>, renamed here to sweep.resume-<pid> so that the staging of this sweep does not remove it, and
// those of earlier resumes; newest first. Only folders a killed sweep left (killed_leftover(): a staging marker of a
// process that has ended, holding nothing fretwear did not write); a copy of the user's so named stays untouched.
// A killed sweep's folder that holds files of the user's is left whole, and said in `passed` with those files.
std::vector<fs::path> take_over_killed(const fs::path& dir, std::vector<std::string>& passed) {
  std::vector<std::pair<fs::file_time_type, fs::path>> found;
  const fs::path parent = dir.parent_path();
  const std::string name = dir.filename().string(), own = std::to_string(::getpid());
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string entry = e.path().filename().string();
    for (const std::string kind : {".partial-", ".resume-"}) {
      const std::string prefix = name + kind;
      if (entry.rfind(prefix, 0) != 0) continue;
      const std::string pid = entry.substr(prefix.size());
      if (pid.empty() || pid == own || pid.size() > 9 || pid.find_first_not_of("0123456789") != std::string::npos)
        continue;
      std::vector<std::string> foreign;
      if (!killed_leftover(e.path(), std::stol(pid), &foreign)) {  // a copy of the user's, or a sweep still running
        if (!foreign.empty())
          passed.push_back(fmt::format("sweep: \"{}\" is a stopped sweep's folder but holds what fretwear did not "
                                       "write ({}): its runs are not taken and it is left as it is; move that "
                                       "out of it to resume from it",
                                       e.path().string(), fmt::join(foreign, ", ")));
        continue;
      }
      fs::path at = e.path();
      if (kind == std::string(".partial-")) {
        const fs::path renamed = parent / (name + ".resume-" + pid);
        std::error_code rename_ec;
        fs::rename(at, renamed, rename_ec);
        if (rename_ec) continue;
        at = renamed;
      }
      found.emplace_back(fs::last_write_time(at, ec), at);
    }
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<fs::path> sources;
  for (const auto& f : found) sources.push_back(f.second);
  return sources;
}

// Removes j[group][key], if there.
void erase_at(json& j, const char* group, const char* key) {
  if (j.contains(group) && j[group].is_object()) j[group].erase(key);
}

// True when the resolved scene a run wrote is the one `wanted` (the variant's scene before solving) resolves to:
// equal, but for what legitimately differs between the two:
// - grid.window and grid.reference_depth, when `wanted` leaves them to the run: the run writes those it computed
//   from the rest of the scene (engine/output.cpp), equal for equal scenes; when `wanted` gives them, the run
//   writes them as given, and they are compared;
// - output.dir, which names where the run's folder is, not what it computed: a run is kept only from the folder of
//   the variant's own name, moved or copied to <output.dir>/sweep/runs/<name>, so its output.dir can only spell
//   that folder otherwise (a relative or absolute output.dir in the scene).
bool same_run(json resolved, json wanted) {
  for (const char* key : {"window", "reference_depth"})
    if (!wanted.contains("grid") || !wanted["grid"].contains(key)) erase_at(resolved, "grid", key);
  erase_at(resolved, "output", "dir");
  erase_at(wanted, "output", "dir");
  return resolved == wanted;
}

// The summary of a complete run folder of `scene` (written whole by its own staging and commit: a folder under its
// final name has every file), or null when the folder is missing, partial, of another scene, or of a run that did
// not complete (a not-converged summary also holds the normal contact's sections).
json complete_summary(const fs::path& folder, const Scene& scene) {
  std::error_code ec;
  if (!fs::is_regular_file(folder / "summary.json", ec) || !fs::is_regular_file(folder / "scene.resolved.json", ec))
    return nullptr;
  std::ifstream summary_file(folder / "summary.json"), scene_file(folder / "scene.resolved.json");
  const json summary = json::parse(summary_file, nullptr, false), resolved = json::parse(scene_file, nullptr, false);
  if (!summary.is_object() || summary.value("status", "") != "completed" || !summary.contains("contact") ||
      !resolved.is_object())
    return nullptr;
  if (!same_run(resolved, scene.to_json())) return nullptr;
  return summary;
}

// The codes of a run's warnings (summary.json's `warnings`), in their order, each once.
std::vector<std::string> warning_codes(const json& summary) {
  std::vector<std::string> codes;
  if (!summary.is_object() || !summary.contains("warnings") || !summary["warnings"].is_array()) return codes;
  for (const json& w : summary["warnings"]) {
    const std::string code = w.value("code", "");
    if (!code.empty() && std::find(codes.begin(), codes.end(), code) == codes.end()) codes.push_back(code);
  }
  return codes;
}

// The number of runs after which kKillAfterRunsVariable kills this process; 0: never.
std::size_t kill_after_runs() {
  const char* v = std::getenv(kKillAfterRunsVariable);
  return v ? std::size_t(std::strtoul(v, nullptr, 10)) : 0;
}

// Runs one run into the folder `at`, inside the sweep's staging folder; its scene.resolved.json names
// scene.output_dir, the folder the run has once the sweep is committed. Never throws.
SweepOutcome run_one(const Scene& scene, const fs::path& at) {
  SweepOutcome o;
  try {
    OutputFolder folder(at);
    const RunResult r = Simulation(scene).run();
    o.summary = write_results(scene, r, folder);
    folder.commit();
  } catch (const ConvergenceError& e) {
    o.status = 3, o.message = e.what();
  } catch (const InputError& e) {
    o.status = 2, o.message = e.what();
  } catch (const std::exception& e) {
    o.status = 1, o.message = std::string("internal error: ") + e.what();
  }
  return o;
}

class ThreadDispatch final : public SweepDispatch {
 public:
  explicit ThreadDispatch(int jobs) : jobs_(std::max(1, jobs)) {}
  bool root() const override { return true; }
  std::string share(const std::string& text) override { return text; }
  void run_all(const std::vector<std::size_t>& todo, const std::function<SweepOutcome(std::size_t)>& run,
               const std::function<void(std::size_t, const SweepOutcome&)>& done) override {
    std::atomic<std::size_t> next{0};
    std::mutex report;
    auto worker = [&] {
      for (std::size_t i; (i = next++) < todo.size();) {
        const SweepOutcome o = run(todo[i]);
        const std::lock_guard lock(report);
        done(todo[i], o);
      }
    };
    std::vector<std::jthread> pool;
    for (int t = 0; t < jobs_; ++t) pool.emplace_back(worker);
  }
  std::vector<std::vector<std::string>> check_all(
      std::size_t n, const std::function<std::vector<std::string>(std::size_t)>& check) override {
    std::vector<std::vector<std::string>> out(n);
    std::atomic<std::size_t> next{0};
    std::mutex failing;
    std::exception_ptr failure;
    auto worker = [&] {
      for (std::size_t k; (k = next++) < n;) try {
          out[k] = check(k);
        } catch (...) {
          const std::lock_guard lock(failing);
          if (!failure) failure = std::current_exception();
        }
    };
    {
      std::vector<std::jthread> pool;
      for (std::size_t t = 0; t < std::min(std::size_t(jobs_), n); ++t) pool.emplace_back(worker);
    }
    if (failure) std::rethrow_exception(failure);
    return out;
  }

 private:
  int jobs_;
};

}  // namespace

json to_json(const SweepOutcome& o) {
  return {{"status", o.status}, {"message", o.message}, {"summary", o.summary}, {"rank", o.rank}};
}

SweepOutcome outcome_from_json(const json& j) {
  SweepOutcome o;
  o.status = j.at("status").get<int>();
  o.message = j.at("message").get<std::string>();
  o.summary = j.at("summary");
  o.rank = j.at("rank").get<int>();
  return o;
}

std::string status_word(int status) {
  switch (status) {
    case 0: return "completed";
    case 2: return "refused";
    case 3: return "not_converged";
    default: return "internal_error";
  }
}

std::unique_ptr<SweepDispatch> thread_dispatch(int jobs) { return std::make_unique<ThreadDispatch>(jobs); }

SweepResult run_sweep(const fs::path& scene_file, const std::vector<Variation>& variations,
                      const SweepOptions& options) {
  std::unique_ptr<SweepDispatch> own_dispatch;
  SweepDispatch* dispatch = options.dispatch;
  if (!dispatch) dispatch = (own_dispatch = thread_dispatch(options.jobs)).get();
  // Every rank reads the scene, and mpirun hands standard input to rank 0 alone.
  if (scene_file == kStdinScene)
    throw SceneError({"-: a sweep reads its scene from a file (every rank of mpirun or srun reads it, and only one "
                      "is given standard input); give the scene's file"});
  std::ifstream in(scene_file);
  const Scene base_scene = load_scene_for(scene_file, OutputCommand::sweep);  // the base must be valid on its own
  json base = json::parse(in, nullptr, false);
  SweepResult result;
  result.variations = variations;
  result.dir = output_folder(base_scene, OutputCommand::sweep);
  result.root = dispatch->root();

  // Every combination, validated before anything runs (every process parses all, and checks the physics of its
  // share; all learn every problem). A run's scene names its folder as it will be once the sweep is committed.
  std::vector<Scene> scenes;
  std::vector<std::string> problems = variation_problems(variations);
  double product = 1.0;  // in double: a product past any integer type is refused as well
  for (const auto& v : variations) product *= double(v.values.size());
  if (product > double(kMaxSweepRuns)) {
    std::string factors;
    for (const auto& v : variations) factors += fmt::format("{}{} {}", factors.empty() ? "" : " x ", v.values.size(), v.key);
    problems.push_back(fmt::format("--vary: the sweep would be {:.4g} runs ({}), more than the {} a sweep may hold "
                                   "(each is a folder of results, and each run is validated before any starts); "
                                   "give fewer values, or split the sweep",
                                   product, factors, kMaxSweepRuns));
    throw SceneError(problems);
  }
  const std::size_t total = std::size_t(product);
  for (std::size_t k = 0; k < total; ++k) {
    SweepRun run;
    for (std::size_t rest = k; const auto& v : variations) {
      run.values.push_back(v.values[rest % v.values.size()]);
      rest /= v.values.size();
    }
    result.runs.push_back(std::move(run));
  }
  for (const std::string& p : name_runs(base_scene.name, variations, result.runs)) problems.push_back(p);
  std::vector<std::vector<std::string>> run_problems(result.runs.size());  // each run's, said in the runs' order
  std::vector<std::size_t> parsed;  // the run of each of `scenes`
  for (std::size_t r = 0; r < result.runs.size(); ++r) {
    const SweepRun& run = result.runs[r];
    json j = base;
    bool placed = true;
    for (std::size_t i = 0; i < variations.size(); ++i)
      if (const std::string p = set_path(j, variations[i].key, run.values[i]); !p.empty()) {
        if (r == 0) problems.push_back(p);  // the scene's shape, the same for every run: said once
        placed = false;
      }
    if (!placed) continue;
    j["name"] = run.name;
    j["output"] = {{"dir", (result.dir / "runs" / run.name).string()}, {"plots", base_scene.plots}};
    try {
      scenes.push_back(parse_scene(j, "scene", scene_file.parent_path()));  // a table's file beside the scene
      parsed.push_back(r);
    } catch (const SceneError& e) {
      for (const auto& p : e.problems()) run_problems[r].push_back(run.name + ": " + p);
    }
  }
  // The physics of every variant that parsed: its solves, shared among the threads or the ranks.
  const auto physics = dispatch->check_all(scenes.size(), [&](std::size_t i) {
    std::vector<std::string> out;
    for (const auto& p : physics_problems(scenes[i])) out.push_back(result.runs[parsed[i]].name + ": " + p);
    return out;
  });
  for (std::size_t i = 0; i < scenes.size(); ++i)
    run_problems[parsed[i]].insert(run_problems[parsed[i]].end(), physics[i].begin(), physics[i].end());
  for (const auto& each : run_problems) problems.insert(problems.end(), each.begin(), each.end());
  // The output folder is checked by the root alone, before it makes anything there (another process checking it
  // meanwhile could find the root's staging folder), and its verdict is every process's.
  if (result.root) {
    const std::vector<std::string> target = output_dir_problems(base_scene, scene_file, OutputCommand::sweep);
    problems.insert(problems.begin(), target.begin(), target.end());
  }
  const std::string verdict = dispatch->share(problems.empty() ? "" : "invalid");
  if (!problems.empty()) throw SceneError(problems);
  if (!verdict.empty()) throw SceneError({"the sweep is invalid (rank 0 says why)"});
  dispatch->parted = true;

  // The root stages the sweep's folder, takes over the complete runs of a killed sweep, and tells every process
  // where the runs go.
  std::optional<OutputFolder> out;
  std::vector<fs::path> killed;
  std::vector<std::string> passed;  // stopped sweeps' folders left whole for the user's files in them
  std::vector<std::size_t> todo;
  std::size_t from_killed = 0, from_finished = 0;  // runs kept from killed sweeps, from the last finished one
  std::string runs_dir;
  if (result.root) {
    if (options.resume) killed = take_over_killed(result.dir, passed);
    out.emplace(result.dir, OutputCommand::sweep);
    fs::create_directories(out->path("runs"));
    for (std::size_t k = 0; k < scenes.size(); ++k) {
      SweepRun& run = result.runs[k];
      const fs::path to = out->path("runs") / run.name;
      if (options.resume) {
        // Moved from a killed sweep's folder; copied from the last finished sweep's, which stays whole until this
        // one replaces it.
        std::vector<fs::path> sources = killed;
        if (has_marker(result.dir)) sources.push_back(result.dir);
        for (const fs::path& source : sources) {
          const fs::path from = source / "runs" / run.name;
          json summary = complete_summary(from, scenes[k]);
          if (summary.is_null()) continue;
          std::error_code ec;
          if (source == result.dir)
            fs::copy(from, to, fs::copy_options::recursive, ec);
          else
            fs::rename(from, to, ec);
          if (ec) {
            fs::remove_all(to, ec);
            continue;
          }
          run.summary = std::move(summary);
          run.kept = true;
          ++(source == result.dir ? from_finished : from_killed);
          break;
        }
      }
      if (!run.kept) todo.push_back(k);
    }
    runs_dir = out->path("runs").string();
  }
  runs_dir = dispatch->share(runs_dir);

  const std::size_t kept = result.runs.size() - todo.size(), kill_after = kill_after_runs();
  if (options.progress && result.root) {
    *options.progress << fmt::format("sweep: {} runs", result.runs.size());
    if (options.resume) {
      if (kept == 0)
        *options.progress << (passed.empty() ? ", 0 kept (no complete run of the same resolved scene was found)"
                                             : ", 0 kept");
      if (from_killed > 0)
        *options.progress << fmt::format(", {} kept from the {}", from_killed,
                                         killed.size() == 1 ? "sweep that was stopped" : "sweeps that were stopped");
      if (from_finished > 0) *options.progress << fmt::format(", {} kept from the last finished sweep", from_finished);
    }
    *options.progress << "\n";
    for (const std::string& line : passed) *options.progress << line << "\n";
    *options.progress << std::flush;
  }
  const auto started = std::chrono::steady_clock::now();
  std::size_t finished = 0;
  auto run = [&](std::size_t k) { return run_one(scenes[k], fs::path(runs_dir) / result.runs[k].name); };
  auto done = [&](std::size_t k, const SweepOutcome& o) {
    SweepRun& r = result.runs[k];
    r.status = o.status, r.message = o.message, r.summary = o.summary;
    ++finished;
    if (kill_after != 0 && finished == kill_after) {
      if (options.progress) *options.progress << fmt::format("  killed after {} runs ({})\n", finished, kKillAfterRunsVariable) << std::flush;
      std::raise(SIGKILL);
    }
    if (!options.progress) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    const std::size_t left = todo.size() - finished;
    if (options.terminal) {
      // The time left, as if the runs still to come cost what those finished did on average.
      *options.progress << fmt::format("\r\033[Ksweep: {}/{} runs{}, {} elapsed, ~{} left{}", kept + finished,
                                       result.runs.size(), kept ? fmt::format(" ({} kept)", kept) : "",
                                       clock_time(elapsed), clock_time(elapsed * double(left) / double(finished)),
                                       o.status == 0 ? "" : fmt::format("; {}: {}\n", r.name, o.message));
      if (left == 0) *options.progress << "\n";
      *options.progress << std::flush;
    } else {
      const std::vector<std::string> warned = warning_codes(r.summary);
      *options.progress << fmt::format("  [{}/{}] {}: {}{}{}\n", kept + finished, result.runs.size(), r.name,
                                       o.status == 0 ? "done" : o.message,
                                       warned.empty() ? "" : fmt::format(", warned: {}", fmt::join(warned, ", ")),
                                       o.rank >= 0 ? fmt::format(" (rank {})", o.rank) : "")
                        << std::flush;
    }
  };
  dispatch->run_all(todo, run, done);
  if (!result.root) return result;

  // The table: the varied values, the status, the name, the summary's scalars (each numeric column named with its
  // unit), the codes of the run's warnings (what of it the grid did not resolve, as its summary.json says) and why
  // a run failed.
  std::string csv;
  for (const auto& v : variations) csv += csv_field(column_name(v.key)) + ",";
  csv += "status,name";
  for (const Column& c : kColumns) csv += fmt::format(",{}{}{}", c.key, *c.unit ? "_" : "", c.unit);
  csv += ",warnings,message\n";
  json table = json::array(), units = json::object();
  for (const Column& c : kColumns)
    if (*c.unit) units[c.key] = c.unit;
  for (const auto& v : variations)
    if (!key_unit(v.key).label.empty()) units[v.key] = key_unit(v.key).label;
  for (const SweepRun& r : result.runs) {
    for (const auto& v : r.values) csv += csv_field(text(v)) + ",";
    csv += fmt::format("{},{}", status_word(r.status), r.name);
    json row = {{"name", r.name}, {"status", status_word(r.status)}, {"values", r.values}};
    for (const Column& c : kColumns) {
      const json v = get(r.summary, c.key);
      csv += "," + (v.is_null() ? std::string() : csv_field(text(v), v.is_array()));
      row[c.key] = v;
    }
    const std::vector<std::string> warned = warning_codes(r.summary);
    csv += "," + csv_field(fmt::format("{}", fmt::join(warned, " "))) + "," + csv_field(r.message);
    row["warnings"] = warned;
    if (!r.message.empty()) row["message"] = r.message;
    csv += "\n";
    table.push_back(row);
  }
  out->write("sweep.csv", csv);
  out->write_json("sweep.json", {{"scene", base_scene.name}, {"units", units}, {"runs", table}});
  write_sweep_maps(result, base_scene.name, base_scene.wear.has_value(), bool(base_scene.life), base_scene.plots,
                   *out);
  const DeferredStopSignals hold;
  out->commit();
  for (const fs::path& k : killed) {
    std::error_code ec;
    if (has_marker(k)) fs::remove_all(k, ec);
  }
  return result;
}

}  // namespace fretwear
