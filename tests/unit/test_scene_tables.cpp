// Scene parsing of measured profiles (SCENES.md, "Measured profiles"): a table read from a CSV file relative to the
// scene, in its units, with its interpolation and checksum; every malformed file named with its line. And one problem
// per mistake: a wrong word never also makes the keys that depend on it unknown, missing or misplaced.
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "engine/scene.hpp"

using namespace fretwear;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// A folder of its own for a test's files, removed afterwards.
struct Folder {
  fs::path dir = fs::temp_directory_path() / ("fretwear_tables_" + std::to_string(::getpid()));
  Folder() { fs::create_directories(dir); }
  ~Folder() { fs::remove_all(dir); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
};

json with_profile(const json& profile) {
  return {{"name", "s"},
          {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
          {"profile", profile},
          {"load", {{"P", 1e5}}}};
}

std::vector<std::string> problems(const json& j, const fs::path& dir = {}) {
  try {
    parse_scene(j, "scene", dir);
  } catch (const SceneError& e) {
    return e.problems();
  }
  return {};
}

// A parabola x²/(2R), R = 10 mm, at x = −0.5 … 0.5 mm every 0.1 mm: heights in µm.
const std::string kPadCsv =
    "x_mm,h_um\n-0.5,12.5\n-0.4,8\n-0.3,4.5\n-0.2,2\n-0.1,0.5\n0,0\n0.1,0.5\n0.2,2\n0.3,4.5\n0.4,8\n0.5,12.5\n";

}  // namespace

TEST_CASE("a table file in mm and um, relative to the scene's folder, reads as the same table in metres") {
  Folder f;
  f.write("pad.csv", kPadCsv);
  const json j = with_profile({{"type", "table"}, {"file", "pad.csv"}, {"x_unit", "mm"}, {"h_unit", "um"},
                               {"interpolation", "makima"}});
  const Scene s = parse_scene(j, "scene", f.dir);
  REQUIRE(s.profile.x.size() == 11);
  CHECK(s.profile.x.front() == doctest::Approx(-0.5e-3).epsilon(1e-15));
  CHECK(s.profile.h.front() == doctest::Approx(12.5e-6).epsilon(1e-15));
  CHECK(s.profile.interpolation == Interpolation::makima);
  // The resolved scene names the file by its full path, its units, and its checksum.
  const json r = s.to_json()["profile"];
  CHECK(r["file"] == (f.dir / "pad.csv").lexically_normal().string());
  CHECK(r["x_unit"] == "mm");
  CHECK(r["h_unit"] == "um");
  CHECK(r["interpolation"] == "makima");
  CHECK(r["checksum"].get<std::string>().rfind("fnv1a64:", 0) == 0);
  CHECK(r["checksum"].get<std::string>().size() == 8 + 16);
  CHECK_FALSE(r.contains("x"));
  // The resolved scene parses again, from anywhere, to the same table.
  const Scene again = parse_scene(s.to_json());
  CHECK(again.profile.x == s.profile.x);
  CHECK(again.profile.h == s.profile.h);
}

TEST_CASE("a table file with its fields in double quotes, as spreadsheets export them, reads as without") {
  Folder f;
  std::string quoted = "\"x_mm\",\"h_um\"\n";
  for (const std::string row : {"-0.5,12.5", "0,0", "0.5,12.5"})
    quoted += "\"" + row.substr(0, row.find(',')) + "\", \"" + row.substr(row.find(',') + 1) + "\"\n";
  f.write("quoted.csv", quoted);
  f.write("plain.csv", "x_mm,h_um\n-0.5,12.5\n0,0\n0.5,12.5\n");
  auto table = [&](const std::string& file) {
    return parse_scene(with_profile({{"type", "table"}, {"file", file}, {"x_unit", "mm"}, {"h_unit", "um"}}), "scene",
                       f.dir)
        .profile;
  };
  const ProfileSpec q = table("quoted.csv"), p = table("plain.csv");
  CHECK(q.x == p.x);
  CHECK(q.h == p.h);
}

TEST_CASE("the checksum of a resolved scene refuses a file that changed since") {
  Folder f;
  f.write("pad.csv", kPadCsv);
  const json resolved = parse_scene(with_profile({{"type", "table"}, {"file", "pad.csv"}, {"x_unit", "mm"},
                                                  {"h_unit", "um"}}),
                                    "scene", f.dir)
                            .to_json();
  f.write("pad.csv", kPadCsv + "0.6,18\n");
  const auto p = problems(resolved);
  REQUIRE(p.size() == 1);
  CHECK(p[0].rfind("profile.checksum:", 0) == 0);
  CHECK(p[0].find("the file changed") != std::string::npos);
}

TEST_CASE("the units of an inline table scale it, and every interpolation applies to it") {
  const json j = with_profile({{"type", "table"}, {"x", {-200, -100, 0, 100, 200}}, {"h", {4, 1, 0, 1, 4}},
                               {"x_unit", "um"}, {"h_unit", "um"}, {"interpolation", "cubic"}});
  const Scene s = parse_scene(j);
  CHECK(s.profile.x.back() == doctest::Approx(2e-4).epsilon(1e-15));
  CHECK(s.profile.h.back() == doctest::Approx(4e-6).epsilon(1e-15));
  const json r = s.to_json()["profile"];
  CHECK(r["interpolation"] == "cubic");
  CHECK(r["x"].back().get<double>() == s.profile.x.back());  // written in metres
  CHECK_FALSE(r.contains("x_unit"));
}

TEST_CASE("a malformed table file: one problem naming the key, the file, the line and what is wrong") {
  Folder f;
  struct Case {
    const char* what;
    std::string text;
    std::string said;
  };
  const std::vector<Case> cases = {
      {"missing column", "x,h\n0,1\n1\n2,3\n", "line 3: has 1 column; give two, x and h"},
      {"text in a number", "x,h\n0,1\n1,1.2.3\n2,3\n", "line 3: \"1.2.3\" in column h is not a finite number"},
      {"unsorted x", "x,h\n0,1\n2,1\n1,3\n", "line 4: x = 1 does not exceed x = 2 on line 3"},
      {"one row", "x,h\n0,1\n", "line 2: has one data row"},
      {"a header only", "x,h\n", "line 1: has no data rows"},
      {"empty", "", "is empty"},
      {"no header", "0,1\n1,2\n2,3\n", "line 1: holds two numbers, not a header"},
      {"no header after a byte order mark", "\xEF\xBB\xBF" "0,1\n1,2\n2,3\n", "line 1: holds two numbers, not a header"},
      {"three columns", "x,h\n0,1,2\n1,2\n2,3\n", "line 2: has 3 columns"},
      {"infinity", "x,h\n0,1\n1,inf\n2,3\n", "line 3: \"inf\" in column h is not a finite number"},
      {"beyond 100 m", "x,h\n0,1\n1,1e6\n", "line 3: h = 1000 m is not allowed"},
  };
  for (const Case& c : cases) {
    const std::string what = c.what;
    CAPTURE(what);
    f.write("bad.csv", c.text);
    const auto p = problems(with_profile({{"type", "table"}, {"file", "bad.csv"}, {"h_unit", "mm"}}), f.dir);
    REQUIRE(p.size() == 1);
    CHECK(p[0].rfind("profile.file: \"" + (f.dir / "bad.csv").string() + "\"", 0) == 0);
    CHECK_MESSAGE(p[0].find(c.said) != std::string::npos, p[0]);
  }
}

TEST_CASE("a table file that is missing, a folder, or too large is refused without reading it") {
  Folder f;
  fs::create_directory(f.dir / "folder.csv");
  {
    std::ofstream(f.dir / "large.csv") << "x,h\n";
    fs::resize_file(f.dir / "large.csv", kMaxSceneBytes + 1);
  }
  for (const auto& [file, said] : {std::pair{"missing.csv", "no such file"},
                                   {"folder.csv", "is not a regular file"},
                                   {"large.csv", "is larger than"}}) {
    CAPTURE(file);
    const auto p = problems(with_profile({{"type", "table"}, {"file", file}}), f.dir);
    REQUIRE(p.size() == 1);
    CHECK(p[0].find(said) != std::string::npos);
  }
}

TEST_CASE("a table file after a byte order mark reads as without it") {
  Folder f;
  f.write("pad.csv", kPadCsv);
  f.write("pad_bom.csv", "\xEF\xBB\xBF" + kPadCsv);
  const auto read = [&](const char* file) {
    return parse_scene(with_profile({{"type", "table"}, {"file", file}, {"x_unit", "mm"}, {"h_unit", "um"}}), "scene",
                       f.dir);
  };
  const Scene a = read("pad.csv"), b = read("pad_bom.csv");
  CHECK(b.profile.x == a.profile.x);
  CHECK(b.profile.h == a.profile.h);
  CHECK(b.profile.x.size() == 11);
}

TEST_CASE("a table file whose path holds a NUL byte, or whose folder's path is not UTF-8, is refused up front") {
  Folder f;
  const fs::path odd = f.dir / "caf\xE9";  // Latin-1, not UTF-8
  fs::create_directories(odd);
  std::ofstream(odd / "pad.csv", std::ios::binary) << kPadCsv;
  const auto p = problems(with_profile({{"type", "table"}, {"file", "pad.csv"}}), odd);
  REQUIRE(p.size() == 1);
  CHECK_MESSAGE(p[0].rfind("profile.file: \"pad.csv\" is read from ", 0) == 0, p[0]);
  CHECK_MESSAGE(p[0].find("not UTF-8") != std::string::npos, p[0]);
  f.write("pad.csv", kPadCsv);
  const auto q = problems(with_profile({{"type", "table"}, {"file", std::string("pad.csv\0x", 9)}}), f.dir);
  REQUIRE(q.size() == 1);
  CHECK_MESSAGE(q[0].find("holds a NUL byte") != std::string::npos, q[0]);
}

TEST_CASE("one problem per mistake: a wrong word does not make its dependent keys unknown, missing or misplaced") {
  const json cycle = {{"name", "s"},
                      {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}}};
  const auto with = [&](const json& patch) {
    json j = cycle;
    j.merge_patch(patch);
    return j;
  };
  const auto grown = [](json g, const json& patch) {
    g.merge_patch(patch);
    return g;
  };
  const json growth = {{"law", "paris"}, {"C", 5e-30}, {"m", 3.0}, {"dK_th", 2e6}, {"a_initial", 2e-5},
                       {"a_final", 1e-3}};
  const json blocks = {{{"Q", {{"ratio", 0.3}}}, {"cycles", 10}}, {{"Q", {{"ratio", 0.5}}}, {"cycles", 10}}};
  struct Case {
    const char* root;
    json scene;
  };
  const std::vector<Case> cases = {
      {"effects.wear.law", with({{"effects", {{"wear", {{"law", "archad"}, {"k", 1e-15}, {"cycles", 10}}}}}})},
      {"effects.wear.k", with({{"effects", {{"wear", {{"law", "energy"}, {"k", 1e-15}, {"cycles", 10}}}}}})},
      {"effects.wear.cycles", with({{"load", {{"Q", nullptr}, {"blocks", blocks}}},
                                    {"effects", {{"wear", {{"k", 1e-15}, {"cycles", "20"}}}}}})},
      {"load.blocks[0]", with({{"load", {{"Q", nullptr}, {"blocks", {{{"cycles", 10}}, blocks[1]}}}},
                               {"effects", {{"wear", {{"k", 1e-15}, {"cycles", 20}}}}}})},
      {"load.blocks[0].Q.ratio", with({{"load", {{"Q", nullptr}, {"blocks", {{{"Q", {{"ratio", -1}}}, {"cycles", 10}},
                                                                             blocks[1]}}}},
                                       {"effects", {{"wear", {{"k", 1e-15}, {"cycles", 20}}}}}})},
      {"load.blocks", with({{"load", {{"Q", nullptr}, {"blocks", "two"}}},
                            {"effects", {{"wear", {{"k", 1e-15}, {"cycles", 20}}}}}})},
      {"load.control", with({{"load", {{"Q", nullptr}, {"control", "displace"}, {"delta", 1e-6}}},
                             {"effects", {{"tangential", json::object()}}}})},
      {"effects.life.growth.short_crack",
       with({{"effects", {{"tangential", json::object()},
                          {"life", {{"growth", grown(growth, {{"short_crack", "elhaddad"},
                                                                 {"fatigue_limit", 6e8}})}}}}}})},
      {"effects.life.growth.law",
       with({{"effects", {{"tangential", json::object()}, {"life", {{"growth", grown(growth, {{"law", "walker"}})}}}}}})},
      {"profile.type", with_profile({{"type", "cylindre"}, {"R", 0.01}})},
      {"profile.interpolation", with_profile({{"type", "table"}, {"x", {0, 1e-4, 2e-4}}, {"h", {1e-6, 0, 1e-6}},
                                                   {"interpolation", "spline"}})},
      {"profile.x_unit", with_profile({{"type", "table"}, {"x", {0, 100, 200}}, {"h", {1e-6, 0, 1e-6}},
                                            {"x_unit", "micron"}})},
      {"profile.file", with_profile({{"type", "table"}, {"file", "pad.csv"}, {"x", {0, 1e-4}}})},
  };
  for (const Case& c : cases) {
    const std::string root = c.root;
    CAPTURE(root);
    const auto p = problems(c.scene);
    CHECK_MESSAGE(p.size() == 1, "problems: " << json(p).dump());
    REQUIRE(!p.empty());
    CHECK(p[0].rfind(std::string(c.root) + ":", 0) == 0);
  }
}
