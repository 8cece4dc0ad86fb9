// The Python module fretwear (docs/PYTHON.md): the command line's run, validate and defaults on scenes held as dicts,
// results in memory with numpy arrays, files only where asked.
#include <algorithm>
#include <chrono>
#include <cstring>
#include <exception>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "engine/api.hpp"
#include "engine/deferred_signals.hpp"
#include "engine/folder.hpp"
#include "engine/output.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/version.hpp"
#include "engine/wear_stage.hpp"
#include "python/convert.hpp"
#include "python/tables.hpp"

namespace py = pybind11;
namespace fs = std::filesystem;
using nlohmann::json;

namespace fretwear::python {
namespace {

// The module's exceptions and warning category, made at import.
PyObject* g_scene_error = nullptr;
PyObject* g_convergence_error = nullptr;
PyObject* g_warning = nullptr;

// Text from the engine as str. A problem may quote the scene's own bytes, which need not be UTF-8: those are kept as
// Python keeps undecodable bytes of file names (surrogateescape).
py::str text(const std::string& s) {
  return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(s.data(), py::ssize_t(s.size()), "surrogateescape"));
}

py::list texts(const std::vector<std::string>& lines) {
  py::list list;
  for (const auto& line : lines) list.append(text(line));
  return list;
}

[[noreturn]] void raise_scene_error(const std::vector<std::string>& problems) {
  std::string message = "the scene is invalid:";
  for (const auto& p : problems) message += "\n  " + p;
  py::object error = py::reinterpret_borrow<py::object>(g_scene_error)(text(message));
  error.attr("problems") = texts(problems);
  PyErr_SetObject(g_scene_error, error.ptr());
  throw py::error_already_set();
}

[[noreturn]] void raise_convergence_error(const std::string& message) {
  PyErr_SetObject(g_convergence_error, text(message).ptr());
  throw py::error_already_set();
}

// A scene argument: a dict (its name "scene" unless it gives one), or the path of a scene file (str or os.PathLike)
// read as the command line reads it. scene_file: where it was read, for the output folder's rules.
struct SceneArgument {
  Scene scene;
  fs::path scene_file;
};

// A path as str, bytes or os.PathLike, as the file system takes it: its bytes (os.fsencode), whatever their encoding.
fs::path path_argument(py::handle arg) {
  return fs::path(py::module_::import("os").attr("fsencode")(arg).cast<py::bytes>().cast<std::string>());
}

// The path quoted as JSON writes it ("a\u0000b"), its bytes that are not UTF-8 shown as U+FFFD: what a problem shows of
// a path the file system cannot take.
std::string quoted(const fs::path& path) {
  return json(path.string()).dump(-1, ' ', false, json::error_handler_t::replace);
}

// The problems of an invalid scene read from scene_file ("" for a dict), and after them those of the folder `output`
// names: `output` is an argument of its own here, so its folder is known whatever the scene's keys say, and every
// problem is raised at once, as the command line lists them.
[[noreturn]] void raise_with_folder(std::vector<std::string> problems, const fs::path& scene_file,
                                    const std::optional<fs::path>& output) {
  if (output) {
    const std::vector<std::string> more = output_dir_problems(*output, scene_file, OutputCommand::run);
    problems.insert(problems.end(), more.begin(), more.end());
  }
  raise_scene_error(problems);
}

// The scene argument; when it is invalid, a SceneError with its problems and those of the folder `output` names.
SceneArgument scene_argument(py::handle arg, const std::optional<fs::path>& output) {
  const py::module_ os = py::module_::import("os");
  fs::path scene_file;
  try {
    if (py::isinstance<py::str>(arg) || py::isinstance<py::bytes>(arg) || py::isinstance(arg, os.attr("PathLike"))) {
      const fs::path path = path_argument(arg);
      if (holds_nul(path.native())) raise_with_folder({fmt::format("{}: {}", quoted(path), kHoldsNul)}, {}, output);
      scene_file = path;
      if (path == kStdinScene)  // the command line's word for standard input, which a Python caller reads itself
        raise_with_folder({"\"-\": is standard input on the command line; here give the scene as a dict (e.g. "
                           "json.load(sys.stdin)), or the path of a scene file (./- for a file named -)"},
                          {}, output);
      return {load_scene(path), path};
    }
    if (!py::isinstance<py::dict>(arg))
      raise_with_folder({fmt::format("(top): the scene is a {}; give a dict (or the path of a scene file)",
                                     std::string(py::str(py::type::handle_of(arg).attr("__name__"))))},
                        {}, output);
    std::vector<std::string> problems, nulled;
    const json j = to_json(arg, problems, nulled);
    if (problems.empty()) return {parse_scene(j), {}};
    // A value no JSON holds is null in j: the parser still reports the scene's other problems, all but its own
    // about those paths and what lies under them.
    try {
      parse_scene(j);
    } catch (const SceneError& e) {
      for (const std::string& p : e.problems()) {
        const std::string path = p.substr(0, p.find(": "));
        const bool covered = std::any_of(nulled.begin(), nulled.end(), [&](const std::string& at) {
          return at == "(top)" || path == at || path.starts_with(at + ".") || path.starts_with(at + "[");
        });
        if (!covered) problems.push_back(p);
      }
    }
    raise_with_folder(problems, {}, output);
  } catch (const SceneError& e) {
    raise_with_folder(e.problems(), scene_file, output);
  }
}

// The folder an `output` argument names; scene.output_dir is replaced by it.
std::optional<fs::path> output_argument(py::handle output) {
  if (output.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(output) && !py::isinstance<py::bytes>(output) &&
      !py::isinstance(output, py::module_::import("os").attr("PathLike")))
    throw py::type_error(fmt::format("output must be a folder's path (str, bytes or os.PathLike) or None, not {}",
                                     std::string(py::str(py::type::handle_of(output).attr("__name__")))));
  return path_argument(output);
}

void warn(const std::vector<Warning>& warnings) {
  for (const Warning& w : warnings)
    // Level 1: fretwear's functions have no Python frame of their own, so the warning is the caller's line.
    if (PyErr_WarnEx(g_warning, (w.code + ": " + w.message).c_str(), 1) < 0) throw py::error_already_set();
}

// What the checks before solving find: every problem, as the command line's preflight.
std::vector<std::string> problems_before_solving(const Scene& scene, const fs::path& scene_file, bool output,
                                                 Preflight* checked) {
  std::vector<std::string> problems;
  py::gil_scoped_release release;
  if (output) problems = output_dir_problems(scene, scene_file, OutputCommand::run);
  const std::vector<std::string> physics = physics_problems(scene, checked);
  problems.insert(problems.end(), physics.begin(), physics.end());
  return problems;
}

// The runs in progress, counted with the GIL held. The interpreter, as it exits, takes a thread that asks for the
// GIL off its stack without unwinding it (pthread_exit), which a run's C++ frames do not survive (std::terminate).
// Python waits for its threads before it exits, but not for one whose join() a Ctrl-C interrupted, and not for a
// daemon thread: so at exit (atexit, below) the runs still going are asked to stop, at their next step or part, and
// awaited; a run asked for after that is refused. Both raise SystemExit in the run's thread, which a thread ends on
// without a word.
int g_runs = 0;
thread_local int t_runs = 0;  // those of this thread (a progress callable may run fretwear again)
bool g_exiting = false;
constexpr const char* kExiting = "fretwear.run stopped: the Python interpreter is exiting";

class RunInProgress {
 public:
  RunInProgress() {
    if (g_exiting) {
      PyErr_SetString(PyExc_SystemExit, kExiting);
      throw py::error_already_set();
    }
    ++g_runs;
    ++t_runs;
  }
  ~RunInProgress() {
    --g_runs;
    --t_runs;
  }
  RunInProgress(const RunInProgress&) = delete;
  RunInProgress& operator=(const RunInProgress&) = delete;
};

void stop_runs_at_exit() {
  g_exiting = true;
  while (g_runs > t_runs) {
    py::gil_scoped_release release;  // for the runs to reach their next check, and to return
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

class Result {
 public:
  py::object summary = py::dict(), scene = py::dict(), output = py::none();
  std::map<std::string, py::object> tables;
  py::object table(const std::string& name) const {
    const auto it = tables.find(name);
    return it == tables.end() ? py::none() : it->second;
  }
};

// The run's stop hooks: at each step boundary of the wear stage and between the parts of the others
// (WearControl::stop_now), Python's pending signals are run (with the GIL taken for that moment), and the caller's
// progress callable, if any, is called with where the run stands. A handler or a callable that raises (Ctrl-C's
// KeyboardInterrupt) stops the run there; the exception is kept and raised once the run has returned. Copies of the
// hooks share the callable (a shared_ptr, whose copies touch no Python reference count without the GIL); the one in
// run() is the last to go, with the GIL held.
class SignalCheck {
 public:
  explicit SignalCheck(py::object progress) : progress_(std::make_shared<py::object>(std::move(progress))) {}
  bool operator()(const WearProgress& p) { return check("wear", p.cycles, p.total, "cycles"); }
  bool operator()(const StagePart& p) { return check(p.stage, p.done, p.total, p.unit); }

  bool check(const char* stage, double done, double total, const char* unit) {
    py::gil_scoped_acquire acquire;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();
      if (g_exiting) {
        PyErr_SetString(PyExc_SystemExit, kExiting);
        throw py::error_already_set();
      }
      // The wear stage asks again at a record that ends a step: the callable hears of each place once. A history's
      // march, told against the most it may march, ends with what it marched as both done and total.
      if (!progress_->is_none() && total > 0.0 &&
          (last_->stage != stage || last_->done != done || last_->total != total)) {
        *last_ = {stage, done, total};
        (*progress_)(stage, done, total, unit);
      }
    } catch (py::error_already_set& e) {
      *pending_ = std::move(e);
      return true;
    }
    return false;
  }
  std::shared_ptr<std::optional<py::error_already_set>> pending_ =
      std::make_shared<std::optional<py::error_already_set>>();

 private:
  struct Told {
    std::string stage;
    double done = -1.0, total = -1.0;
  };
  std::shared_ptr<py::object> progress_;
  std::shared_ptr<Told> last_ = std::make_shared<Told>();
};

Result run(py::handle scene_arg, py::handle output_arg, py::object progress) {
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error(fmt::format("progress must be a callable (stage, done, total, unit) or None, not {}",
                                     py::str(py::type::of(progress)).cast<std::string>()));
  const RunInProgress counted;
  const std::optional<fs::path> output = output_argument(output_arg);
  SceneArgument arg = scene_argument(scene_arg, output);
  Scene& scene = arg.scene;
  if (output) scene.output_dir = *output;
  SignalCheck check(progress);
  Preflight checked;
  checked.stop = check;  // the checks march a wear scene's first cycle
  std::vector<std::string> problems;
  try {
    problems = problems_before_solving(scene, arg.scene_file, output.has_value(), &checked);
  } catch (const StopRequested&) {
    (*check.pending_)->restore();
    throw py::error_already_set();
  }
  if (!problems.empty()) raise_scene_error(problems);
  warn(checked.warnings);

  WearControl control;
  control.stop_requested = check;
  control.stop_now = check;
  RunResult result;
  json summary;
  std::string failure;  // a ConvergenceError's message, raised with the GIL held
  bool converged = true;
  // Problems found once solving has begun, raised with the GIL held as a SceneError: the output folder's when it
  // cannot be written after all (a SceneError of the engine's, whose problems are taken as they are, not its message
  // that already says "the scene is invalid"), or the engine's InputError (a worn contact grown to the window's end).
  std::vector<std::string> refused;
  {
    py::gil_scoped_release release;
    try {
      try {
        result = Simulation(scene).run(&control, &checked.solved);
        if (!check.pending_->has_value()) {
          result.warnings.insert(result.warnings.begin(), checked.warnings.begin(), checked.warnings.end());
          if (output) {
            OutputFolder out(scene.output_dir, OutputCommand::run);
            const DeferredStopSignals hold;  // the results are written whole, or not at all
            summary = write_results(scene, result, out);
            out.commit();
          } else {
            summary = make_summary(scene, result);
            summary["plots"] = json::array();  // none drawn
          }
        }
      } catch (const ConvergenceError& e) {
        converged = false;
        failure = e.what();
        if (output) {  // a folder that cannot be written after all is the SceneError below, as on the command line
          OutputFolder out(scene.output_dir, OutputCommand::run);
          const DeferredStopSignals hold;
          write_not_converged(scene, e, checked.warnings, out);
          out.commit();
        }
      }
    } catch (const SceneError& e) {
      refused = e.problems();
    } catch (const InputError& e) {
      refused = {e.what()};
    } catch (const StopRequested&) {  // the pending exception below says why
    }
  }
  if (check.pending_->has_value()) {
    (*check.pending_)->restore();
    throw py::error_already_set();
  }
  if (!refused.empty()) raise_scene_error(refused);
  if (!converged) raise_convergence_error(failure);
  // The preflight's warnings were given before the run.
  warn(std::vector<Warning>(result.warnings.begin() + std::ptrdiff_t(checked.warnings.size()), result.warnings.end()));

  Result r;
  r.summary = to_python(summary);
  Scene resolved = scene;  // as write_results resolves it: the window and the datum as used
  resolved.window = std::pair(result.normal.grid.x_min, result.normal.grid.x_max);
  if (result.cycle) resolved.reference_depth = result.cycle->reference_depth;
  r.scene = to_python(resolved.to_json());
  r.output = output ? py::object(py::module_::import("pathlib").attr("Path")(output->string())) : py::none();
  for (auto& [name, table] : result_tables(scene, result)) r.tables[name] = py::cast(std::move(table));
  return r;
}

// Pickling by the state (__getstate__, __setstate__) at every protocol. Protocols 0 and 1 would otherwise rebuild
// the object through object.__new__, which a pybind11 class refuses (an abort); protocol 2's reduction
// (copyreg.__newobj__, the class, the state) is read by every protocol.
py::object reduce_by_state(py::handle self, int protocol) {
  return py::module_::import("builtins").attr("object").attr("__reduce_ex__")(self, std::max(protocol, 2));
}

// Every Table and Result Python holds is a constructed one. pybind11's own __new__ allocates an instance whose C++
// object only __init__ makes, and these classes have none (fretwear.run makes them): Cls.__new__(Cls), which
// copyreg.__newobj__ calls to unpickle and anyone may call, would hand out an object whose every attribute reads
// memory never written. Their __new__ makes an empty one instead (a table of no columns, a result of an empty
// summary), which __setstate__ fills when unpickled. The classes are final, so the class is always Cls itself.
// Both doors are set: Cls.__new__ as Python finds it in the class's dict (PyType_Ready gave the class none of its
// own), and the type's slot, which Cls() reaches (then refused by __init__) and which makes pybind11's base
// __new__ refuse the class as not safe for it.
template <class T>
py::object new_empty(py::handle cls, const py::args& args, const py::kwargs& kwargs) {
  const py::type type = py::type::of<T>();
  const std::string name = "fretwear." + std::string(py::str(type.attr("__name__")));
  if (!cls.is(type))
    throw py::type_error(fmt::format("{}.__new__({}): not {}", name, std::string(py::repr(cls)), name));
  if (!args.empty() || !kwargs.empty()) throw py::type_error(name + "() takes no arguments: fretwear.run makes one");
  return py::cast(T());
}

template <class T>
void new_makes_an_empty_one(py::class_<T>& cls) {
  auto* type = reinterpret_cast<PyTypeObject*>(cls.ptr());
  type->tp_new = [](PyTypeObject* subtype, PyObject* args, PyObject* kwargs) -> PyObject* {
    try {
      return new_empty<T>(reinterpret_cast<PyObject*>(subtype), py::reinterpret_borrow<py::args>(args),
                          kwargs ? py::reinterpret_borrow<py::kwargs>(kwargs) : py::kwargs())
          .release()
          .ptr();
    } catch (py::error_already_set& e) {
      e.restore();
    } catch (const py::builtin_exception& e) {
      e.set_error();
    } catch (const std::exception& e) {
      PyErr_SetString(PyExc_RuntimeError, e.what());
    }
    return nullptr;
  };
  const py::object new_ = py::module_::import("builtins").attr("staticmethod")(py::cpp_function(
      &new_empty<T>, py::name("__new__"), "an empty one, for __setstate__ to fill (fretwear.run makes a full one)"));
  if (PyDict_SetItemString(type->tp_dict, "__new__", new_.ptr()) != 0) throw py::error_already_set();
  PyType_Modified(type);
}

// __setstate__, which unpickling calls on what __new__ made. Bound under another name: pybind11 takes a method named
// __setstate__ for a constructor, and a constructor called on a constructed object does nothing.
template <class T, class F>
void set_state_by(py::class_<T>& cls, F&& set) {
  cls.attr("__setstate__") = py::cpp_function(std::forward<F>(set), py::name("set_state"), py::is_method(cls),
                                              py::arg("state"), "the object again from what __getstate__ gave");
}

py::list validate(py::handle scene_arg, py::handle output_arg) {
  std::vector<std::string> problems;
  try {
    const std::optional<fs::path> output = output_argument(output_arg);
    SceneArgument arg = scene_argument(scene_arg, output);
    if (output) arg.scene.output_dir = *output;
    Preflight checked;
    problems = problems_before_solving(arg.scene, arg.scene_file, output.has_value(), &checked);
    // As `fretwear validate` prints them (long_run, window_reached, wear_per_cycle).
    if (problems.empty()) warn(checked.warnings);
  } catch (py::error_already_set& e) {
    if (!e.matches(g_scene_error)) throw;
    return e.value().attr("problems");
  }
  return texts(problems);
}

py::object defaults(const std::optional<std::string>& effect) {
  try {
    return to_python(default_scene_json(effect.value_or("")));
  } catch (const InputError& e) {
    // The engine words it for the command line's option (--effect: ...); here it is the argument `effect`.
    std::string message = e.what();
    if (message.starts_with("--effect: ")) message = "effect: " + message.substr(std::strlen("--effect: "));
    PyErr_SetObject(PyExc_ValueError, text(message).ptr());
    throw py::error_already_set();
  }
}

const char* kRunDoc = R"doc(run(scene, output=None, *, progress=None) -> Result

Run a scene: the normal contact, then each effect it asks for (the load cycle, wear, the stresses with the fatigue
measures, the crack's stress intensity factors, the life), all in memory, as `fretwear run` does.

scene   a dict in the scene format (docs/SCENES.md; fretwear.defaults() gives every key), or the path of a scene
        file. Lengths in m, loads per unit length in N/m, stresses and moduli in Pa, cycles as counts.
output  None (the default): nothing is written, and the scene's output.dir is ignored. A folder (str or
        pathlib.Path): the results are also written there exactly as the command line writes them (summary.json,
        the CSV files, the plots, index.html, scene.resolved.json), under the same rules for output folders.
progress  None, or a callable progress(stage, done, total, unit), called as the run goes: at every step of the
        wear stage ("wear", cycles done, cycles asked for, "cycles") and at every part of the stress, crack and life
        stages (e.g. "stress", 120, 322, "map columns"), the last call of each stage with done == total. It runs
        with the GIL held, between the solver's steps: keep it short. An exception it raises stops the run there
        and is raised by run(), nothing written.

Returns a Result: `summary` (the dict of summary.json: SI units, every number the command line reports), `scene`
(the resolved scene) and one table of numpy arrays per CSV file, e.g. result.contact.x (m), result.contact.p (Pa);
a table the run does not produce is None. print(result.contact) lists its columns with units.

Raises SceneError (its `problems` each name a JSON path) for an invalid scene, with nothing computed or written;
ConvergenceError where a solver did not converge (the command line's exit status 3); KeyboardInterrupt when Ctrl-C
stops a wear run (at its next step; nothing is written). The solve runs without the GIL. Warnings about results the
grid cannot resolve are issued as fretwear.FretwearWarning (and listed in summary["warnings"]).

Example:
    import fretwear
    result = fretwear.run(fretwear.defaults("wear"))
    print(result.summary["wear"]["worn_area"], result.wear_history.worn_area[-1])   # m^2
)doc";

const char* kValidateDoc = R"doc(validate(scene, output=None) -> list[str]

Every problem of a scene that fretwear.run would refuse, each "json.path: what is wrong; what is allowed" (the
path first, "(top)" for the scene itself), or [] for a valid scene. Makes every check run makes before solving: the
format, the ranges, the physics that shows before solving (the contact strain, the cycle's route, a wear run's
estimated time, refused past a day) and, when `output` names a folder, the output folder's rules. Writes nothing.
A valid scene's warnings before solving (a wear run estimated past an hour, a gross-slip scar near the window's
end) are given as FretwearWarning, as run gives them.
)doc";

// defaults' docstring, its numbers and its effects those of the default scene itself.
std::string defaults_doc() {
  const json d = default_scene_json();
  const json& both = d.at("materials").at("both");
  std::string effects;
  for (const std::string& e : default_effect_words()) effects += (effects.empty() ? "\"" : "\", \"") + e;
  return fmt::format(R"doc(defaults(effect=None) -> dict

The complete default scene, PHYSICS.md's Hertz contact (a cylinder of radius R = {:g} m on a flat under P = {:g} N/m,
both bodies of E = {:g} Pa, nu = {:g}), with every effect and every key written out, as `fretwear defaults` prints
it; or, given an effect, with that effect and the load cycle it needs. The effects:
    {}"
Units as in docs/SCENES.md (m, N/m, Pa). Raises ValueError for another effect.
)doc",
                     d.at("profile").at("R").get<double>(), d.at("load").at("P").get<double>(),
                     both.at("E").get<double>(), both.at("nu").get<double>(), effects);
}

// A table's column names, in the CSV's order.
std::vector<std::string> column_names(const Table& t) {
  std::vector<std::string> names;
  for (const Column& c : t.columns()) names.push_back(c.name);
  return names;
}

}  // namespace
}  // namespace fretwear::python

PYBIND11_MODULE(fretwear, m) {
  using namespace fretwear::python;
  m.doc() = R"doc(fretwear: fretting in plane elastic contacts, from one scene (docs/PYTHON.md).

    import fretwear
    result = fretwear.run(fretwear.defaults("wear"))      # a dict in, nothing written
    print(result.summary["contact"]["p_max"], result.contact.p.max())   # Pa

run(scene, output=None) runs a scene in memory; validate(scene) lists its problems; defaults(effect=None) gives the
complete default scene. Errors: SceneError (with .problems), ConvergenceError. Units are SI throughout.)doc";
  m.attr("__version__") = fretwear::kVersion;

  // Every function-local static that calls into Python is initialised here, while the import holds the GIL and no
  // other thread can call the module yet. Initialised later, by the first run that makes an array, such a static
  // would hang two threads running at once: the first to reach it holds its guard while the import inside it
  // (numpy.core.multiarray, for numpy's C API) hands the GIL on, and the second, holding the GIL, waits on the guard.
  // pybind11's npy_api::get() is that static (every py::array_t made in tables.cpp reaches it).
  py::detail::npy_api::get();

  py::module_::import("atexit").attr("register")(py::cpp_function(&stop_runs_at_exit));
  // A forked child has only the thread that forked: the parent's other runs are not its own.
  py::module_::import("os").attr("register_at_fork")(py::arg("after_in_child") = py::cpp_function([] {
                                                       g_runs = t_runs;
                                                     }));

  g_scene_error = PyErr_NewExceptionWithDoc(
      "fretwear.SceneError",
      "An invalid scene: nothing was computed or written. `problems` lists every problem, each "
      "\"json.path: what is wrong; what is allowed\" (the command line's exit status 2).",
      PyExc_ValueError, nullptr);
  g_convergence_error = PyErr_NewExceptionWithDoc(
      "fretwear.ConvergenceError",
      "A solver stopped short of its tolerance; the message names the stage, the cycle and the residual (the command "
      "line's exit status 3). With `output`, summary.json says \"status\": \"not_converged\".",
      PyExc_RuntimeError, nullptr);
  g_warning = PyErr_NewExceptionWithDoc(
      "fretwear.FretwearWarning",
      "A result the grid cannot resolve, a closed form missed, a long run: \"code: message\" (docs/SCENES.md, "
      "\"Warnings\"); summary[\"warnings\"] lists them too.",
      PyExc_UserWarning, nullptr);
  m.attr("SceneError") = py::handle(g_scene_error);
  m.attr("ConvergenceError") = py::handle(g_convergence_error);
  m.attr("FretwearWarning") = py::handle(g_warning);

  auto table = py::class_<Table>(m, "Table", py::is_final(),
                                 R"doc(One CSV file's fields as numpy arrays: table.x, table["x"]; the same rows and
columns as the file, each column named by its header without the unit ("p_Pa" is p) and in that unit (SI; the
critical plane's angle in degrees). An empty CSV value is NaN. The arrays are read-only (every access hands out
the same one): table.x.copy() gives an array to change. print(table) lists the columns with their units;
table.units maps each to its unit; pandas.DataFrame(table.to_dict()) makes a data frame. Iterating a table gives
its column names, as a dict's keys ("p" in table, dict(table)); len(table) is the number of rows. A table pickles
(its arrays read-only again when unpickled).)doc")
      .def("__getattr__",
           [](const Table& t, const std::string& name) -> py::object {
             for (const Column& c : t.columns())
               if (c.name == name) return c.values;
             throw py::attribute_error(fmt::format("{} has no column {}", t.file(), quoted_name(name)));
           })
      // As a dict's: a key that is not a column name (of whatever type) is a KeyError, and not in the table.
      .def("__getitem__",
           [](const Table& t, py::handle key) {
             if (!py::isinstance<py::str>(key))
               throw py::key_error(fmt::format("{} has no column {}; its columns are named by str", t.file(),
                                               std::string(py::repr(key))));
             return t.column(key.cast<std::string>()).values;
           })
      .def("__contains__",
           [](const Table& t, py::handle key) {
             if (!py::isinstance<py::str>(key)) return false;
             const auto name = key.cast<std::string>();
             for (const Column& c : t.columns())
               if (c.name == name) return true;
             return false;
           })
      .def("__len__", &Table::rows, "the number of rows")
      .def("__dir__",
           [](const Table& t) {
             std::vector<std::string> names{"columns", "file", "keys", "rows", "to_dict", "units"};
             for (std::string& c : column_names(t)) names.push_back(std::move(c));
             return names;
           })
      .def(
          "__iter__", [](const Table& t) { return py::iter(py::cast(column_names(t))); },
          "the column names, in the CSV's order, as a dict's keys")
      .def("keys", &column_names, "the column names, in the CSV's order")
      .def_property_readonly("columns", &column_names, "the column names, in the CSV's order")
      .def_property_readonly(
          "units",
          [](const Table& t) {
            py::dict d;
            for (const Column& c : t.columns()) d[py::str(c.name)] = c.unit;
            return d;
          },
          "each column's unit: \"m\", \"Pa\", \"N/m\", \"1\" for a count or a pure number, \"\" for a label")
      .def_property_readonly("rows", &Table::rows, "the number of rows")
      .def_property_readonly("file", &Table::file, "the CSV file the command line writes it to")
      .def("to_dict",
           [](const Table& t) {
             py::dict d;
             for (const Column& c : t.columns()) d[py::str(c.name)] = c.values;
             return d;
           },
           "{column: numpy array}, in the CSV's order (pandas.DataFrame(table.to_dict()))")
      .def("__repr__", &Table::describe)
      .def("__getstate__", &Table::state)
      .def("__reduce_ex__", &reduce_by_state, py::arg("protocol"));
  new_makes_an_empty_one(table);
  set_state_by(table, [](Table& t, const py::tuple& state) { t = Table::from_state(state); });

  std::string result_doc = R"doc(What fretwear.run returns.

summary  the dict of summary.json (SI units; "plots" is empty unless run wrote them into `output`)
scene    the resolved scene (scene.resolved.json): every default filled in, the window as used
output   the folder written (pathlib.Path), or None
tables   {name: Table} of the tables below that the run produced

One attribute per CSV file, None when the run does not produce it:
)doc";
  for (const auto& [name, line] : table_names()) result_doc += fmt::format("  {:<15}{}\n", name, line);
  auto result = py::class_<Result>(m, "Result", py::is_final(), result_doc.c_str())
                    .def_readonly("summary", &Result::summary, "the dict of summary.json (SI units)")
                    .def_readonly("scene", &Result::scene, "the resolved scene, every default filled in")
                    .def_readonly("output", &Result::output, "the folder written (pathlib.Path), or None")
                    .def_property_readonly(
                        "tables",
                        [](const Result& r) {
                          py::dict d;
                          for (const auto& [name, t] : r.tables) d[py::str(name)] = t;
                          return d;
                        },
                        "{name: Table} of the tables the run produced")
                    .def("__repr__",
                         [](const Result& r) {
                           std::string names;
                           for (const auto& [name, t] : r.tables) names += (names.empty() ? "" : ", ") + name;
                           return fmt::format("<fretwear.Result of scene \"{}\": {}>",
                                              std::string(py::str(r.summary.attr("get")("scene", ""))), names);
                         })
                    // (summary, scene, output, {name: Table}): a Result pickles whole, so that a process of a pool
                    // can return one.
                    .def("__getstate__",
                         [](const Result& r) {
                           py::dict tables;
                           for (const auto& [name, t] : r.tables) tables[py::str(name)] = t;
                           return py::make_tuple(r.summary, r.scene, r.output, tables);
                         })
                    .def("__reduce_ex__", &reduce_by_state, py::arg("protocol"));
  new_makes_an_empty_one(result);
  set_state_by(result, [](Result& self, const py::tuple& state) {
    if (state.size() != 4 || !py::isinstance<py::dict>(state[0]) || !py::isinstance<py::dict>(state[1]) ||
        !py::isinstance<py::dict>(state[3]))
      throw std::runtime_error(
          "a pickled fretwear.Result holds 4 items: summary, scene, output, tables, the first, second and last dicts");
    Result r;
    r.summary = state[0];
    r.scene = state[1];
    r.output = state[2];
    for (const auto& [name, t] : state[3].cast<py::dict>()) {
      if (!py::isinstance<Table>(t))
        throw std::runtime_error("a pickled fretwear.Result holds a table that is not one");
      r.tables[name.cast<std::string>()] = py::reinterpret_borrow<py::object>(t);
    }
    self = std::move(r);
  });
  for (const auto& [name, line] : table_names()) {
    const std::string key = name;
    result.def_property_readonly(
        name.c_str(), [key](const Result& r) { return r.table(key); }, line.c_str());
  }

  {
    // Each docstring opens with its own signature, in the types a caller gives (pybind11's would say "handle").
    py::options options;
    options.disable_function_signatures();
    m.def("run", &run, py::arg("scene"), py::arg("output") = py::none(), py::kw_only(),
          py::arg("progress") = py::none(), kRunDoc);
    m.def("validate", &validate, py::arg("scene"), py::arg("output") = py::none(), kValidateDoc);
    m.def("defaults", &defaults, py::arg("effect") = py::none(), defaults_doc().c_str());
  }
}
