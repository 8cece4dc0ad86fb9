// Output folders (SCENES.md, Additions: "fretwear writes only into folders it made"). output.dir is refused with
// exit 2 and a message naming it, before anything is computed and with nothing of the user's touched, when it is an
// existing file, a folder that holds anything and has no .fretwear marker, the scene's own folder or one that holds
// the scene, ".", "..", a path ending in "/..", "/", or any ancestor of the working folder. A missing folder, an
// empty one or one fretwear made is accepted, and the folder made holds the marker. Each command owns its part:
// `run` output.dir, `convergence` <output.dir>/convergence/, `sweep` <output.dir>/sweep/; none removes another's.
// A folder fretwear made is replaced only while it holds nothing but what its marker lists (or, for a marker that
// lists nothing, the names fretwear writes); a folder named like a staging folder beside it is removed only when its
// marker says it is the staging folder of a process of this host that has ended.
#include <algorithm>
#include <csignal>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// Where a case puts the scene (relative to the working folder) and what it names as output.dir (nothing: the
// default output/<name>); `plots_only` gives "output": {"plots": false} and no dir; `wear` a wear scene, which keeps
// a checkpoint beside output.dir.
struct Setup {
  std::string scene = "s.json";
  std::optional<std::string> dir = std::nullopt;
  bool plots_only = false;
  bool wear = false;
};

// A case: what it prepares in the tree (folders, files, earlier runs), the command it runs, and what a refusal's
// message must say besides output.dir.
struct FolderCase {
  std::string label;
  std::function<Setup(const Scratch&)> prepare;
  std::string command = "run";
  std::string says = "";
};

std::string scene_text(const Setup& setup, const std::string& name = "h") {
  json scene = setup.wear ? wear_scene() : base_scene();
  scene["name"] = name;
  if (setup.dir) scene["output"] = {{"dir", *setup.dir}};
  if (setup.plots_only) scene["output"] = {{"plots", false}};
  return scene.dump();
}

// The command line of each command, cheap: a convergence study over two grids, a sweep of two runs.
std::vector<std::string> command_line(const std::string& command, const std::string& scene) {
  if (command == "convergence") return {"convergence", scene, "--from", "64", "--to", "128", "-q"};
  if (command == "sweep") return {"sweep", scene, "--vary", "load.P=5e4,1e5", "--jobs", "1", "-q"};
  return {command, scene, "-q"};
}

// What the command leaves in the folder it was given, relative to it.
std::string result_of(const std::string& command) {
  if (command == "convergence") return "convergence/convergence.csv";
  if (command == "sweep") return "sweep/sweep.csv";
  return "summary.json";
}

// Runs a scene beforehand, as a case's preparation: it must complete.
void run_before(const Scratch& s, const std::string& scene, const std::string& text) {
  s.write(scene, text);
  const Outcome r = s.fretwear({"run", scene, "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), "the preparing run: " << r.describe());
  std::filesystem::remove(s.work / scene);
}

void link(const Scratch& s, const std::string& target, const std::string& name) {
  std::filesystem::create_directory_symlink(target, s.work / name);
}

// Refused: exit 2 naming output.dir, the tree as it was (nothing new, nothing changed), and `validate` refusing
// it as well (validate 0 must mean run does not exit 2).
void check_refused(const FolderCase& c) {
  INFO("case: " << c.label << " (" << c.command << ")");
  Scratch s;
  const Setup setup = c.prepare(s);
  s.write(setup.scene, scene_text(setup));
  const Snapshot before = s.snapshot();
  const Outcome v = s.fretwear({"validate", setup.scene, "-q"});
  const Outcome r = s.fretwear(command_line(c.command, setup.scene));
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(!r.crashed(), r.describe());
  CHECK_MESSAGE(r.exited(kInvalid), "want exit 2, got " << r.describe());
  CHECK_MESSAGE(r.err.find("output.dir") != std::string::npos, "the message should name output.dir: " << r.describe());
  CHECK_MESSAGE(r.err.find(c.says) != std::string::npos,
                "the message should say \"" << c.says << "\": " << r.describe());
  CHECK_MESSAGE(changes(before, after).empty(), "the tree changed: " << join(changes(before, after)));
  CHECK_MESSAGE(!v.crashed(), "validate: " << v.describe());
  CHECK_MESSAGE(v.exited(kInvalid), "validate should refuse what run refuses: " << v.describe());
}

// Accepted: exit 0, the results and the marker in the folder, everything of the user's outside it as it was, no
// staging folder or temporary file left. `folder` is where the results land, relative to the working folder.
void check_accepted(const FolderCase& c, const std::string& folder) {
  INFO("case: " << c.label << " (" << c.command << ")");
  Scratch s;
  const Setup setup = c.prepare(s);
  s.write(setup.scene, scene_text(setup));
  const Snapshot before = s.snapshot();
  const Outcome v = s.fretwear({"validate", setup.scene, "-q"});
  const Outcome r = s.fretwear(command_line(c.command, setup.scene));
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(!r.crashed(), r.describe());
  CHECK_MESSAGE(r.exited(kDone), "want exit 0, got " << r.describe());
  CHECK_MESSAGE(v.exited(kDone), "validate: " << v.describe());
  const std::filesystem::path out = s.work / folder;
  CHECK_MESSAGE(std::filesystem::exists(out / result_of(c.command)), (out / result_of(c.command)).string());
  CHECK_MESSAGE(std::filesystem::exists(out / ".fretwear"), "no marker in " << out.string());
  const std::string exempt = (s.work / folder).lexically_normal().lexically_relative(s.tree).generic_string();
  std::vector<std::string> touched;
  for (const auto& line : changes(before, after, {exempt}))
    if (line.rfind("new ", 0) != 0) touched.push_back(line);
  CHECK_MESSAGE(touched.empty(), "the user's files were touched: " << join(touched));
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
}

// The refusals every command shares.
std::vector<FolderCase> refusals_of_every_command(const std::string& command) {
  return {
      {"an existing file", [](const Scratch&) { return Setup{"s.json", "notes.txt"}; }, command},
      {"a folder of the user's holding a file", [](const Scratch&) { return Setup{"s.json", "keep"}; }, command},
      {"the default output/<name> holding the user's files",
       [](const Scratch& s) {
         s.write("output/h/notes.txt", "the user's, not fretwear's\n");
         return Setup{};
       },
       command},
      {"\".\"", [](const Scratch&) { return Setup{"s.json", "."}; }, command},
      {"\"..\"", [](const Scratch&) { return Setup{"s.json", ".."}; }, command},
      {"the parent of the working folder by its absolute path",
       [](const Scratch& s) { return Setup{"s.json", s.home.string()}; }, command},
  };
}

}  // namespace

TEST_CASE("output.dir refused for run: files, the user's folders, the scene's folder, . and ..") {
  const std::vector<FolderCase> cases = {
      {"an existing file", [](const Scratch&) { return Setup{"s.json", "notes.txt"}; }},
      {"an existing file by its absolute path",
       [](const Scratch& s) { return Setup{"s.json", (s.work / "notes.txt").string()}; }},
      {"a folder under an existing file", [](const Scratch&) { return Setup{"s.json", "notes.txt/results"}; }},
      {"a folder of the user's holding a file", [](const Scratch&) { return Setup{"s.json", "keep"}; }},
      {"the same folder with a trailing slash", [](const Scratch&) { return Setup{"s.json", "keep/"}; }},
      {"the same folder through ..", [](const Scratch&) { return Setup{"s.json", "keep/../keep"}; }},
      {"a link to the same folder",
       [](const Scratch& s) {
         link(s, "keep", "keep-link");
         return Setup{"s.json", "keep-link"};
       }},
      {"a folder holding only an empty folder",
       [](const Scratch& s) {
         std::filesystem::create_directories(s.work / "holder" / "empty");
         return Setup{"s.json", "holder"};
       }},
      {"a folder holding only a hidden file",
       [](const Scratch& s) {
         s.write("hidden/.profile", "export PATH\n");
         return Setup{"s.json", "hidden"};
       }},
      {"the default output/<name> holding the user's files",
       [](const Scratch& s) {
         s.write("output/h/notes.txt", "the user's, not fretwear's\n");
         return Setup{};
       }},
      {"the scene's own folder", [](const Scratch&) { return Setup{"scenes/s.json", "scenes"}; }},
      {"the scene's own folder by its absolute path",
       [](const Scratch& s) { return Setup{"scenes/s.json", (s.work / "scenes").string()}; }},
      {"the scene's own folder, made by fretwear",
       [](const Scratch& s) {
         run_before(s, "first.json", scene_text(Setup{"first.json", "made"}));
         return Setup{"made/s.json", "made"};
       }},
      {"a folder made by fretwear holding the scene deeper down",
       [](const Scratch& s) {
         run_before(s, "first.json", scene_text(Setup{"first.json", "made"}));
         return Setup{"made/sub/s.json", "made"};
       }},
      {"a folder of the user's holding the scene's folder",
       [](const Scratch&) { return Setup{"scenes/deep/s.json", "scenes"}; }},
      {"a folder under /proc", [](const Scratch&) { return Setup{"s.json", "/proc/fretwear"}; }},
  };
  for (const auto& c : cases) check_refused(c);
}

TEST_CASE("output.dir refused for run: the working folder and its ancestors however spelt") {
  // Every path here resolves inside the scratch tree: a program that wrongly replaces it harms only the tree.
  const std::vector<FolderCase> cases = {
      {"\".\"", [](const Scratch&) { return Setup{"s.json", "."}; }},
      {"\"./\"", [](const Scratch&) { return Setup{"s.json", "./"}; }},
      {"\"..\"", [](const Scratch&) { return Setup{"s.json", ".."}; }},
      {"\"../..\" (the top of the tree)", [](const Scratch&) { return Setup{"s.json", "../.."}; }},
      {"a missing folder followed by /..", [](const Scratch&) { return Setup{"s.json", "missing/.."}; }},
      {"a folder of the user's followed by /..", [](const Scratch&) { return Setup{"s.json", "keep/.."}; }},
      {"a new folder path followed by /../..", [](const Scratch&) { return Setup{"s.json", "a/b/../.."}; }},
      {"the working folder by its absolute path", [](const Scratch& s) { return Setup{"s.json", s.work.string()}; }},
      {"its parent by its absolute path", [](const Scratch& s) { return Setup{"s.json", s.home.string()}; }},
      {"the top of the tree by its absolute path", [](const Scratch& s) { return Setup{"s.json", s.tree.string()}; }},
      {"the parent by its absolute path and /.",
       [](const Scratch& s) { return Setup{"s.json", s.home.string() + "/."}; }},
      {"the parent by its absolute path and a trailing slash",
       [](const Scratch& s) { return Setup{"s.json", s.home.string() + "/"}; }},
      {"a link to the working folder",
       [](const Scratch& s) {
         link(s, ".", "here");
         return Setup{"s.json", "here"};
       }},
      {"a link to the parent",
       [](const Scratch& s) {
         link(s, "..", "up");
         return Setup{"s.json", "up"};
       }},
  };
  for (const auto& c : cases) check_refused(c);
}

TEST_CASE("output.dir refused for convergence and sweep as for run") {
  for (const char* command : {"convergence", "sweep"})
    for (const auto& c : refusals_of_every_command(command)) check_refused(c);
}

TEST_CASE("an invalid scene's output.dir problems are said with its other problems, by every command") {
  // A negative load and an unknown key once hid that output.dir names the user's file: the user fixed two problems
  // to be told of a third.
  for (const std::string command : {"validate", "run", "convergence", "sweep"}) {
    INFO("command: " << command);
    Scratch s;
    s.write("notes.txt", "the user's\n");
    s.write("output/h/mine.txt", "the user's too\n");
    json scene = base_scene();
    scene["name"] = "h";
    scene["load"]["P"] = -5;
    scene["bogus"] = 1;
    scene["output"] = {{"dir", "notes.txt"}};
    s.write("given.json", scene.dump());
    scene.erase("output");  // the default folder, output/h
    s.write("default.json", scene.dump());
    scene["name"] = "h/x";  // no folder can be named: its problems wait for the name's
    s.write("unnamed.json", scene.dump());
    const Snapshot before = s.snapshot();
    const Outcome given = s.fretwear(command_line(command, "given.json"));
    const Outcome by_default = s.fretwear(command_line(command, "default.json"));
    const Outcome unnamed = s.fretwear(command_line(command, "unnamed.json"));
    CHECK(changes(before, s.snapshot()).empty());
    for (const Outcome* r : {&given, &by_default, &unnamed}) {
      CHECK_MESSAGE(r->exited(kInvalid), r->describe());
      CHECK_MESSAGE(r->err.find("load.P: -5 is not allowed") != std::string::npos, r->describe());
      CHECK_MESSAGE(r->err.find("bogus: unknown key") != std::string::npos, r->describe());
    }
    CHECK_MESSAGE(given.err.find("notes.txt\" is an existing file") != std::string::npos,
                  given.describe());
    CHECK_MESSAGE(by_default.err.find("output/h\" holds files fretwear did not write") != std::string::npos, by_default.describe());
    CHECK_MESSAGE(unnamed.err.find("output.dir") == std::string::npos, unnamed.describe());
  }
}

TEST_CASE("output.dir accepted: a missing folder, an empty one, one fretwear made") {
  struct Accepted {
    FolderCase c;
    std::string folder;  // where the results land, relative to the working folder
  };
  const std::vector<Accepted> cases = {
      {{"a missing folder", [](const Scratch&) { return Setup{"s.json", "fresh"}; }}, "fresh"},
      {{"a missing folder three levels down", [](const Scratch&) { return Setup{"s.json", "a/b/c"}; }}, "a/b/c"},
      {{"a missing folder with a trailing slash", [](const Scratch&) { return Setup{"s.json", "fresh/"}; }}, "fresh"},
      {{"a missing folder by its absolute path",
        [](const Scratch& s) { return Setup{"s.json", (s.work / "fresh").string()}; }},
       "fresh"},
      {{"a missing folder inside a folder of the user's",
        [](const Scratch&) { return Setup{"s.json", "keep/results"}; }},
       "keep/results"},
      {{"a missing folder inside the scene's folder",
        [](const Scratch&) { return Setup{"scenes/s.json", "scenes/out"}; }},
       "scenes/out"},
      {{"an empty folder of the user's",
        [](const Scratch& s) {
          std::filesystem::create_directory(s.work / "empty");
          return Setup{"s.json", "empty"};
        }},
       "empty"},
      {{"the default output/<name>", [](const Scratch&) { return Setup{}; }}, "output/h"},
      {{"the default when only output.plots is given", [](const Scratch&) { return Setup{"s.json", {}, true}; }},
       "output/h"},
      {{"the default beside the user's files in output/",
        [](const Scratch& s) {
          s.write("output/README.md", "the user's notes on the outputs\n");
          return Setup{};
        }},
       "output/h"},
      {{"the default beside a folder of the user's named like a staging folder",
        [](const Scratch& s) {
          s.write("output/h.partial-4194303/inner.txt", "the user's, whatever its name\n");
          return Setup{};
        }},
       "output/h"},
      {{"a folder fretwear made for another scene",
        [](const Scratch& s) {
          run_before(s, "other.json", scene_text(Setup{"other.json", "shared"}, "other"));
          return Setup{"s.json", "shared"};
        }},
       "shared"},
      {{"its own folder from the run before",
        [](const Scratch& s) {
          run_before(s, "s.json", scene_text(Setup{}));
          return Setup{};
        }},
       "output/h"},
  };
  for (const auto& a : cases) check_accepted(a.c, a.folder);
  for (const char* command : {"convergence", "sweep"}) {
    check_accepted({"the default output/<name>", [](const Scratch&) { return Setup{}; }, command}, "output/h");
    check_accepted({"a missing folder", [](const Scratch&) { return Setup{"s.json", "fresh"}; }, command}, "fresh");
    check_accepted({"an empty folder of the user's",
                    [](const Scratch& s) {
                      std::filesystem::create_directory(s.work / "empty");
                      return Setup{"s.json", "empty"};
                    },
                    command},
                   "empty");
  }
}

TEST_CASE("run, convergence, sweep, run: each keeps the others' results") {
  Scratch s;
  s.write("s.json", base_scene().dump());
  const std::filesystem::path out = s.work / "output" / "h";
  const std::vector<std::pair<std::string, std::string>> steps = {
      {"run", "summary.json"}, {"convergence", "convergence/convergence.csv"}, {"sweep", "sweep/sweep.csv"},
      {"run", "summary.json"}};
  std::vector<std::string> present;
  int step = 0;
  for (const auto& [command, result] : steps) {
    const int n = ++step;
    INFO("step " << n << ": " << command);
    const Outcome r = s.fretwear(command_line(command, "s.json"));
    CHECK_MESSAGE(r.exited(kDone), command << ": " << r.describe());
    present.push_back(result);
    for (const auto& file : present) CHECK_MESSAGE(std::filesystem::exists(out / file), file << " is gone");
    CHECK(std::filesystem::exists(out / ".fretwear"));
  }
}

TEST_CASE("a rerun of run replaces its own results") {
  Scratch s;
  json scene = base_scene();
  s.write("s.json", scene.dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
  scene["load"]["P"] = 2e5;
  s.write("s.json", scene.dump());
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear({"run", "s.json", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  const json summary = json::parse(read_file(s.work / "output" / "h" / "summary.json"), nullptr, false);
  REQUIRE(summary.is_object());
  CHECK(summary["contact"]["load"].get<double>() == doctest::Approx(2e5).epsilon(1e-6));
  CHECK(leftovers(before, s.snapshot()).empty());
}

TEST_CASE("output.dir \"/\" is refused before anything is computed") {
  // A program that does not refuse "/" would replace it: as root, everything. So the case runs only where such a
  // program is held before it writes anything: a wear run told to pause ten minutes at each step boundary
  // (FRETWEAR_STEP_PAUSE_MS) is killed after 5 s. A probe shows first that this program does pause so: the same
  // scene into a folder of the tree is still running after 5 s. The correct program refuses "/" at once.
  const std::vector<std::pair<std::string, std::string>> pause = {{"FRETWEAR_STEP_PAUSE_MS", "600000"}};
  constexpr double kHeld = 5.0;  // s
  Scratch s;
  json scene = wear_scene();
  scene["output"] = {{"dir", "probe"}};
  s.write("probe.json", scene.dump());
  const Outcome probe = s.fretwear({"run", "probe.json", "-q"}, pause, kHeld);
  REQUIRE_MESSAGE(probe.timed_out, "the probe did not stay paused (" << probe.describe()
                                                                       << "): \"/\" cannot be tried safely");

  scene["output"] = {{"dir", "/"}};
  s.write("root.json", scene.dump());
  std::set<std::string> top_before;
  for (const auto& e : std::filesystem::directory_iterator("/")) top_before.insert(e.path().string());
  const Snapshot before = s.snapshot();
  Child child = s.start({"run", "root.json", "-q"}, pause, kHeld);
  const pid_t pid = child.pid();
  const Outcome r = child.wait();
  // What a program that did not refuse made at the top before it was held: its empty staging folder, a checkpoint.
  std::vector<std::string> made;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator("/")) {
    if (top_before.count(e.path().string())) continue;
    made.push_back(e.path().string());
    const std::string name = e.path().filename().string();
    if (name == ".partial-" + std::to_string(pid) || name == ".checkpoint" || name.rfind(".checkpoint.tmp", 0) == 0)
      std::filesystem::remove(e.path(), ec);  // a folder only if empty
  }
  CHECK_MESSAGE(r.exited(kInvalid), "want exit 2 at once, got " << r.describe());
  CHECK_MESSAGE(r.err.find("output.dir") != std::string::npos, "the message should name output.dir: " << r.describe());
  CHECK_MESSAGE(made.empty(), "made at the top of the file system: " << join(made));
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "the tree changed: " << join(changes(before, s.snapshot())));
}

TEST_CASE("output.dir refused where the wear run's checkpoint would replace a file of the user's") {
  // A wear run keeps its checkpoint in <output.dir>.checkpoint, overwrites it at every record and deletes it at the
  // end: there only a file fretwear wrote (a fretwear checkpoint, of any scene or version) may stand.
  const std::vector<FolderCase> cases = {
      {"a file of the user's",
       [](const Scratch& s) {
         s.write("res.checkpoint", "the user's notes\n");
         return Setup{"s.json", "res", false, true};
       },
       "run", "res.checkpoint"},
      {"an empty file",
       [](const Scratch& s) {
         s.write("res.checkpoint", "");
         return Setup{"s.json", "res", false, true};
       },
       "run", "res.checkpoint"},
      {"a folder of the user's",
       [](const Scratch& s) {
         s.write("res.checkpoint/inner.txt", "the user's\n");
         return Setup{"s.json", "res", false, true};
       },
       "run", "res.checkpoint"},
      {"a link to a file of the user's",
       [](const Scratch& s) {
         std::filesystem::create_symlink("notes.txt", s.work / "res.checkpoint");
         return Setup{"s.json", "res", false, true};
       },
       "run", "res.checkpoint"},
      {"a file of the user's beside the default output/<name>",
       [](const Scratch& s) {
         s.write("output/h.checkpoint", "the user's notes\n");
         return Setup{"s.json", std::nullopt, false, true};
       },
       "run", "h.checkpoint"},
  };
  for (const auto& c : cases) check_refused(c);
}

TEST_CASE("a checkpoint fretwear wrote beside output.dir does not stop a run") {
  // An interrupted run leaves its checkpoint; a run from the start takes its place, and deletes it when done.
  Scratch s;
  json scene = wear_scene();
  scene["output"] = {{"dir", "res"}, {"plots", false}};
  s.write("s.json", scene.dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_STOP_AT_STEP", "2"}}).exited(kInterrupted));
  REQUIRE(std::filesystem::is_regular_file(s.work / "res.checkpoint"));
  CHECK(s.fretwear({"validate", "s.json", "-q"}).exited(kDone));
  const Outcome r = s.fretwear({"run", "s.json", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  CHECK(!std::filesystem::exists(s.work / "res.checkpoint"));
}

TEST_CASE("output.dir refused when named like fretwear's staging folders") {
  // A command removes <name>.partial-<pid> and <name>.old-<pid> beside its folder <name> when their process is gone:
  // a results folder so named would be removed by a later run of the scene writing into <name>.
  const std::vector<FolderCase> cases = {
      {".partial- and digits", [](const Scratch&) { return Setup{"s.json", "h.partial-123"}; }, "run", "h.partial-123"},
      {".old- and digits, deeper", [](const Scratch&) { return Setup{"s.json", "out/h.old-7"}; }, "run", "h.old-7"},
      {".partial- and digits, a trailing slash", [](const Scratch&) { return Setup{"s.json", "h.partial-4/"}; }},
      {".partial- and digits, for convergence", [](const Scratch&) { return Setup{"s.json", "h.partial-123"}; },
       "convergence"},
  };
  for (const auto& c : cases) check_refused(c);
  check_accepted({".old- and no digits", [](const Scratch&) { return Setup{"s.json", "h.old-v2"}; }},
                 "h.old-v2");
}

TEST_CASE("output.dir refused when it is a symbolic link, or goes through one that dangles or loops") {
  // A results folder is replaced as a whole: a link given as output.dir would be replaced by a folder. A link that
  // leads nowhere cannot be written through.
  auto prepared = [](std::function<void(const Scratch&)> make, std::string dir) {
    return [make, dir](const Scratch& s) {
      make(s);
      return Setup{"s.json", dir};
    };
  };
  const auto empty_link = [](const Scratch& s) {
    std::filesystem::create_directory(s.work / "empty");
    link(s, "empty", "elink");
  };
  const auto results_link = [](const Scratch& s) {
    run_before(s, "first.json", scene_text(Setup{"first.json", "made"}));
    link(s, "made", "mlink");
  };
  const auto dangling = [](const Scratch& s) { link(s, "nowhere", "dangling"); };
  const auto loop = [](const Scratch& s) {
    link(s, "loopb", "loopa");
    link(s, "loopa", "loopb");
  };
  const std::vector<FolderCase> cases = {
      {"a link to an empty folder", prepared(empty_link, "elink"), "run", "\"elink\" is a symbolic link"},
      {"a link to an empty folder, a trailing slash", prepared(empty_link, "elink/"), "run", "symbolic link"},
      {"a link to earlier results", prepared(results_link, "mlink"), "run", "\"mlink\" is a symbolic link"},
      {"a dangling link", prepared(dangling, "dangling"), "run", "\"dangling\" is a symbolic link"},
      {"a folder under a dangling link", prepared(dangling, "dangling/sub"), "run", "\"dangling\" is a symbolic link"},
      {"a link loop", prepared(loop, "loopa"), "run", "\"loopa\" is a symbolic link"},
      {"a folder under a link loop", prepared(loop, "loopa/sub"), "run", "\"loopa\" is a symbolic link"},
      {"a link to an empty folder, for convergence", prepared(empty_link, "elink"), "convergence", "symbolic link"},
      {"a dangling link, for sweep", prepared(dangling, "dangling/sub"), "sweep", "symbolic link"},
  };
  for (const auto& c : cases) check_refused(c);
  // A link above the folder is followed: the folder is made in the folder it points to.
  check_accepted({"a missing folder under a link to a folder", prepared(empty_link, "elink/sub")}, "empty/sub");
}

TEST_CASE("output.dir refused when its name with the staging suffix passes the file system's limit") {
  // The staging folder <name>.partial-<pid> (a pid of up to 7 digits: 16 characters more) and a wear run's
  // checkpoint <name>.checkpoint.tmp-<pid> (23 more) must be names the file system takes.
  Scratch probe;
  const long max = ::pathconf(probe.work.c_str(), _PC_NAME_MAX);
  REQUIRE(max > 30);
  const std::string longest = std::string(std::size_t(max) - 16, 'a');
  const std::vector<FolderCase> cases = {
      {"a name one past the limit", [longest](const Scratch&) { return Setup{"s.json", longest + "a"}; }, "run",
       "at most " + std::to_string(max)},
      {"a missing folder above, past the limit itself",
       [max](const Scratch&) { return Setup{"s.json", std::string(std::size_t(max) + 1, 'b') + "/c"}; }, "run",
       "at most " + std::to_string(max)},
      {"a wear run's checkpoint one past the limit",
       [max](const Scratch&) { return Setup{"s.json", std::string(std::size_t(max) - 22, 'w'), false, true}; }, "run",
       "at most " + std::to_string(max)},
  };
  for (const auto& c : cases) check_refused(c);
  check_accepted({"a name at the limit", [longest](const Scratch&) { return Setup{"s.json", longest}; }}, longest);
  const std::string wear_longest(std::size_t(max) - 23, 'w');
  check_accepted({"a wear run's checkpoint at the limit",
                  [wear_longest](const Scratch&) { return Setup{"s.json", wear_longest, false, true}; }},
                 wear_longest);
}

TEST_CASE("results that cannot be written (a full disk) exit 2, keep nothing of the run, leave the earlier ones") {
  // A file size limit stands in for a full disk (Scratch::fretwear_file_limited).
  Scratch s;
  json scene = base_scene();
  scene["output"] = {{"plots", false}};
  s.write("s.json", scene.dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
  scene["grid"]["cells"] = 512;
  s.write("s.json", scene.dump());
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear_file_limited(8, {"run", "s.json"});
  CHECK_MESSAGE(r.exited(kInvalid), r.describe());
  CHECK_MESSAGE(
      r.err.find("fretwear: the results cannot be written:\n  output.dir: cannot write ") != std::string::npos,
      r.describe());
  CHECK_MESSAGE(r.err.find("(File too large); nothing of this run is kept and the folder is as it was") !=
                    std::string::npos,
                r.describe());
  CHECK(r.err.find("internal error") == std::string::npos);
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "the tree changed: " << join(changes(before, s.snapshot())));
  // Without the limit the same run replaces them.
  CHECK(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
}

TEST_CASE("a replaced folder keeps its permission bits") {
  // The new results folder takes the place of the one it replaces, with its mode: an empty folder of the user's and
  // earlier results alike.
  namespace fs = std::filesystem;
  Scratch s;
  s.write("s.json", scene_text(Setup{"s.json", "ro"}));
  fs::create_directory(s.work / "ro");
  fs::permissions(s.work / "ro", fs::perms(0555));
  Outcome r = s.fretwear({"run", "s.json", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(fs::exists(s.work / "ro" / "summary.json"));
  CHECK(fs::status(s.work / "ro").permissions() == fs::perms(0555));
  fs::permissions(s.work / "ro", fs::perms(0750));
  REQUIRE(s.fretwear({"convergence", "s.json", "--from", "64", "--to", "128", "-q"}).exited(kDone));
  fs::permissions(s.work / "ro" / "convergence", fs::perms(0700));
  r = s.fretwear({"run", "s.json", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  CHECK(fs::status(s.work / "ro").permissions() == fs::perms(0750));
  CHECK(fs::status(s.work / "ro" / "convergence").permissions() == fs::perms(0700));
  CHECK(fs::exists(s.work / "ro" / "convergence" / "convergence.csv"));
  fs::permissions(s.work / "ro", fs::perms(0755));
}

// ---------------------------------------------------------------------------------------------------------------
// What fretwear may remove: only what it wrote (SCENES.md, "Output folders"). A folder's marker lists what the
// command wrote there; a rerun refuses, before anything is computed, a folder holding anything else, and names it.

namespace {

namespace fs = std::filesystem;

// The marker of the first format, which listed nothing: its folder may hold only the names fretwear writes.
constexpr const char* kFirstFormatMarker = "fretwear's results: fretwear may replace this folder\n";

// Runs `command` of the scene s.json beforehand, as a case's preparation: it must complete.
void command_before(const Scratch& s, const std::string& command) {
  const Outcome r = s.fretwear(command_line(command, "s.json"));
  REQUIRE_MESSAGE(r.exited(kDone), "the preparing " << command << ": " << r.describe());
}

// The first run folder of a sweep in `sweep` (its runs/), relative to it.
std::string first_run(const fs::path& sweep) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(sweep / "runs")) names.push_back(e.path().filename().string());
  REQUIRE(!names.empty());
  std::sort(names.begin(), names.end());
  return "runs/" + names.front();
}

// `args` is refused: exit 2, a message naming output.dir and each of `says`, and the tree as it was.
void refused_untouched(const Scratch& s, const std::vector<std::string>& args, const std::vector<std::string>& says) {
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear(args);
  CHECK_MESSAGE(r.exited(kInvalid), "want exit 2, got " << r.describe());
  CHECK_MESSAGE(r.err.find("output.dir") != std::string::npos, "the message should name output.dir: " << r.describe());
  for (const auto& word : says)
    CHECK_MESSAGE(r.err.find(word) != std::string::npos, "the message should name " << word << ": " << r.describe());
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "the tree changed: " << join(changes(before, s.snapshot())));
}

// The start of this process in clock ticks after boot (field 22 of /proc/self/stat), the host's name and its boot
// id: what a staging folder's marker records of the process writing it.
struct ThisProcess {
  long long start_time = -1;
  std::string host, boot_id;
  ThisProcess() {
    const std::string stat = read_file("/proc/self/stat");
    std::istringstream fields(stat.substr(stat.rfind(')') + 1));
    std::string field;
    for (int k = 3; k <= 22 && fields >> field; ++k)
      if (k == 22) start_time = std::stoll(field);
    char name[256] = {};
    ::gethostname(name, sizeof name - 1);
    host = name;
    boot_id = read_file("/proc/sys/kernel/random/boot_id");
    if (!boot_id.empty() && boot_id.back() == '\n') boot_id.pop_back();
  }
};

}  // namespace

TEST_CASE("a rerun refuses to remove the user's files in its results folder, naming each") {
  // The reproducer: a user's note, a folder of theirs, a copy of the resolved scene to edit.
  Scratch s;
  json scene = base_scene();
  scene["name"] = "b";
  s.write("b.json", scene.dump());
  REQUIRE(s.fretwear({"run", "b.json", "-q"}).exited(kDone));
  const fs::path out = s.work / "output" / "b";
  s.write("output/b/notes.txt", "x\n");
  fs::create_directory(out / "mystuff");
  fs::copy_file(out / "scene.resolved.json", out / "variant.json");
  refused_untouched(s, {"run", "b.json"}, {"\"output/b\"", "notes.txt", "mystuff/", "variant.json"});
  refused_untouched(s, {"validate", "b.json"}, {"notes.txt"});
  // Moved away, the folder is fretwear's again.
  fs::remove(out / "notes.txt");
  fs::remove(out / "mystuff");
  fs::remove(out / "variant.json");
  const Outcome r = s.fretwear({"run", "b.json", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
}

TEST_CASE("output.dir refused when fretwear's folder holds entries it did not write, of either marker format") {
  const auto earlier_run = [](const Scratch& s) { run_before(s, "s.json", scene_text(Setup{})); };
  const auto first_format = [](const Scratch& s) { s.write("output/h/.fretwear", kFirstFormatMarker); };
  // The earlier run's `entry` in output/h, replaced by what `by` makes at its path.
  using Make = std::function<void(const Scratch&, const fs::path&)>;
  const auto replaced = [=](const std::string& entry, const Make& by) {
    return [=](const Scratch& s) {
      earlier_run(s);
      by(s, s.work / "output" / "h" / entry);
      return Setup{};
    };
  };
  const Make by_pipe = [](const Scratch&, const fs::path& p) {
    fs::remove(p);
    REQUIRE(::mkfifo(p.c_str(), 0600) == 0);
  };
  const Make by_link_to_copy = [](const Scratch& s, const fs::path& p) {
    const std::string copy = p.filename().string() + ".copy";
    fs::copy_file(p, s.work / copy);
    fs::remove(p);
    fs::create_symlink("../../" + copy, p);
  };
  const std::vector<FolderCase> cases = {
      {"a file of the user's added",
       [=](const Scratch& s) {
         earlier_run(s);
         s.write("output/h/notes.txt", "the user's\n");
         return Setup{};
       },
       "run", "notes.txt"},
      {"an empty folder of the user's added",
       [=](const Scratch& s) {
         earlier_run(s);
         fs::create_directory(s.work / "output" / "h" / "mystuff");
         return Setup{};
       },
       "run", "mystuff/"},
      {"a hidden file of the user's added",
       [=](const Scratch& s) {
         earlier_run(s);
         s.write("output/h/.notes", "the user's\n");
         return Setup{};
       },
       "run", ".notes"},
      {"a marker of the first format, a file of the user's added",
       [=](const Scratch& s) {
         earlier_run(s);
         first_format(s);
         s.write("output/h/notes.txt", "the user's\n");
         return Setup{};
       },
       "run", "notes.txt"},
      {"a marker of the first format, a scene of the user's added",
       [=](const Scratch& s) {
         earlier_run(s);
         first_format(s);
         s.write("output/h/variant.json", "{}\n");
         return Setup{};
       },
       "run", "variant.json"},
      {"a marker of the first format, a folder of the user's holding a plot",
       [=](const Scratch& s) {
         earlier_run(s);
         first_format(s);
         fs::create_directory(s.work / "output" / "h" / "mine");
         fs::copy_file(s.work / "output" / "h" / "summary.json", s.work / "output" / "h" / "mine" / "summary.json");
         return Setup{};
       },
       "run", "mine/"},
      {"a file fretwear wrote, then edited by the user",
       [=](const Scratch& s) {
         earlier_run(s);
         s.write("output/h/summary.json", read_file(s.work / "output" / "h" / "summary.json") + "\n");
         return Setup{};
       },
       "run", "summary.json (changed since fretwear wrote it)"},
      {"a file fretwear wrote, replaced by a link to a copy of it (the same bytes, the same checksum)",
       replaced("summary.json", by_link_to_copy), "run", "summary.json (a link)"},
      // fretwear writes regular files only, and never opens a pipe: opening one to read waits for a writer, and the
      // check of the folder waited for ever.
      {"a file fretwear wrote, replaced by a named pipe", replaced("summary.json", by_pipe), "run",
       "summary.json (not a regular file)"},
      {"its marker replaced by a named pipe", replaced(".fretwear", by_pipe), "run", "no .fretwear marker"},
      {"its marker replaced by a link to a copy of it", replaced(".fretwear", by_link_to_copy), "run",
       "no .fretwear marker"},
      {"a run folder a convergence study made, a file of the user's added",
       [](const Scratch& s) {
         s.write("s.json", scene_text(Setup{}));
         command_before(s, "convergence");
         s.write("output/h/notes.txt", "the user's\n");
         return Setup{};
       },
       "run", "notes.txt"},
  };
  for (const auto& c : cases) check_refused(c);
}

TEST_CASE("output.dir accepted: fretwear's folder of either marker format holding only what fretwear writes") {
  const std::vector<FolderCase> cases = {
      {"a marker of the first format",
       [](const Scratch& s) {
         run_before(s, "s.json", scene_text(Setup{}));
         s.write("output/h/.fretwear", kFirstFormatMarker);
         return Setup{};
       }},
      {"a marker of the first format, with the other commands' folders",
       [](const Scratch& s) {
         s.write("s.json", scene_text(Setup{}));
         for (const char* command : {"run", "convergence", "sweep"}) command_before(s, command);
         for (const char* at : {"output/h/.fretwear", "output/h/convergence/.fretwear", "output/h/sweep/.fretwear"})
           s.write(at, kFirstFormatMarker);
         const fs::path sweep = s.work / "output" / "h" / "sweep";
         s.write((fs::path("output/h/sweep") / first_run(sweep) / ".fretwear").string(), kFirstFormatMarker);
         return Setup{};
       }},
  };
  check_accepted({"a file fretwear wrote, rewritten with the same bytes",
                  [](const Scratch& s) {
                    run_before(s, "s.json", scene_text(Setup{}));
                    s.write("output/h/summary.json", read_file(s.work / "output" / "h" / "summary.json"));
                    return Setup{};
                  }},
                 "output/h");
  for (const auto& c : cases) check_accepted(c, "output/h");
  for (const char* command : {"convergence", "sweep"})
    check_accepted({"a marker of the first format",
                    [command](const Scratch& s) {
                      s.write("s.json", scene_text(Setup{}));
                      command_before(s, command);
                      s.write("output/h/" + std::string(command) + "/.fretwear", kFirstFormatMarker);
                      return Setup{};
                    },
                    command},
                   "output/h");
}

TEST_CASE("the marker lists what the command wrote, and a rerun replaces exactly that") {
  Scratch s;
  s.write("s.json", base_scene().dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
  const fs::path out = s.work / "output" / "h";
  const json marker = json::parse(read_file(out / ".fretwear"), nullptr, false);
  REQUIRE(marker.is_object());
  CHECK(marker["format"] == "fretwear-folder");
  CHECK(marker["kind"] == "results");
  std::vector<std::string> present;
  for (const auto& e : fs::directory_iterator(out))
    if (e.path().filename() != ".fretwear") present.push_back(e.path().filename().string());
  std::sort(present.begin(), present.end());
  CHECK(marker["entries"].get<std::vector<std::string>>() == present);
  for (const std::string& file : present)  // every file with its checksum, by which an edit is told
    if (fs::is_regular_file(out / file))
      CHECK_MESSAGE(marker["checksums"].value(file, "").rfind("fnv1a64:", 0) == 0, file);
  CHECK(std::find(present.begin(), present.end(), "summary.json") != present.end());
}

TEST_CASE("the convergence and sweep folders refuse entries fretwear did not write, and a run carries them over") {
  Scratch s;
  s.write("s.json", base_scene().dump());
  for (const char* command : {"run", "convergence", "sweep"}) command_before(s, command);
  const fs::path out = s.work / "output" / "h";
  s.write("output/h/convergence/notes.txt", "the user's, in convergence/\n");
  const std::string run = first_run(out / "sweep");
  s.write("output/h/sweep/" + run + "/notes.txt", "the user's, in a run of the sweep\n");
  s.write("output/h/sweep/runs/mine.csv", "the user's, among the runs\n");
  const std::string edited = "output/h/sweep/" + run + "/summary.json";
  s.write(edited, read_file(s.work / edited) + " ");
  refused_untouched(s, command_line("convergence", "s.json"), {"convergence/", "notes.txt"});
  refused_untouched(s, command_line("sweep", "s.json"),
                    {run + "/notes.txt", "runs/mine.csv", run + "/summary.json (changed since fretwear wrote it)"});
  // The run replaces its own folder and carries the two over, the user's files in them as they were.
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear(command_line("run", "s.json"));
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  const Snapshot after = s.snapshot();
  const std::vector<std::string> kept = {"output/h/convergence/notes.txt", "output/h/sweep/" + run + "/notes.txt",
                                         "output/h/sweep/runs/mine.csv", "output/h/convergence/convergence.csv"};
  for (const std::string& file : kept) {
    const std::string key = (s.work / file).lexically_relative(s.tree).generic_string();
    const bool same = after.count(key) == 1 && after.at(key) == before.at(key);
    CHECK_MESSAGE(same, file << " is gone or changed");
  }
}

TEST_CASE("a file the user adds while the run computes is left, and the results kept beside it") {
  // Checked before anything is computed, and again when the results are put in place: a wear run paused at each
  // step boundary gives the time to add it.
  Scratch s;
  json scene = wear_scene();
  scene["output"] = {{"plots", false}};
  s.write("s.json", scene.dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
  const fs::path out = s.work / "output" / "h";
  const std::string summary = read_file(out / "summary.json");
  Child child = s.start({"run", "s.json", "-q"}, {{"FRETWEAR_STEP_PAUSE_MS", "150"}});
  const pid_t pid = child.pid();
  ::usleep(700000);
  REQUIRE(child.running());
  s.write("output/h/notes.txt", "written while fretwear ran\n");
  const Outcome r = child.wait();
  CHECK_MESSAGE(r.exited(kInvalid), "want exit 2, got " << r.describe());
  CHECK_MESSAGE(r.err.find("notes.txt") != std::string::npos, r.describe());
  CHECK(read_file(out / "notes.txt") == "written while fretwear ran\n");
  CHECK(read_file(out / "summary.json") == summary);
  const fs::path kept = s.work / "output" / ("h.partial-" + std::to_string(pid));
  CHECK_MESSAGE(r.err.find(kept.filename().string()) != std::string::npos, r.describe());
  CHECK(fs::exists(kept / "summary.json"));
  const json marker = json::parse(read_file(kept / ".fretwear"), nullptr, false);
  CHECK_MESSAGE(marker.value("kind", "") == "results", marker.dump());
}

TEST_CASE("copies of a results folder beside it are kept, whatever their names") {
  // The reproducer: backups named like staging folders, of no running process, with the user's notes in one.
  Scratch s;
  json scene = base_scene();
  scene["name"] = "b";
  s.write("b.json", scene.dump());
  REQUIRE(s.fretwear({"run", "b.json", "-q"}).exited(kDone));
  const fs::path output = s.work / "output";
  for (const char* copy : {"b.old-20241127", "b.partial-4000000", "b.old-4000001"})
    fs::copy(output / "b", output / copy, fs::copy_options::recursive);
  s.write("output/b.old-20241127/mynotes.txt", "mine\n");
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear({"run", "-q", "b.json"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  const std::string exempt = (output / "b").lexically_relative(s.tree).generic_string();
  CHECK_MESSAGE(changes(before, s.snapshot(), {exempt}).empty(),
                "touched: " << join(changes(before, s.snapshot(), {exempt})));
}

TEST_CASE("a killed command's staging folder is removed by the next, unless it holds an entry of the user's") {
  // A sweep killed after its first run leaves <output.dir>/sweep.partial-<pid>, marked as its staging folder.
  const std::vector<std::string> sweep = {"sweep", "s.json", "--vary", "load.P=5e4,1e5,2e5", "--jobs", "1", "-q"};
  auto killed_sweep = [&](const Scratch& s) {
    s.write("s.json", base_scene().dump());
    const Outcome killed = s.fretwear(sweep, {{"FRETWEAR_SWEEP_KILL_AFTER_RUNS", "1"}});
    REQUIRE_MESSAGE(killed.signal == SIGKILL, killed.describe());
    std::vector<fs::path> staging;
    for (const auto& e : fs::directory_iterator(s.work / "output" / "h"))
      if (e.path().filename().string().rfind("sweep.partial-", 0) == 0) staging.push_back(e.path());
    REQUIRE(staging.size() == 1);
    const json marker = json::parse(read_file(staging.front() / ".fretwear"), nullptr, false);
    CHECK_MESSAGE(marker.value("kind", "") == "staging", marker.dump());
    return staging.front();
  };
  {
    Scratch s;
    const fs::path leftover = killed_sweep(s);
    const Outcome r = s.fretwear(sweep);
    CHECK_MESSAGE(r.exited(kDone), r.describe());
    CHECK_MESSAGE(!fs::exists(leftover), leftover.string() << " is left");
  }
  {
    // Killed between making its staging folder and writing the marker: empty, named for a process that cannot exist
    // (a pid above Linux's largest, 2^22). Removed; one holding anything is left.
    Scratch s;
    s.write("s.json", base_scene().dump());
    const fs::path empty = s.work / "output" / "h.partial-4999999", held = s.work / "output" / "h.partial-4999998";
    fs::create_directories(empty);
    write_file(held / "notes.txt", "the user's\n");
    const Outcome r = s.fretwear({"run", "s.json", "-q"});
    CHECK_MESSAGE(r.exited(kDone), r.describe());
    CHECK_MESSAGE(!fs::exists(empty), empty.string() << " is left");
    CHECK(read_file(held / "notes.txt") == "the user's\n");
  }
  {
    Scratch s;
    const fs::path leftover = killed_sweep(s);
    write_file(leftover / "runs" / "notes.txt", "the user's, in a killed sweep's folder\n");
    const Outcome r = s.fretwear(sweep);
    CHECK_MESSAGE(r.exited(kDone), r.describe());
    CHECK(read_file(leftover / "runs" / "notes.txt") == "the user's, in a killed sweep's folder\n");
  }
}

TEST_CASE("a run killed as its results replace the earlier ones leaves results in place, and the next removes the rest") {
  // FRETWEAR_KILL_AFTER_REPLACING kills the run as soon as its first step has moved the folder it replaces: one step
  // that exchanges the two, so output/h never goes missing.
  Scratch s;
  json scene = base_scene();
  s.write("s.json", scene.dump());
  REQUIRE(s.fretwear({"run", "s.json", "-q"}).exited(kDone));
  const fs::path out = s.work / "output" / "h";
  const std::string earlier = read_file(out / "summary.json");
  scene["load"]["P"] = 2e5;
  s.write("s.json", scene.dump());
  const Outcome killed = s.fretwear({"run", "s.json", "-q"}, {{"FRETWEAR_KILL_AFTER_REPLACING", "1"}});
  REQUIRE_MESSAGE(killed.signal == SIGKILL, killed.describe());
  REQUIRE_MESSAGE(fs::exists(out / "summary.json"), "output/h is missing after the kill");
  const json now = json::parse(read_file(out / "summary.json"));
  CHECK(now["contact"]["load"].get<double>() > 1.5e5);  // this run's P = 2e5 N/m, not the earlier 1e5
  CHECK(json::parse(read_file(out / ".fretwear"))["kind"] == "results");
  std::vector<fs::path> left;
  for (const auto& e : fs::directory_iterator(s.work / "output"))
    if (e.path().filename() != "h") left.push_back(e.path());
  REQUIRE(left.size() == 1);  // the earlier results, marked as the killed process's staging folder
  CHECK(read_file(left.front() / "summary.json") == earlier);
  CHECK(json::parse(read_file(left.front() / ".fretwear"))["kind"] == "staging");
  const Outcome next = s.fretwear({"run", "s.json", "-q"});
  CHECK_MESSAGE(next.exited(kDone), next.describe());
  CHECK_MESSAGE(!fs::exists(left.front()), left.front().string() << " is left");
}

TEST_CASE("a staging folder is removed only when its marker names a process of this host that has ended") {
  // Markers made here name this test's process (alive): as it is, it is kept; with another start time it names a
  // process that has ended (its pid taken since), and is removed; on another host it is kept.
  const ThisProcess self;
  REQUIRE(self.start_time >= 0);
  struct Case {
    std::string label;
    long long start_time;
    std::string host;
    bool removed;
  };
  const std::vector<Case> cases = {
      {"a live process", self.start_time, self.host, false},
      {"another process with the pid", self.start_time + 1, self.host, true},
      {"a process of another host", self.start_time + 1, self.host + "-elsewhere", false},
  };
  for (const Case& c : cases) {
    INFO("case: " << c.label);
    Scratch s;
    s.write("s.json", base_scene().dump());
    const std::string name = "output/h.partial-" + std::to_string(::getpid());
    s.write(name + "/summary.json", "{}\n");
    const json marker = {{"format", "fretwear-folder"}, {"kind", "staging"},      {"pid", long(::getpid())},
                         {"host", c.host},              {"boot_id", self.boot_id}, {"start_time", c.start_time}};
    s.write(name + "/.fretwear", marker.dump());
    const Outcome r = s.fretwear({"run", "s.json", "-q"});
    CHECK_MESSAGE(r.exited(kDone), r.describe());
    CHECK(fs::exists(s.work / name) == !c.removed);
  }
}
