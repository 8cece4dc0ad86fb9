// Measured profiles through the program (SCENES.md, "Measured profiles"): a table file beside the scene is read from
// the scene's folder wherever the program runs; a malformed one makes validate and run exit 2 naming the file and the
// line, and write nothing; the resolved scene a run writes records the file's checksum and runs again.
#include <string>
#include <vector>

#include <doctest/doctest.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

json table_scene(const std::string& file) {
  json j = base_scene();
  j["profile"] = {{"type", "table"}, {"file", file}, {"x_unit", "mm"}, {"h_unit", "um"}, {"interpolation", "makima"}};
  return j;
}

// x²/(2R), R = 10 mm, every 10 µm over ±0.3 mm: x in mm, h in µm.
std::string cylinder_csv() {
  std::string csv = "x_mm,h_um\n";
  for (int i = -30; i <= 30; ++i) {
    const double x = i * 1e-2;
    csv += std::to_string(x) + "," + std::to_string(x * x / 20.0 * 1e3) + "\n";
  }
  return csv;
}

}  // namespace

TEST_CASE("a malformed profile file: validate and run exit 2 naming the file and the line, nothing written") {
  Scratch s;
  struct Case {
    const char* what;
    const char* csv;
    const char* said;
  };
  const std::vector<Case> cases = {
      {"missing column", "x,h\n0,1\n0.1\n0.2,3\n", "line 3: has 1 column"},
      {"text in a number", "x,h\n0,1\n0.1,1.0e\n0.2,3\n", "line 3: \"1.0e\" in column h is not a finite number"},
      {"unsorted x", "x,h\n0,1\n0.2,1\n0.1,3\n", "line 4: x = 0.1 does not exceed x = 0.2 on line 3"},
      {"one row", "x,h\n0,1\n", "line 2: has one data row"},
  };
  for (const Case& c : cases) {
    const std::string what = c.what;
    CAPTURE(what);
    s.write("scenes/pad.csv", c.csv);
    s.write("scenes/s.json", table_scene("pad.csv").dump());
    const Snapshot before = s.snapshot();
    for (const char* command : {"validate", "run"}) {
      const Outcome r = s.fretwear({command, "scenes/s.json"});
      CHECK_MESSAGE(r.exited(kInvalid), r.describe());
      CHECK_MESSAGE(names(r.err, "profile.file: \""), r.describe());
      CHECK_MESSAGE(names(r.err, "pad.csv\", " + std::string(c.said)), r.describe());
    }
    CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "wrote: " << join(changes(before, s.snapshot())));
  }
}

TEST_CASE("a profile file is read from the scene's folder, and the resolved scene names it with its checksum") {
  Scratch s;
  s.write("scenes/pad.csv", cylinder_csv());
  json j = table_scene("pad.csv");
  j["output"] = {{"dir", "out"}};
  s.write("scenes/s.json", j.dump());
  const Outcome r = s.fretwear({"run", "scenes/s.json", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const json resolved = json::parse(read_file(s.work / "out" / "scene.resolved.json"));
  CHECK(resolved["profile"]["file"] == (s.work / "scenes" / "pad.csv").lexically_normal().string());
  CHECK(resolved["profile"]["checksum"].get<std::string>().rfind("fnv1a64:", 0) == 0);
  // The resolved scene validates as it is, and refuses the file once it changed.
  s.write("again.json", resolved.dump());
  const Outcome same = s.fretwear({"validate", "again.json"});
  CHECK_MESSAGE(same.exited(kDone), same.describe());
  s.write("scenes/pad.csv", cylinder_csv() + "0.31,4.805\n");
  const Outcome changed = s.fretwear({"validate", "again.json"});
  CHECK_MESSAGE(changed.exited(kInvalid), changed.describe());
  CHECK_MESSAGE(names(changed.err, "profile.checksum:"), changed.describe());
}
