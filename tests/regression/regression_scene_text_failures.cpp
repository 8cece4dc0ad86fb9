// The scene file's own failures: a number that overflows a double was an internal error (exit 1); a duplicate key
// was accepted, the last one silently winning; "output": {"plots": false} without a dir was refused although the
// dir has a default; an invalid load.Q drew a second, contradictory "load.Q: missing"; a denormal modulus passed
// validate. Each is now exit 2 naming the key (or, for the default dir, a run), and one message per problem.
#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

namespace {

const std::string kHead = R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, )";

// validate and run exit with `status`; both print `fragment`; a refusal writes nothing.
Outcome both(const std::string& scene, int status, const std::string& fragment) {
  Scratch scratch{"scenetext"};
  write_file(scratch.path / "s.json", scene);
  Outcome last;
  for (const char* command : {"validate", "run"}) {
    CAPTURE(command);
    last = run_program(scratch.path, {command, "-q", "s.json"});
    CAPTURE(last.all());
    CHECK(last.status == status);
    CHECK(last.all().find(fragment) != std::string::npos);
  }
  if (status == 2) CHECK(snapshot(scratch.path).size() == 1);
  return last;
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("a number that overflows a double was an internal error: now exit 2 naming the key and its line") {
  both(kHead + R"("load": {"P": 1e309}})", 2, "load.P: 1e309 on line 2 overflows a double");
}

TEST_CASE("a duplicate key was accepted, the last one winning: now exit 2 naming it and its lines") {
  both(kHead + "\"load\": {\"P\": 1e5,\n \"P\": 2e5}}", 2, "load.P: given twice (lines 2 and 3)");
}

TEST_CASE("output.plots without output.dir was refused: now the default folder output/<name> is used") {
  Scratch scratch{"plots"};
  write_file(scratch.path / "s.json", kHead + R"("load": {"P": 1e5}, "grid": {"cells": 256},
    "output": {"plots": false}})");
  const Outcome o = run_program(scratch.path, {"run", "-q", "s.json"});
  CAPTURE(o.all());
  CHECK(o.status == 0);
  CHECK(fs::exists(scratch.path / "output" / "s" / "summary.json"));
}

TEST_CASE("an invalid load.Q drew a second, contradictory 'missing': now one message") {
  const Outcome o = both(kHead + R"("friction": 0.5, "load": {"P": 1e5, "Q": {"ratio": -1}},
    "effects": {"tangential": {}}})", 2, "load.Q.ratio: -1 is not allowed");
  CHECK(count(o.err, "load.Q") == 1);
}

TEST_CASE("a denormal modulus passed validate and failed in run: now both refuse it, naming the key") {
  both(R"({"name": "s", "materials": {"both": {"E": 1e-310, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}})", 2, "materials.both.E");
}

// A NUL in a scene's string or key ended the message there: `name: "p` and nothing of the problems after it.
TEST_CASE("a NUL in a scene's strings cut every problem after it: now each is printed, the NUL as \\u0000") {
  const Outcome o = both(R"({"name": "p\u0000x", "\u0000bad": 1, "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cyl\u0000inder", "R": 0.01}, "load": {"P": 1e5}})",
                         2, R"(name: "p\u0000x" cannot name a folder)");
  CHECK(o.err.find(R"(profile.type: "cyl\u0000inder" is not a profile type)") != std::string::npos);
  CHECK(o.err.find(R"(\u0000bad: unknown key)") != std::string::npos);
  CHECK(o.err.find('\0') == std::string::npos);
}

// A block's cycles refused (0) drew a second, false problem: the blocks' total, counted with a stand-in 1, did not
// match effects.wear.cycles.
TEST_CASE("a block's invalid cycles drew a false 'not the blocks' total': now one message") {
  const Outcome o = both(kHead + R"("friction": 0.5, "load": {"P": 1e5, "blocks": [{"Q": {"ratio": 0.5}, "cycles": 0},
    {"Q": {"ratio": 0.6}, "cycles": 1e6}]}, "effects": {"wear": {"law": "archard", "k": 1e-12, "cycles": 1e6}}})",
                         2, "load.blocks[0].cycles: 0 is not allowed");
  CHECK(count(o.all(), "effects.wear.cycles") == 0);
}
