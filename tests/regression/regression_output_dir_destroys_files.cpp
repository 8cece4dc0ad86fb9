// output.dir could destroy a user's files: "." or "x/.." emptied that folder (the scene with it) and then failed
// with an internal error; a path naming an existing file replaced the file; the scene's own folder lost the scene;
// `convergence` and `sweep` deleted the results of `run`. Each case now: exit 2 naming output.dir, before anything
// is computed, with every file of the scratch folder as it was (docs/SCENES.md, "Output folders").
#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

namespace {

std::string scene_with_dir(const std::string& name, const std::string& dir) {
  return R"({"name": ")" + name + R"(", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256},
    "output": {"dir": ")" + dir + R"("}})";
}

// A scratch folder with the user's files: a thesis chapter, data in a subfolder, and the scene.
struct UserFolder {
  Scratch scratch{"outdir"};
  fs::path work = scratch.path / "work";
  UserFolder() {
    write_file(work / "chapter.tex", "\\chapter{Fretting}\n");
    write_file(work / "data" / "measured.csv", "x,h\n0,0\n");
  }
};

// The command is refused, names output.dir, and leaves every file as it was.
void refused_untouched(UserFolder& u, const std::vector<std::string>& args) {
  const auto before = snapshot(u.scratch.path);
  const Outcome o = run_program(u.work, args);
  CAPTURE(o.all());
  CHECK(o.status == 2);
  CHECK(o.all().find("output.dir") != std::string::npos);
  CHECK(snapshot(u.scratch.path) == before);
}

}  // namespace

TEST_CASE("output.dir \".\" emptied the working folder: now refused, nothing touched") {
  UserFolder u;
  write_file(u.work / "s.json", scene_with_dir("s", "."));
  refused_untouched(u, {"run", "s.json"});
  refused_untouched(u, {"validate", "s.json"});
}

TEST_CASE("output.dir ending in /.. emptied that folder: now refused, nothing touched") {
  UserFolder u;
  write_file(u.work / "s.json", scene_with_dir("s", "data/.."));
  refused_untouched(u, {"run", "s.json"});
  write_file(u.work / "t.json", scene_with_dir("t", "data/sub/../.."));
  refused_untouched(u, {"run", "t.json"});
  write_file(u.work / "a.json", scene_with_dir("a", (u.work / "data" / "..").string()));
  refused_untouched(u, {"run", "a.json"});
}

TEST_CASE("output.dir naming an existing file replaced the file: now refused, nothing touched") {
  UserFolder u;
  write_file(u.work / "s.json", scene_with_dir("s", "chapter.tex"));
  refused_untouched(u, {"run", "s.json"});
}

TEST_CASE("output.dir naming the scene's folder deleted the scene: now refused, nothing touched") {
  UserFolder u;
  write_file(u.work / "data" / "s.json", scene_with_dir("s", (u.work / "data").string()));
  refused_untouched(u, {"run", "data/s.json"});
  refused_untouched(u, {"convergence", "data/s.json"});
  // and a folder above it, and the working folder's parent
  write_file(u.work / "data" / "t.json", scene_with_dir("t", u.work.string()));
  refused_untouched(u, {"run", "data/t.json"});
  write_file(u.work / "data" / "p.json", scene_with_dir("p", u.scratch.path.string()));
  refused_untouched(u, {"run", "data/p.json"});
}

TEST_CASE("output.dir naming a folder fretwear did not make, with files in it: refused, an empty one is used") {
  UserFolder u;
  write_file(u.work / "s.json", scene_with_dir("s", "data"));
  refused_untouched(u, {"run", "s.json"});
  fs::create_directories(u.work / "empty");
  write_file(u.work / "e.json", scene_with_dir("e", "empty"));
  const Outcome o = run_program(u.work, {"run", "-q", "e.json"});
  CHECK(o.status == 0);
  CHECK(fs::exists(u.work / "empty" / "summary.json"));
  CHECK(fs::exists(u.work / "empty" / ".fretwear"));
  CHECK(read_file(u.work / "chapter.tex") == "\\chapter{Fretting}\n");
}

TEST_CASE("convergence and sweep deleted the results of run: now each writes its own subfolder") {
  Scratch scratch{"owners"};
  write_file(scratch.path / "c.json", R"({"name": "c", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 256}, "effects": {"tangential": {}}, "output": {"dir": "output/c", "plots": false}})");
  const fs::path out = scratch.path / "output" / "c";
  auto all_present = [&] {
    CHECK(fs::exists(out / "summary.json"));
    CHECK(fs::exists(out / "convergence" / "convergence.csv"));
    CHECK(fs::exists(out / "sweep" / "sweep.csv"));
  };
  REQUIRE(run_program(scratch.path, {"run", "-q", "c.json"}).status == 0);
  REQUIRE(run_program(scratch.path, {"convergence", "-q", "--to", "512", "c.json"}).status == 0);
  REQUIRE(run_program(scratch.path, {"sweep", "-q", "c.json", "--vary", "load.Q.ratio=0.2,0.4"}).status == 0);
  all_present();
  REQUIRE(run_program(scratch.path, {"run", "-q", "c.json"}).status == 0);  // a rerun replaces its own, keeps theirs
  all_present();
  REQUIRE(run_program(scratch.path, {"convergence", "-q", "--to", "256", "c.json"}).status == 0);
  all_present();
  CHECK(leftovers(scratch.path).empty());
}
