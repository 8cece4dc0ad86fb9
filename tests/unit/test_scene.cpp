// Scene parsing: defaults, the resolved scene, and one test per kind of error, each naming its JSON path and what is
// allowed, all problems reported at once.
#include <cmath>
#include <limits>
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/scene.hpp"
#include "support.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json good() {
  return {{"name", "s"},
          {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"load", {{"P", 1e5}}}};
}

// The problems parse_scene reports for j (empty when it is valid).
std::vector<std::string> problems(const json& j) {
  try {
    parse_scene(j);
  } catch (const SceneError& e) {
    return e.problems();
  }
  return {};
}

// True when some problem starts with path and contains every fragment.
bool reports(const json& j, const std::string& path, std::initializer_list<std::string> fragments) {
  for (const auto& p : problems(j)) {
    if (p.rfind(path + ":", 0) != 0) continue;
    bool all = true;
    for (const auto& f : fragments) all = all && p.find(f) != std::string::npos;
    if (all) return true;
  }
  return false;
}

// The problems parse_scene_text reports for text (empty when it is valid).
std::vector<std::string> text_problems(const std::string& text) {
  try {
    parse_scene_text(text, "s");
  } catch (const SceneError& e) {
    return e.problems();
  }
  return {};
}

// good() written one key a line; extra is put in "load" after P (P on line 7, extra from line 8).
std::string good_text(const std::string& extra = "") {
  return "{\n"
         "\"name\": \"s\",\n"
         "\"materials\": {\"both\": {\"E\": 2e11, \"nu\": 0.3}},\n"
         "\"profile\": {\"type\": \"cylinder\", \"R\": 0.01},\n"
         "\"load\": {\n"
         "\n"
         "  \"P\": 1e5" + extra + "\n"
         "}\n"
         "}\n";
}

}  // namespace

TEST_CASE("a minimal scene gets every default") {
  const Scene s = parse_scene(good());
  CHECK(s.plane == PlaneState::strain);
  CHECK(s.cells == 1024);
  CHECK_FALSE(s.window);
  CHECK(s.output_dir == std::filesystem::path("output/s"));
  CHECK(s.plots);
  const json r = s.to_json();
  CHECK(r["profile"]["offset_x"] == 0.0);
  CHECK(r["grid"]["cells"] == 1024);
  // The resolved scene parses back to the same scene.
  CHECK(parse_scene(r).to_json() == r);
}

TEST_CASE("the default scene is valid and resolves to itself") {
  const json d = default_scene_json();
  CHECK(parse_scene(d).to_json() == d);
}

TEST_CASE("a scene without a name takes the file's") {
  json j = good();
  j.erase("name");
  CHECK(parse_scene(j, "from_file").name == "from_file");
}

TEST_CASE("unknown keys are errors that list the known ones") {
  json j = good();
  j["profile"]["radius"] = 0.01;
  j["lod"] = 1;
  CHECK(reports(j, "profile.radius", {"unknown key", "R"}));
  CHECK(reports(j, "lod", {"unknown key", "load"}));
}

TEST_CASE("missing keys") {
  json j = good();
  j.erase("load");
  j["materials"]["both"].erase("E");
  j["profile"].erase("R");
  CHECK(reports(j, "load", {"missing"}));
  CHECK(reports(j, "materials.both.E", {"missing"}));
  CHECK(reports(j, "profile.R", {"missing", "a radius in [1e-9, 100] m"}));
}

TEST_CASE("wrong types") {
  json j = good();
  j["load"]["P"] = "100 kN";
  j["profile"]["R"] = json::array({1});
  j["materials"] = 3;
  j["output"] = {{"plots", "yes"}};
  CHECK(reports(j, "load.P", {"a string", "a normal load in"}));
  CHECK(reports(j, "profile.R", {"an array"}));
  CHECK(reports(j, "materials", {"a number", "object"}));
  CHECK(reports(j, "output.plots", {"true or false"}));
  CHECK(problems(json::array({1, 2})).at(0).find("JSON object") != std::string::npos);
}

TEST_CASE("impossible physics: E ≤ 0, ν outside (−1, 0.5), P ≤ 0, R ≤ 0") {
  json j = good();
  j["materials"] = {{"pad", {{"E", 0}, {"nu", 0.3}}}, {"specimen", {{"E", 2e11}, {"nu", 0.5}}}};
  j["load"]["P"] = -1;
  j["profile"]["R"] = 0;
  CHECK(reports(j, "materials.pad.E", {"a Young's modulus in [1000, 1e13] Pa"}));
  CHECK(reports(j, "materials.specimen.nu", {"(-1, 0.5)"}));
  CHECK(reports(j, "load.P", {"a normal load in [1e-6, 1e12] N/m"}));
  CHECK(reports(j, "profile.R", {"a radius in [1e-9, 100] m"}));
  CHECK(problems(j).size() == 4);  // every problem at once
}

TEST_CASE("materials: both, or pad and specimen") {
  json j = good();
  j["materials"]["pad"] = {{"E", 1e11}, {"nu", 0.3}};
  CHECK(reports(j, "materials", {"not both"}));
  j["materials"].erase("both");
  CHECK(reports(j, "materials.specimen", {"missing"}));
}

TEST_CASE("tables: at least two points, x increasing, one h per x") {
  json j = good();
  j["profile"] = {{"type", "table"}, {"x", {0.0}}, {"h", {0.0}}};
  CHECK(reports(j, "profile.x", {"at least two"}));
  j["profile"] = {{"type", "table"}, {"x", {0.0, 1e-3, 1e-3}}, {"h", {0.0, 1e-6, 2e-6}}};
  CHECK(reports(j, "profile.x[2]", {"increase"}));
  j["profile"] = {{"type", "table"}, {"x", {0.0, 1e-3}}, {"h", {0.0}}};
  CHECK(reports(j, "profile.h", {"one h per x"}));
  j["profile"] = {{"type", "table"}, {"x", {0.0, "a"}}, {"h", {0.0, 0.0}}};
  CHECK(reports(j, "profile.x[1]", {"finite number"}));
}

TEST_CASE("enum words list what is accepted") {
  json j = good();
  j["profile"]["type"] = "cylindre";
  j["plane"] = "strane";
  CHECK(reports(j, "profile.type", {"cylinder", "flat_rounded", "envelope"}));
  CHECK(reports(j, "plane", {"\"strain\" or \"stress\""}));
}

TEST_CASE("nested profiles report the path of the term") {
  json j = good();
  j["profile"] = {{"type", "sum"},
                  {"terms", {{{"type", "cylinder"}, {"R", 0.01}}, {{"type", "wavy"}, {"amplitude", -1}}}}};
  CHECK(reports(j, "profile.terms[1].amplitude", {"an amplitude in [1e-9, 100] m"}));
  CHECK(reports(j, "profile.terms[1].wavelength", {"missing"}));
  j["profile"] = {{"type", "envelope"}, {"terms", json::array()}};
  CHECK(reports(j, "profile.terms", {"non-empty"}));
}

TEST_CASE("grid: at least 16 whole cells, and a window that contains the lowest point") {
  json j = good();
  j["grid"] = {{"cells", 8}};
  CHECK(reports(j, "grid.cells", {"16"}));
  j["grid"] = {{"cells", 100.5}};
  CHECK(reports(j, "grid.cells", {"whole number"}));
  j["grid"] = {{"cells", 1e9}};
  CHECK(reports(j, "grid.cells", {"out of range"}));
  j["grid"] = {{"window", {1e-3, 2e-3}}};
  CHECK(reports(j, "grid.window", {"lowest point"}));
  j["grid"] = {{"window", {1e-3, -1e-3}}};
  CHECK(reports(j, "grid.window", {"x_min < x_max"}));
  j["grid"] = {{"window", {1e-3}}};
  CHECK(reports(j, "grid.window", {"[x_min, x_max]"}));
}

TEST_CASE("a lone waviness needs a window") {
  json j = good();
  j["profile"] = {{"type", "wavy"}, {"amplitude", 1e-6}, {"wavelength", 1e-3}};
  CHECK(reports(j, "grid.window", {"missing"}));
  j["grid"] = {{"window", {-5e-4, 5e-4}}};
  CHECK(problems(j).empty());
}

TEST_CASE("a tilt steeper than the flanks has no lowest point") {
  json j = good();
  j["profile"] = {{"type", "wedge"}, {"angle_deg", 0.01}, {"tilt_rad", 0.5}};
  CHECK(reports(j, "profile", {"no lowest point"}));
}

TEST_CASE("keys of capabilities not built yet are reported as such, never ignored") {
  json j = good();
  j["load"]["history"] = json::array();
  j["effects"] = {{"crack", {{"lengths", {1e-5}}, {"angle_deg", 5}}}, {"tangential", {{"route", "incremental"}, {"increments", 42}}}};
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  CHECK(reports(j, "load.history", {"not long enough", "[t, P, Q, sigma_bulk]"}));  // built: an empty one is named
  CHECK(reports(j, "effects.crack.angle_deg", {"[15, 165]"}));  // inclined cracks are built; too flat ones are not
  CHECK(reports(j, "effects.tangential.increments", {"multiple of 4"}));
}

TEST_CASE("the tangential effect: friction, and Q as exactly one of amplitude or ratio") {
  json j = good();
  j["effects"] = {{"tangential", json::object()}};
  CHECK(reports(j, "friction", {"missing"}));
  CHECK(reports(j, "load.Q", {"missing", "amplitude", "ratio"}));
  j["friction"] = 0.0;
  j["load"]["Q"] = {{"ratio", 0.5}, {"amplitude", 1e4}};
  CHECK(reports(j, "friction", {"(0, 10]"}));
  CHECK_FALSE(reports(j, "friction", {"missing"}));  // one problem for one cause: given, but not allowed
  CHECK(reports(j, "load.Q", {"exactly one"}));
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", -0.5}};
  CHECK(reports(j, "load.Q.ratio", {"a ratio Q/(fP) in [0, 100]"}));
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"]["tangential"] = {{"route", "analogie"}, {"increments", 2}};
  CHECK(reports(j, "effects.tangential.route", {"auto", "analogy"}));
  CHECK(reports(j, "effects.tangential.increments", {"4 to 100000"}));
  j["effects"]["tangential"] = {{"route", "analogy"}};
  const Scene s = parse_scene(j);
  CHECK(s.Q_max() == test::rel(0.5 * 0.5 * 1e5, 1e-15));
  CHECK(parse_scene(s.to_json()).to_json() == s.to_json());
}

TEST_CASE("the wear effect: law and its coefficient, cycles, stepper, tolerance, records, it implies the cycle") {
  json j = good();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"wear", {{"law", "archard"}, {"k", 1e-15}, {"cycles", 1e6}}}};
  Scene s = parse_scene(j);
  REQUIRE(s.wear);
  CHECK(s.tangential);
  CHECK(s.tangential_implied);
  CHECK(s.wear->record_count == 16);
  CHECK(parse_scene(s.to_json()).to_json() == s.to_json());
  for (const char* stepper : {"implicit", "explicit", "cycle_by_cycle"}) {
    j["effects"]["wear"]["stepper"] = stepper;
    CHECK(to_string(parse_scene(j).wear->stepper) == stepper);
  }
  j["effects"]["wear"] = {{"law", "energy"}, {"k", 1e-15}, {"cycles", 1.5}, {"stepper", "rk45"},
                          {"tolerance", 0.5}, {"record", {10, 5}}, {"pad_fraction", 2}};
  CHECK(reports(j, "effects.wear.k", {"other law", "takes \"alpha\""}));
  CHECK_FALSE(reports(j, "effects.wear.alpha", {"missing"}));  // the same mistake, reported once, as k's
  CHECK(reports(j, "effects.wear.cycles", {"whole number"}));
  CHECK(reports(j, "effects.wear.stepper", {"not a stepper", "\"implicit\"", "\"explicit\"", "\"cycle_by_cycle\""}));
  CHECK(reports(j, "effects.wear.tolerance", {"[1e-5, 0.1]"}));
  CHECK(reports(j, "effects.wear.pad_fraction", {"[0, 1]"}));
  j["effects"]["wear"] = {{"law", "archard"}, {"k", 1e-15}, {"cycles", 100}, {"record", {10, 5}}};
  CHECK(reports(j, "effects.wear.record[1]", {"increasing"}));
  j.erase("friction");
  CHECK(reports(j, "friction", {"effects.wear"}));
}

TEST_CASE("per-body wear coefficients set the sum and the pad's share, and exclude the shared form") {
  json j = good();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"wear", {{"k_pad", 1e-15}, {"k_specimen", 3e-15}, {"cycles", 1e6}}}};
  const Scene s = parse_scene(j);
  REQUIRE(s.wear);
  CHECK(s.wear->per_body);
  CHECK(s.wear->coefficient == 4e-15);
  CHECK(s.wear->pad_fraction == 0.25);
  const json resolved = s.to_json();
  CHECK(resolved["effects"]["wear"]["k_pad"] == 1e-15);
  CHECK(resolved["effects"]["wear"]["k_specimen"] == 3e-15);
  CHECK_FALSE(resolved["effects"]["wear"].contains("k"));
  CHECK_FALSE(resolved["effects"]["wear"].contains("pad_fraction"));
  CHECK(parse_scene(resolved).to_json() == resolved);

  j["effects"]["wear"] = {{"law", "energy"}, {"alpha_pad", 0}, {"alpha_specimen", 2e-15}, {"cycles", 10}};
  const Scene e = parse_scene(j);
  CHECK(e.wear->coefficient == 2e-15);
  CHECK(e.wear->pad_fraction == 0.0);

  j["effects"]["wear"] = {{"k", 1e-15}, {"k_pad", 1e-15}, {"k_specimen", 1e-15}, {"pad_fraction", 0.3},
                          {"cycles", 10}};
  CHECK(reports(j, "effects.wear.k", {"either"}));
  CHECK(reports(j, "effects.wear.pad_fraction", {"leave it out"}));
  j["effects"]["wear"] = {{"k_pad", 1e-15}, {"cycles", 10}};
  CHECK(reports(j, "effects.wear.k_specimen", {"missing"}));
  j["effects"]["wear"] = {{"k_pad", 0}, {"k_specimen", 0}, {"cycles", 10}};
  CHECK(reports(j, "effects.wear.k_pad", {"both 0"}));
  j["effects"]["wear"] = {{"k_pad", -1e-15}, {"k_specimen", 1e-15}, {"alpha_pad", 1e-15}, {"cycles", 10}};
  CHECK(reports(j, "effects.wear.k_pad", {"0 (the body does not wear)"}));
  CHECK(reports(j, "effects.wear.alpha_pad", {"other law"}));
  j["effects"]["wear"] = {{"law", "abrasive"}, {"k_pad", 1e-15}, {"k_specimen", 1e-15}, {"cycles", 10}};
  const std::vector<std::string> bad_law = problems(j);
  CHECK(bad_law.size() == 1);  // the law, and not also its coefficients as unknown keys
}

TEST_CASE("tangential loads without the tangential effect are errors, not ignored") {
  json j = good();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"amplitude", 1e4}};
  j["load"]["bulk_stress"] = {{"amplitude", 1e8}};
  CHECK(reports(j, "friction", {"no effect uses it"}));
  CHECK(reports(j, "load.Q", {"no effect uses it"}));
  CHECK(reports(j, "load.bulk_stress", {"no effect uses it"}));
}

TEST_CASE("dissimilar bodies take the incremental route under any load and every effect: the analogy is refused") {
  json j = good();
  j["materials"] = {{"pad", {{"E", 2e11}, {"nu", 0.3}}}, {"specimen", {{"E", 7e10}, {"nu", 0.33}}}};
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"tangential", json::object()}};
  CHECK_NOTHROW(parse_scene(j));
  j["effects"] = {{"tangential", {{"route", "analogy"}}}};
  CHECK(reports(j, "materials", {"beta", "analogy", "needs similar bodies"}));
  j["effects"] = {{"tangential", json::object()}, {"wear", {{"law", "archard"}, {"k", 1e-17}, {"cycles", 1e6}}}};
  CHECK_NOTHROW(parse_scene(j));  // wear takes the coupled cycle (engine/wear_contacts.hpp)
  j["effects"] = {{"tangential", json::object()}, {"stress", json::object()}};
  CHECK_NOTHROW(parse_scene(j));  // the stresses of the coupled cycle's top and bottom
  j["effects"] = {{"tangential", json::object()}};
  j["load"] = {{"P", 1e5}, {"control", "displacement"}, {"delta", 1e-6}};
  CHECK_NOTHROW(parse_scene(j));
  j["load"] = {{"P", 1e5}, {"history", {{0, 1e5, 2e4, 0}, {1, 1e5, -2e4, 0}, {2, 1e5, 2e4, 0}}}};
  CHECK_NOTHROW(parse_scene(j));
  // A history prescribes Q at its points: with displacement control it is refused with that reason, whatever the
  // bodies.
  j["load"]["control"] = "displacement";
  CHECK(reports(j, "load.history", {"prescribe Q", "force control", "load.control \"force\""}));
}

TEST_CASE("names must make a folder name") {
  json j = good();
  j["name"] = "../escape";
  CHECK(reports(j, "name", {"folder"}));
}

TEST_CASE("the text of a scene: a valid one parses as its document does") {
  CHECK(text_problems(good_text()).empty());
  CHECK(parse_scene_text(good_text()).to_json() == parse_scene(json::parse(good_text()), "scene").to_json());
}

TEST_CASE("a number that overflows a double names its key's path and line, never an internal error") {
  std::vector<std::string> p = text_problems(good_text(",\n  \"Q\": {\"amplitude\": 1e309}"));
  REQUIRE(p.size() == 1);
  CHECK(p[0].rfind("load.Q.amplitude: 1e309 on line 8 overflows a double", 0) == 0);
  CHECK(p[0].find("1.8e308") != std::string::npos);
  p = text_problems("{\"profile\": {\"type\": \"table\", \"x\": [0, -1e400], \"h\": [0, 0]}}");
  REQUIRE(p.size() == 1);
  CHECK(p[0].rfind("profile.x[1]: -1e400 on line 1 overflows", 0) == 0);
  p = text_problems("\n 1" + std::string(400, '0'));
  REQUIRE(p.size() == 1);
  CHECK(p[0].rfind("(top): 1000000000000000000000000000000000000... on line 2 overflows", 0) == 0);
}

TEST_CASE("NaN and Infinity, which are no JSON numbers, are refused at their key, saying what to give") {
  for (const std::string v : {"NaN", "Infinity", "-Infinity", "nan"}) {
    CAPTURE(v);
    const std::vector<std::string> p = text_problems(good_text(",\n  \"Q\": {\"amplitude\": " + v + "}"));
    REQUIRE(p.size() == 1);
    CHECK(p[0].find("not valid JSON (UTF-8) at load.Q.amplitude") != std::string::npos);
    CHECK(p[0].find("NaN and Infinity are not JSON numbers: give a finite number") != std::string::npos);
  }
  const std::vector<std::string> p = text_problems(good_text(",\n  \"Q\": {\"amplitude\": 1e5x}"));
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("NaN and Infinity") == std::string::npos);  // another error, another message
}

TEST_CASE("a key given twice names its full path and every line, with the scene's other problems") {
  std::vector<std::string> p = text_problems(good_text(",\n  \"P\": -1,\n  \"P\": 2e5"));
  REQUIRE(p.size() == 1);
  CHECK(p[0] == "load.P: given 3 times (lines 7, 8 and 9); give each key once");
  p = text_problems(good_text(",\n  \"P\": 2e5,\n  \"lod\": 1"));
  REQUIRE(p.size() == 2);  // every problem at once
  CHECK(p[0] == "load.P: given twice (lines 7 and 8); give each key once");
  CHECK(p[1].rfind("load.lod: unknown key", 0) == 0);
  p = text_problems("{\"materials\": {\"both\": {\"E\": 1, \"E\": 1}}, \"name\": [{\"a\": 1,\n\"a\": 2}]}");
  CHECK(p.at(0) == "materials.both.E: given twice (lines 1 and 1); give each key once");
  CHECK(p.at(1) == "name[0].a: given twice (lines 1 and 2); give each key once");
}

TEST_CASE("the text of a scene: not JSON is named so, nesting is bounded however deep the text goes") {
  std::vector<std::string> p = text_problems("{\"name\": \"s\",}");
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("not valid JSON") != std::string::npos);
  CHECK(p[0].find("line 1, column 14") != std::string::npos);
  const std::size_t n = 1'000'000;
  p = text_problems("{\"name\": " + std::string(n, '[') + std::string(n, ']') + "}");
  REQUIRE(p.size() == 1);
  CHECK(p[0].find("nests deeper than 64") != std::string::npos);
  CHECK(p[0].find(": name[0][0]") != std::string::npos);  // the file, then the path where it nests too deep
}

TEST_CASE("a deep document handed to parse_scene is described without deep recursion") {
  json deep = json::array();
  for (int i = 0; i < 100000; ++i) deep = json::array({std::move(deep)});
  json j = good();
  j["name"] = std::move(deep);
  CHECK(reports(j, "name", {"[[[[", "...", "an array"}));
}

TEST_CASE("output.dir defaults to output/<name> also when only output.plots is given") {
  json j = good();
  j["output"] = {{"plots", false}};
  const Scene s = parse_scene(j);
  CHECK(s.output_dir == std::filesystem::path("output/s"));
  CHECK_FALSE(s.plots);
  j["output"] = {{"dir", ""}};
  CHECK(reports(j, "output.dir", {"is empty"}));
}

TEST_CASE("an invalid value is one problem: never also reported as missing, nor its placeholder judged") {
  json j = good();
  j["friction"] = 0.5;
  j["effects"] = {{"tangential", json::object()}};
  const auto once = [&](const std::string& path, std::initializer_list<std::string> fragments) {
    const auto p = problems(j);
    CAPTURE(p.size() ? p[0] : "");
    CHECK(p.size() == 1);
    CHECK(reports(j, path, fragments));
  };
  j["load"]["Q"] = {{"ratio", -1}};
  once("load.Q.ratio", {"-1 is not allowed"});
  j["load"]["Q"] = {{"amplitude", "x"}};
  once("load.Q.amplitude", {"a string"});
  j["load"]["Q"] = 3;
  once("load.Q", {"a number", "give an object"});
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["friction"] = "high";
  once("friction", {"a string"});
  j["friction"] = 0.5;
  j["load"]["control"] = "displacment";
  j["load"]["delta"] = 1e-6;
  once("load.control", {"not a load control"});
  j["load"]["control"] = "displacement";
  j["load"].erase("Q");
  j["load"]["delta"] = -1e-6;
  once("load.delta", {"-1e-06 is not allowed"});
  j["load"] = {{"P", 1e5}, {"history", {1, 2}}};
  once("load.history[0]", {"[t, P, Q, sigma_bulk]"});
  j["load"] = {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}};
  j["effects"] = {{"wear", {{"law", "archerd"}, {"k", 1e-15}, {"cycles", 1e6}}}};
  once("effects.wear.law", {"not a wear law"});
  j["effects"]["wear"]["law"] = 3;
  once("effects.wear.law", {"a number"});
  j["effects"]["wear"] = {{"law", "archard"}, {"k", 1e-15}, {"cycles", 0.5}, {"record", {10, 1e5}}};
  once("effects.wear.cycles", {"whole number"});  // the records are not judged against an invalid count
  j["effects"]["wear"]["cycles"] = 1e6;
  j["load"] = {{"P", "1e5"}, {"Q", {{"amplitude", 1e4}}}};
  once("load.P", {"a string"});  // nor is Q against f P with a placeholder P
  j["load"] = {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}};
  j["effects"] = {{"tangential", 1}};
  once("effects.tangential", {"give an object"});
  j["effects"] = 1;
  once("effects", {"give an object"});
  j["effects"] = {{"tangential", json::object()}};
  j["materials"] = {{"pad", 1}, {"specimen", {{"E", 7e10}, {"nu", 0.33}}}};
  once("materials.pad", {"give an object"});
  j["materials"] = {{"both", 1}};
  once("materials.both", {"give an object"});
  j["materials"] = {{"pad", {{"E", "2e11"}, {"nu", 0.3}}}, {"specimen", {{"E", 2e11}, {"nu", 0.3}}}};
  j["effects"] = {{"tangential", {{"route", "analogy"}}}};
  once("materials.pad.E", {"a string"});  // no dissimilar pair made of a placeholder modulus
  j = good();
  j["profile"] = {{"type", "wavy"}, {"amplitude", 1e-6}, {"wavelength", 1e-3}};
  j["grid"] = {{"window", {1e-3}}};
  once("grid.window", {"[x_min, x_max]"});
}

namespace {

// j with the value at pointer set to v.
json with(json j, const std::string& pointer, double v) {
  j[json::json_pointer(pointer)] = v;
  return j;
}

// A dimensional number's span: the scene is valid with the number at either bound, and the nearest doubles beyond
// them are refused with one problem, naming the key (path_lo, path_hi) and the allowed span. The lower bound is set
// at pointer_lo, the upper at pointer_hi.
void check_span(const json& base, const std::string& pointer_lo, const std::string& path_lo,
                const std::string& pointer_hi, const std::string& path_hi, double lo, double hi,
                const std::string& allowed) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  CAPTURE(path_lo);
  CAPTURE(allowed);
  CHECK(problems(with(base, pointer_lo, lo)).empty());
  CHECK(problems(with(base, pointer_hi, hi)).empty());
  CHECK(problems(with(base, pointer_lo, std::nextafter(lo, -inf))).size() == 1);
  CHECK(reports(with(base, pointer_lo, std::nextafter(lo, -inf)), path_lo, {"is not allowed", allowed}));
  CHECK(problems(with(base, pointer_hi, std::nextafter(hi, inf))).size() == 1);
  CHECK(reports(with(base, pointer_hi, std::nextafter(hi, inf)), path_hi, {"is not allowed", allowed}));
}

void check_span(const json& base, const std::string& pointer, const std::string& path, double lo, double hi,
                const std::string& allowed) {
  check_span(base, pointer, path, pointer, path, lo, hi, allowed);
}

}  // namespace

TEST_CASE("every dimensional number has a physical span: its bounds pass, the next doubles beyond are refused") {
  using namespace fretwear::spans;
  const std::string lengths = "[1e-9, 100] m", positions = "[-100, 100] m";
  json j = good();
  check_span(j, "/profile/R", "profile.R", kMinLength, kMaxLength, "a radius in " + lengths);
  check_span(j, "/profile/offset_x", "profile.offset_x", -kMaxPosition, kMaxPosition, "a position in " + positions);
  check_span(j, "/materials/both/E", "materials.both.E", kMinModulus, kMaxModulus,
             "a Young's modulus in [1000, 1e13] Pa");
  check_span(j, "/load/P", "load.P", kMinLoad, kMaxLoad, "a normal load in [1e-6, 1e12] N/m");
  j["grid"] = {{"window", {-1e-3, 1e-3}}};
  check_span(j, "/grid/window/0", "grid.window[0]", "/grid/window/1", "grid.window[1]", -kMaxPosition, kMaxPosition,
             "a position in " + positions);
  j["grid"] = {{"window", {0.0, 5e-10}}};
  j["profile"] = {{"type", "flat"}, {"b", 1e-3}};
  CHECK(reports(j, "grid.window", {"narrower than 1e-9 m"}));

  j = good();
  j["profile"] = {{"type", "flat_rounded"}, {"a", 1e-3}, {"R", 1e-2}};
  check_span(j, "/profile/a", "profile.a", kMinLength, kMaxLength, "a flat half-length in " + lengths);
  j["profile"] = {{"type", "flat"}, {"b", 1e-3}};
  check_span(j, "/profile/b", "profile.b", kMinLength, kMaxLength, "a half-width in " + lengths);
  j["profile"] = {{"type", "wavy"}, {"amplitude", 1e-6}, {"wavelength", 1e-3}};
  j["grid"] = {{"window", {-5e-4, 5e-4}}};
  check_span(j, "/profile/amplitude", "profile.amplitude", kMinLength, kMaxLength, "an amplitude in " + lengths);
  // A lone waviness of 1 nm passes the span, but Profile places its lowest point, one of a million in a window of
  // 1 mm, outside the window; a cylinder under the waviness keeps the lowest point in place.
  j["profile"] = {{"type", "sum"},
                  {"terms", {{{"type", "cylinder"}, {"R", 1e-2}}, {{"type", "wavy"}, {"amplitude", 1e-9}, {"wavelength", 1e-3}}}}};
  j["grid"] = {{"window", {-5e-4, 5e-4}}};
  check_span(j, "/profile/terms/1/wavelength", "profile.terms[1].wavelength", kMinLength, kMaxLength,
             "a wavelength in " + lengths);
  j = good();
  j["profile"] = {{"type", "table"}, {"x", {-1e-3, 0.0, 1e-3}}, {"h", {1e-6, 0.0, 1e-6}}};
  check_span(j, "/profile/x/0", "profile.x[0]", "/profile/x/2", "profile.x[2]", -kMaxPosition, kMaxPosition,
             "a position in " + positions);
  check_span(j, "/profile/h/0", "profile.h[0]", -kMaxPosition, kMaxPosition, "a height in " + positions);

  json t = good();  // the tangential cycle
  t["friction"] = 0.5;
  t["load"]["Q"] = {{"ratio", 0.5}};
  t["effects"] = {{"tangential", json::object()}};
  check_span(t, "/load/Q/ratio", "load.Q.ratio", 0.0, kMaxLoadRatio, "a ratio Q/(fP) in [0, 100]");
  j = t;
  j["load"]["Q"] = {{"amplitude", 1e4}};
  check_span(j, "/load/Q/amplitude", "load.Q.amplitude", 0.0, kMaxLoad, "a tangential load in [0, 1e12] N/m");
  j = t;
  j["load"]["bulk_stress"] = {{"amplitude", 1e8}};
  check_span(j, "/load/bulk_stress/amplitude", "load.bulk_stress.amplitude", -kMaxStress, kMaxStress,
             "a stress in [-1e12, 1e12] Pa");
  check_span(t, "/grid/reference_depth", "grid.reference_depth", kMinLength, kMaxLength,
             "a depth > 0 m below the contact centre, in " + lengths);
  j = t;
  j["load"] = {{"P", 1e5}, {"control", "displacement"}, {"delta", 1e-6}};
  check_span(j, "/load/delta", "load.delta", kMinLength, std::nextafter(kMaxDelta, 0.0),
             "a displacement amplitude in [1e-9, 1) m");
  j = t;
  j["load"] = {{"P", 1e5}, {"history", {{0.0, 1e5, 0.0, 0.0}, {0.5, 1e5, 1e4, 1e8}, {1.0, 1e5, 0.0, 0.0}}}};
  check_span(j, "/load/history/0/0", "load.history[0]", "/load/history/2/0", "load.history[2]", -kMaxTime, kMaxTime,
             "t = ");
  check_span(j, "/load/history/1/1", "load.history[1]", kMinLoad, kMaxLoad,
             "P = ");
  CHECK(reports(with(j, "/load/history/1/1", 0.0), "load.history[1]", {"give a normal load in [1e-6, 1e12] N/m"}));
  check_span(j, "/load/history/1/2", "load.history[1]", -kMaxLoad, kMaxLoad, "Q = ");
  CHECK(reports(with(j, "/load/history/1/2", 2e12), "load.history[1]", {"a tangential load in [-1e12, 1e12] N/m"}));
  check_span(j, "/load/history/1/3", "load.history[1]", -kMaxStress, kMaxStress, "sigma_bulk = ");
  CHECK(reports(with(j, "/load/history/1/3", 2e12), "load.history[1]", {"a stress in [-1e12, 1e12] Pa"}));

  j = t;
  j["effects"]["wear"] = {{"k", 1e-15}, {"cycles", 1e6}};
  check_span(j, "/effects/wear/k", "effects.wear.k", kMinWearCoefficient,
             std::nextafter(kMaxWearCoefficient, 0.0), "a wear coefficient in [1e-30, 1) 1/Pa");
  j = t;
  j["effects"]["stress"] = {{"depth", 1e-3}};
  check_span(j, "/effects/stress/depth", "effects.stress.depth", kMinLength, kMaxLength,
             "0 (the contact half-width) or a depth in " + lengths);
  CHECK(problems(with(j, "/effects/stress/depth", 0.0)).empty());
  j = t;
  j["effects"]["crack"] = {{"lengths", {1e-5, 2e-5}}, {"at", 0.0}};
  check_span(j, "/effects/crack/lengths/0", "effects.crack.lengths[0]", kMinLength, kMaxLength,
             "a crack length in " + lengths);
  check_span(j, "/effects/crack/at", "effects.crack.at", -kMaxPosition, kMaxPosition,
             "a position x in " + positions);
}

TEST_CASE("absurd magnitudes that crashed or completed with nonsense are refused") {
  json j = good();
  j["grid"] = {{"window", {-1e200, 1e200}}};
  CHECK(reports(j, "grid.window[0]", {"-1e+200 is not allowed"}));
  CHECK(reports(j, "grid.window[1]", {"1e+200 is not allowed"}));
  j = good();
  j["profile"]["R"] = 1e-308;
  CHECK(reports(j, "profile.R", {"1e-308 is not allowed", "[1e-9, 100] m"}));
  j = good();
  j["materials"]["both"]["E"] = 1e-310;
  CHECK(reports(j, "materials.both.E", {"is not allowed", "[1000, 1e13] Pa"}));
}

namespace {

json life_scene() {
  json j = good();
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["effects"] = {{"tangential", json::object()},
                  {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52},
                                            {"critical_distance", 2e-5}}},
                            {"growth", {{"law", "paris"}, {"C", 5e-30}, {"m", 3.0}, {"dK_th", 2e6},
                                        {"a_final", 1e-3}, {"K_c", 6e7}, {"short_crack", "el_haddad"},
                                        {"fatigue_limit", 6e8}, {"mode", "I"}}},
                            {"cycles_max", 1e9}}}};
  return j;
}

}  // namespace

TEST_CASE("the life effect's keys: SCENES.md's example is valid, resolves to itself, and needs the load cycle") {
  const Scene s = parse_scene(life_scene());
  REQUIRE(s.life);
  CHECK(s.life->a_initial() == 2e-5);  // the critical distance, as SCENES.md says
  const json resolved = s.to_json();
  CHECK(resolved["effects"]["life"]["growth"]["a_initial"] == 2e-5);
  CHECK(parse_scene(resolved).to_json() == resolved);
  json alone = life_scene();
  alone["effects"].erase("tangential");
  alone.erase("friction");
  alone["load"].erase("Q");
  CHECK(reports(alone, "effects.life", {"needs the load cycle"}));
}

TEST_CASE("the life effect's keys: wrong signs and ranges are named with what is allowed, every one at once") {
  json j = life_scene();
  auto& life = j["effects"]["life"];
  life["initiation"]["b"] = 0.08;
  life["initiation"]["c"] = 0.5;
  life["initiation"]["sigma_f"] = -1;
  life["growth"]["C"] = -5e-30;
  life["growth"]["m"] = 0;
  life["growth"]["a_initial"] = 2e-3;
  life["growth"]["mode"] = "III";
  life["growth"]["short_crack"] = "kitagawa";
  life["cycles_max"] = 0;
  CHECK(reports(j, "effects.life.initiation.b", {"(-1, 0)"}));
  CHECK(reports(j, "effects.life.initiation.c", {"(-2, 0)"}));
  CHECK(reports(j, "effects.life.initiation.sigma_f", {"Pa"}));
  CHECK(reports(j, "effects.life.growth.C", {"Paris coefficient"}));
  CHECK(reports(j, "effects.life.growth.m", {"(0, 20]"}));
  CHECK(reports(j, "effects.life.growth.a_final", {"not longer than a_initial"}));
  CHECK(reports(j, "effects.life.growth.mode", {"\"I\"", "\"equivalent\""}));
  CHECK(reports(j, "effects.life.growth.short_crack", {"el_haddad"}));
  CHECK(reports(j, "effects.life.cycles_max", {"1e15"}));

  json none = life_scene();
  none["effects"]["life"] = json::object();
  CHECK(reports(none, "effects.life", {"neither \"initiation\" nor \"growth\""}));
  json no_start = life_scene();
  no_start["effects"]["life"].erase("initiation");
  CHECK(reports(no_start, "effects.life.growth.a_initial", {"missing"}));
  json no_limit = life_scene();
  no_limit["effects"]["life"]["growth"].erase("fatigue_limit");
  CHECK(reports(no_limit, "effects.life.growth.fatigue_limit", {"missing"}));
  json stray = life_scene();
  stray["effects"]["life"]["growth"]["short_crack"] = "none";
  CHECK(reports(stray, "effects.life.growth.fatigue_limit", {"without short_crack"}));
}

// load.blocks (engine/scene.cpp, parse_blocks): each block one load and its cycles, every problem at its path.
TEST_CASE("load blocks: parsed with wear, every problem named at its block") {
  json j = good();
  j["friction"] = 0.5;
  j["effects"] = {{"wear", {{"law", "archard"}, {"k", 1e-12}, {"cycles", 1000}}}};
  j["load"]["blocks"] = {{{"Q", {{"amplitude", 2e4}}}, {"cycles", 300}},
                         {{"history", {{0, 1e5, 1e4, 0}, {1, 1e5, -1e4, 0}, {2, 1e5, 1e4, 0}}}, {"cycles", 700}}};
  const Scene s = parse_scene(j);
  REQUIRE(s.blocks.size() == 2);
  CHECK(s.Q_amplitude == 2e4);  // the first block's load is the scene's own
  CHECK(s.blocks[1].history.size() == 3);
  CHECK(s.to_json()["load"]["blocks"].size() == 2);
  CHECK(!s.to_json()["load"].contains("Q"));
  CHECK_NOTHROW(parse_scene(s.to_json()));

  json bad = j;
  bad["load"]["blocks"][1]["cycles"] = 0.5;
  CHECK(reports(bad, "load.blocks[1].cycles", {"whole number"}));
  bad = j;
  bad["load"]["blocks"][0]["delta"] = 1e-6;
  CHECK(reports(bad, "load.blocks[0]", {"exactly one of"}));
  bad = j;
  bad["load"]["blocks"][1]["history"][2] = {2, 1e5, 2e4, 0};
  CHECK(reports(bad, "load.blocks[1].history[2]", {"cycle closes"}));
  bad = j;
  bad["load"]["blocks"][0]["Q"] = {{"amplitude", 1}, {"ratio", 0.5}};
  CHECK(reports(bad, "load.blocks[0].Q", {"exactly one"}));
  bad = j;
  bad["effects"]["stress"] = json::object();  // refused with the reason: one cycle's phases, a cycle per block
  CHECK(reports(bad, "load.blocks", {"effects.stress", "one steady cycle", "a cycle of their own each"}));
  bad = j;
  bad["load"]["blocks"][0]["cyles"] = 3;
  CHECK(reports(bad, "load.blocks[0].cyles", {"unknown key"}));
  bad = j;
  bad["load"]["blocks"] = json::array();
  CHECK(reports(bad, "load.blocks", {"non-empty list"}));
  bad = j;
  bad["load"]["Q"] = {{"ratio", 0.5}};
  CHECK(reports(bad, "load.Q", {"given with load.blocks"}));
  bad = j;
  bad["effects"]["wear"]["cycles"] = 999;
  CHECK(reports(bad, "effects.wear.cycles", {"blocks' total", "1000"}));
  bad = j;
  bad["effects"] = {{"tangential", json::object()}};
  CHECK(reports(bad, "load.blocks", {"without effects.wear"}));
}
