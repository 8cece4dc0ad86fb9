// `validate` said valid and `run` then refused, leaving an empty output/ behind: a contact reaching the end of the
// given window, a load whose load–size integral finds no contact half-width, a cycle the analogy route refuses.
// validate now makes every check run makes before solving, and a refusal writes nothing.
#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

namespace {

// validate and run both exit 2 naming `key`, and neither writes anything.
void both_refuse(const std::string& scene, const std::string& key) {
  Scratch scratch{"agree"};
  write_file(scratch.path / "s.json", scene);
  for (const char* command : {"validate", "run"}) {
    CAPTURE(command);
    const Outcome o = run_program(scratch.path, {command, "s.json"});
    CAPTURE(o.all());
    CHECK(o.status == 2);
    CHECK(o.all().find(key) != std::string::npos);
    CHECK(snapshot(scratch.path).size() == 1);  // the scene alone: no output/
  }
}

}  // namespace

TEST_CASE("a contact that reaches the given window's end: validate and run both refuse it") {
  both_refuse(R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5},
    "grid": {"cells": 256, "window": [-1e-4, 1e-4]}})",
              "grid.window: the contact reaches the window's");
}

TEST_CASE("a load for which the default window finds no contact half-width: validate and run both refuse it") {
  // Within every key's range, but a Hertz half-width of some 15 km: a gel-soft body pressed as a steel one.
  both_refuse(R"({"name": "s", "materials": {"both": {"E": 1e3, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 100}, "load": {"P": 1e9}, "grid": {"cells": 256}})",
              "grid.window: cannot be chosen for this profile and load");
}

TEST_CASE("the analogy route asked for a cycle in reverse slip: validate and run both refuse it") {
  both_refuse(R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5,
    "load": {"P": 1e5, "Q": {"ratio": 0.2}, "bulk_stress": {"amplitude": 3e8}},
    "grid": {"cells": 256}, "effects": {"tangential": {"route": "analogy"}}})",
              "effects.tangential");
}

TEST_CASE("a cycle_by_cycle wear run past its stability limit: validate and run both refuse it") {
  both_refuse(R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": 0.5}},
    "grid": {"cells": 4096}, "effects": {"wear": {"k": 1e-9, "cycles": 10, "stepper": "cycle_by_cycle"}}})",
              "effects.wear.stepper");
}

// Wear under load.blocks whose first block is displacement-controlled and a later one slides under force control
// (Q/fP = 1.057): validate passed it and run refused it after solving the first block's cycle. Found by running
// random scenes. Now each later block is checked as the scene's own load is, a history block at every point.
TEST_CASE("a later load block that slides under force control: validate and run both refuse it, naming the block") {
  const std::string head = R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "friction": 0.5, "grid": {"cells": 128},
    "effects": {"wear": {"k": 1e-13, "cycles": 30}}, "load": {"P": 1e5, "blocks": [{"delta": 5e-7, "cycles": 10},)";
  both_refuse(head + R"({"Q": {"ratio": 1.057}, "cycles": 10}, {"Q": {"ratio": 0.5}, "cycles": 10}]}})",
              "load.blocks[1].Q: Q = 52850 N/m reaches f P = 50000 N/m: the bodies slide");
  both_refuse(head + R"({"Q": {"ratio": 0.5}, "cycles": 10},
      {"history": [[0, 1e5, 2e4, 0], [1, 1e5, -6e4, 0], [2, 1e5, 2e4, 0]], "cycles": 10}]}})",
              "load.blocks[2].history: reaches |Q| = 60000 N/m >= f P = 50000 N/m at t = 1");
}
