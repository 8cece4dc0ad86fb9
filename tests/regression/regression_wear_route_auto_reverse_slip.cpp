// Under route "auto" the cycle stage falls back to the incremental route on reverse slip, but the wear stage decided
// the route again, picked the analogy and refused the scene (exit 2) that validate had passed: paper 001's
// reverse-slip example with a wear effect. Even with route "incremental" set by hand, wear.asymptote_note still asked
// for it. The wear stage now runs the route the cycle stage ran.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "program.hpp"

using namespace fretwear::test;

namespace {

// examples/paper001_reverse_slip.json with wear, on a coarser grid and fewer cycles.
std::string reverse_slip_wear(const std::string& route) {
  return R"({"name": "s", "materials": {"both": {"E": 63.545e9, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.0254}, "friction": 0.5,
    "load": {"P": 210152.2, "Q": {"amplitude": 47284.25}, "bulk_stress": {"amplitude": 304220000}},
    "grid": {"cells": 256}, "effects": {"tangential": {"route": ")" + route + R"("},
    "wear": {"k": 1e-15, "cycles": 1e4, "record": 4}}, "output": {"plots": false}})";
}

}  // namespace

TEST_CASE("wear under route auto with reverse slip runs the incremental route the cycle stage chose") {
  for (const char* route : {"auto", "incremental"}) {
    CAPTURE(route);
    Scratch scratch{"route"};
    write_file(scratch.path / "s.json", reverse_slip_wear(route));
    const Outcome v = run_program(scratch.path, {"validate", "s.json"});
    CAPTURE(v.all());
    CHECK(v.status == 0);
    const Outcome o = run_program(scratch.path, {"run", "-q", "s.json"});
    CAPTURE(o.all());
    REQUIRE(o.status == 0);
    const auto summary = nlohmann::json::parse(read_file(scratch.path / "output" / "s" / "summary.json"));
    CHECK(summary["cycle"]["regime"] == "reverse_slip");
    CHECK(summary["wear"]["route"] == "incremental");
    const std::string note = summary["wear"].value("asymptote_note", "");
    CHECK(note.find("reverse slip") != std::string::npos);
    CHECK(note.find("route") == std::string::npos);  // nothing asked of the user that the scene already says
  }
}
