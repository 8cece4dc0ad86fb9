// `validate` and `run` agree: when validate refuses a scene (exit 2), run refuses it too and writes nothing; when
// validate accepts it, run does not refuse it (it exits 0, or 3 when a solver does not converge). Tried on every
// scene of the bad-scene corpus (tests/bad_scenes/expected.tsv) and every example; the hostile tables of the other
// files check the same on each of their cases.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

const fs::path kSource = FRETWEAR_SOURCE_DIR;

// Examples too slow for this tier's budget (kTimeLimit, on a machine running another test beside): a long wear run
// on a fine grid, a wear run under displacement control on 1024 cells or more (in gross slip each body worn in its
// own frame: gross_slip_displacement_wear takes half a minute alone), or a stress map. They are validated only (the
// example tests of tests/CMakeLists.txt run them all).
bool slow(const json& scene) {
  const json effects = scene.value("effects", json::object());
  const int cells = scene.value("grid", json::object()).value("cells", 0);
  const double cycles = effects.contains("wear") ? effects["wear"].value("cycles", 0.0) : 0.0;
  const bool displacement = scene.value("load", json::object()).value("control", "") == "displacement";
  return effects.contains("stress") || (cycles > 1e6 && cells > 1024) ||
         (effects.contains("wear") && displacement && cells >= 1024);
}

}  // namespace

TEST_CASE("validate and run agree on every scene of the bad-scene corpus") {
  std::ifstream list(kSource / "tests" / "bad_scenes" / "expected.tsv");
  REQUIRE(list);
  int n = 0;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    const std::string file = line.substr(0, tab);
    check_scene({file, read_file(kSource / "tests" / "bad_scenes" / file), {kInvalid}, line.substr(tab + 1)});
    ++n;
  }
  CHECK(n >= 40);
}

TEST_CASE("validate and run agree on every example") {
  int n = 0, ran = 0;
  for (const auto& e : fs::directory_iterator(kSource / "examples")) {
    if (e.path().extension() != ".json") continue;
    const std::string text = read_file(e.path());
    const json scene = json::parse(text);
    ++n;
    if (!slow(scene)) {
      check_scene({e.path().filename().string(), text, {kDone}, ""});
      ++ran;
      continue;
    }
    INFO("case: " << e.path().filename().string() << " (validated only: too slow for this tier)");
    Scratch s;
    s.write("s.json", text);
    const Outcome v = s.fretwear({"validate", "s.json", "-q"});
    CHECK_MESSAGE(v.exited(kDone), v.describe());
  }
  CHECK(n >= 20);
  MESSAGE(ran << " of " << n << " examples run, the others validated only");
}
