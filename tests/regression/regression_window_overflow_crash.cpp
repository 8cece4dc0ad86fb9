// A window of ±1e200 m crashed the program (SIGSEGV in locate_zones, a .partial-PID folder left behind): the gap
// x²/2R overflows on every cell, the normal solver returned with no admissible cell and an empty pressure, and the
// zones were located in it. The scene's ranges refuse such a window now; below them, solve_normal() itself refuses a
// window where no cell has a finite gap.
#include <doctest/doctest.h>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "program.hpp"

using namespace fretwear;
using namespace fretwear::test;

TEST_CASE("a window where no cell has a finite gap is an input error, not a crash") {
  Scene s = parse_scene(nlohmann::json::parse(R"({"name": "w", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256}})"));
  s.window = std::pair(-1e200, 1e200);
  CHECK_THROWS_WITH_AS(solve_normal(s), doctest::Contains("grid.window"), InputError);
}

TEST_CASE("fretwear run, validate, convergence and sweep on a window of ±1e200 m: exit 2, nothing written") {
  Scratch scratch{"window"};
  write_file(scratch.path / "w.json", R"({"name": "w", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5},
    "grid": {"cells": 256, "window": [-1e200, 1e200]}})");
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"run", "w.json"}, {"validate", "w.json"}, {"convergence", "--to", "256", "w.json"},
        {"sweep", "w.json", "--vary", "load.P=1e5,2e5"}}) {
    CAPTURE(args.front());
    const Outcome o = run_program(scratch.path, args);
    CHECK(o.signal == 0);
    CHECK(o.status == 2);
    CHECK(o.all().find("grid.window") != std::string::npos);
    CHECK(snapshot(scratch.path).size() == 1);  // the scene alone
  }
}
