// `fretwear sweep` on the command line: the runs, the table, the exit status. What a sweep computes is checked in
// process by tests/unit/test_sweep.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "system/program.hpp"
#include "system/sweep_support.hpp"

using namespace fretwear::system_test;

namespace {

// The sweep scene of tests/unit/test_sweep.cpp, its results under output.dir = <working folder>/out.
fs::path write_scene(const Scratch& s) {
  const json scene = {{"name", "sw"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects", {{"tangential", json::object()}}},
                      {"output", {{"dir", (s.work / "out").string()}, {"plots", false}}}};
  return s.write("sw.json", scene.dump());
}

}  // namespace

TEST_CASE("fretwear sweep on the command line: runs, table, exit 0, and a bad --vary exits 2") {
  Scratch s;
  const std::string scene = write_scene(s).string();
  const Outcome r = s.fretwear({"sweep", scene, "--vary", "load.Q.ratio=0.2,0.4", "--jobs", "2", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  CHECK(fs::exists(s.work / "out" / "sweep" / "sweep.csv"));
  const Outcome bad = s.fretwear({"sweep", scene, "--vary", "load.Q.ratio", "-q"});
  CHECK_MESSAGE(bad.exited(kInvalid), bad.describe());
}

TEST_CASE("a sweep of a scene with a life effect tabulates the lives and draws them against the varied key") {
  Scratch s;
  const json scene = {{"name", "life"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", 2.5e8}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects",
                       {{"tangential", json::object()},
                        {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52}}},
                                  {"growth", {{"C", 5e-30}, {"m", 3.0}, {"a_initial", 2e-5}, {"a_final", 1e-3}}}}}}},
                      {"output", {{"dir", (s.work / "out").string()}}}};
  s.write("life.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", "life.json", "--vary", "load.Q.ratio=0.5,0.7", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  std::string header, row;
  std::ifstream csv(s.work / "out" / "sweep" / "sweep.csv");
  std::getline(csv, header);
  std::getline(csv, row);
  CHECK(header.find("life.total_cycles") != std::string::npos);
  CHECK(header.find("life.fate") != std::string::npos);
  CHECK(row.find("failure") != std::string::npos);
  if (!on_path("gnuplot").empty())
    CHECK(fs::exists(s.work / "out" / "sweep" / "sweep_life.png"));

  // Without plots the lives' data is written all the same, a row per run; only the script and the images are not.
  json quiet = scene;
  quiet["output"] = {{"dir", (s.work / "unplotted").string()}, {"plots", false}};
  s.write("unplotted.json", quiet.dump());
  REQUIRE(s.fretwear({"sweep", "unplotted.json", "--vary", "load.Q.ratio=0.5,0.7", "-q"}).exited(kDone));
  const fs::path unplotted = s.work / "unplotted" / "sweep";
  const std::string lives = read_file(unplotted / "sweep_life.dat");
  CHECK(std::count(lives.begin(), lives.end(), '\n') == 2);
  CHECK(fs::exists(unplotted / "sweep_map.dat"));
  CHECK_FALSE(fs::exists(unplotted / "sweep.gp"));
  CHECK_FALSE(fs::exists(unplotted / "sweep_life.png"));
}

TEST_CASE("a 3 x 3 sweep draws 3 x 3 cells that tile the plane, a regime map with units, and names units in sweep.csv") {
  Scratch s;
  json scene = json::parse(fretwear::test::read_file(write_scene(s)));
  scene["output"]["plots"] = true;
  s.write("sw.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", "sw.json", "--vary", "load.Q.ratio=0.3,0.6,1.2", "--vary",
                                "load.P=1e5,2e5,1.6e6", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "out" / "sweep";
  std::string header;
  std::getline(std::ifstream(dir / "sweep.csv"), header);
  for (const char* column : {"load.Q.ratio,", "load.P_N_m,", "contact.p_max_Pa,", "cycle.stick_zone_m,",
                             "cycle.dissipated_energy_J_m,", "wear.worn_area_m2,", "timings.total_s"})
    CHECK_MESSAGE(header.find(column) != std::string::npos, column);

  // A row per run: x y value x_lo x_hi y_lo y_hi rgb regime. Cells meet halfway between neighbouring values (on a
  // log axis for P, whose values span 16×: geometrically), so they tile the map with no gap and no overlap.
  std::ifstream dat(dir / "sweep_map.dat");
  std::vector<std::array<double, 7>> cells;
  std::vector<std::string> regimes;
  for (std::string line; std::getline(dat, line);) {
    if (line.empty()) continue;
    std::istringstream row(line);
    std::array<double, 7> c{};
    int rgb = 0;
    std::string regime;
    for (double& v : c) row >> v;
    row >> rgb >> regime;
    REQUIRE(row);
    cells.push_back(c);
    regimes.push_back(regime);
  }
  REQUIRE(cells.size() == 9);
  for (std::size_t k = 0; k < 9; ++k) {
    CAPTURE(k);
    CHECK((cells[k][3] < cells[k][0] && cells[k][0] < cells[k][4]));
    CHECK((cells[k][5] < cells[k][1] && cells[k][1] < cells[k][6]));
    if (k % 3 != 2) CHECK(cells[k][4] == cells[k + 1][3]);
    if (k < 6) CHECK(cells[k][6] == cells[k + 3][5]);
  }
  CHECK(cells[0][6] == doctest::Approx(std::sqrt(1e5 * 2e5)));
  CHECK(regimes[0] == "partial_slip");
  CHECK(regimes[2] == "gross_slip");  // Q = 1.2 fP
  const std::string gp = fretwear::test::read_file(dir / "sweep.gp");
  CHECK(gp.find("set ylabel 'load.P (N/m)'") != std::string::npos);
  CHECK(gp.find("set logscale y") != std::string::npos);
  CHECK(gp.find("'#440154'") != std::string::npos);  // viridis
  if (!on_path("gnuplot").empty()) {
    CHECK(fs::exists(dir / "sweep_regime.png"));
    CHECK(fs::exists(dir / "sweep_map.png"));
  }
}

TEST_CASE("a sweep reads a measured profile's file beside its scene, from any working folder") {
  // examples/measured_profile: a table read from crowned_pad.csv, named relative to the scene. The runs of a sweep
  // are the scene's variants; each reads the file from the base scene's folder, not the working folder.
  Scratch s;
  const fs::path source = fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "measured_profile";
  const fs::path folder = s.work / "pads";
  fs::create_directories(folder);
  fs::copy_file(source / "crowned_pad.csv", folder / "crowned_pad.csv");
  json scene = json::parse(std::ifstream(source / "crowned_pad.json"));
  scene["grid"]["cells"] = 256;
  scene["output"] = {{"dir", (s.work / "out").string()}, {"plots", false}};
  std::ofstream(folder / "crowned_pad.json") << scene.dump();
  const Outcome r = s.fretwear({"sweep", (folder / "crowned_pad.json").string(), "--vary", "load.P=2e5,3e5", "-q"});
  CHECK_MESSAGE(r.exited(kDone), r.describe());
  std::ifstream table(s.work / "out" / "sweep" / "sweep.csv");
  std::string line;
  int rows = 0;
  while (std::getline(table, line)) ++rows;
  CHECK(rows == 3);  // the header and the two runs
}

TEST_CASE("a sweep of the normal contact alone maps its peak pressure, and gnuplot has nothing to complain of") {
  // Without a load cycle there is no stick zone to share the contact: the map shows p_max (a stick share of 0 for
  // every run left gnuplot an empty range, and a gnuplot.log in the folder).
  Scratch s;
  json scene = {{"name", "normal"},
                {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                {"load", {{"P", 1e5}}},
                {"grid", {{"cells", 256}}},
                {"output", {{"dir", (s.work / "out").string()}, {"plots", true}}}};
  const fs::path file = s.write("normal.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", file.string(), "--vary", "load.P=5e4,1e5,2e5", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "out" / "sweep";
  std::ifstream gp(dir / "sweep.gp");
  const std::string script((std::istreambuf_iterator<char>(gp)), std::istreambuf_iterator<char>());
  CHECK(script.find("peak pressure p_max (Pa)") != std::string::npos);
  CHECK(fs::exists(dir / "sweep_map.png"));
  CHECK_FALSE(fs::exists(dir / "gnuplot.log"));
}

TEST_CASE("a sweep over whole profiles labels its axis with their JSON, and gnuplot reads the script") {
  // The values' JSON holds double quotes, which in a double-quoted tic label ended the string early.
  Scratch s;
  json scene = {{"name", "profiles"},
                {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                {"load", {{"P", 1e5}}},
                {"grid", {{"cells", 256}}},
                {"output", {{"dir", (s.work / "out").string()}, {"plots", true}}}};
  const fs::path file = s.write("profiles.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", file.string(), "--vary",
                                "profile=[{\"type\": \"cylinder\", \"R\": 0.01}, {\"type\": \"flat_rounded\", "
                                "\"a\": 1e-4, \"R\": 0.01}]",
                                "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const fs::path dir = s.work / "out" / "sweep";
  std::ifstream gp(dir / "sweep.gp");
  const std::string script((std::istreambuf_iterator<char>(gp)), std::istreambuf_iterator<char>());
  CHECK_MESSAGE(script.find("'{\"R\":0.01,\"type\":\"cylinder\"}' 0") != std::string::npos, script);
  CHECK_MESSAGE(script.find("'{\"R\":0.01,\"a\":0.0001,\"type\":\"...' 1") != std::string::npos, script);
  CHECK(fs::exists(dir / "sweep_map.png"));
  std::ifstream log(dir / "gnuplot.log");
  const std::string said((std::istreambuf_iterator<char>(log)), std::istreambuf_iterator<char>());
  CHECK_MESSAGE(!fs::exists(dir / "gnuplot.log"), said);
}

namespace {

// The names of the run folders under <out>/sweep/runs.namespace {

// The names of the run folders under <out>/sweep/runs.
std::vector<std::string> run_folders(const fs::path& out) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(out / "sweep" / "runs")) names.push_back(e.path().filename().string());
  return names;
}

}  // namespace

TEST_CASE("a sweep checks its variants' physics on all its threads: every problem once, in the runs' order, exit 2") {
  // load.P past what half-plane elasticity can carry is refused once the variant's contact is solved (its mean
  // pressure over E*): four of the six variants. The checks are shared among the threads; what is said is what one
  // thread says, each run's problems in the runs' order (load.P varying fastest).
  Scratch s;
  const std::string scene = write_scene(s).string();
  std::string said[2];
  for (const int jobs : {1, 2}) {
    const Outcome r = s.fretwear({"sweep", scene, "--vary", "load.P=1e5,3e10,1e11", "--vary", "friction=0.4,0.5",
                                  "--jobs", std::to_string(jobs), "-q"});
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    said[jobs - 1] = r.err;
    CHECK_FALSE(fs::exists(s.work / "out"));
  }
  CHECK(said[0] == said[1]);
  std::vector<std::size_t> at;
  for (const char* run : {"sw__load.P_30000000000.0__friction_0.4: load.P: the mean contact pressure",
                          "sw__load.P_100000000000.0__friction_0.4: load.P: the mean contact pressure",
                          "sw__load.P_30000000000.0__friction_0.5: load.P: the mean contact pressure",
                          "sw__load.P_100000000000.0__friction_0.5: load.P: the mean contact pressure"}) {
    at.push_back(said[1].find(run));
    CHECK_MESSAGE(at.back() != std::string::npos, run, "\n", said[1]);
    CHECK_MESSAGE(said[1].find(run, at.back() + 1) == std::string::npos, run, "\n", said[1]);
  }
  CHECK(std::is_sorted(at.begin(), at.end()));
  CHECK(said[1].find("sw__load.P_100000.0") == std::string::npos);
}

TEST_CASE("a sweep refuses a value given twice for a key, exit 2, naming the key and the value, nothing written") {
  // Two runs of one variant would share a folder and write it at once.
  Scratch s;
  const std::string scene = write_scene(s).string();
  for (const std::string vary : {"load.P=1e5,1e5", "friction=0.5,0.5", "load.P=1e5,2e5,100000"}) {
    CAPTURE(vary);
    const Outcome r = s.fretwear({"sweep", scene, "--vary", vary, "-q"});
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    const std::string key = vary.substr(0, vary.find('='));
    CHECK_MESSAGE(r.err.find("--vary " + key + ": ") != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find("give each value once") != std::string::npos, r.err);
    CHECK_FALSE(fs::exists(s.work / "out"));
  }
}

TEST_CASE("values that differ only in characters a folder name cannot hold get a run folder each") {
  // a/p.csv and a_p.csv both read as the name part a_p.csv: the runs are named by their index instead.
  Scratch s;
  const fs::path source = fs::path(FRETWEAR_SOURCE_DIR) / "examples" / "measured_profile" / "crowned_pad.csv";
  fs::create_directories(s.work / "a");
  fs::copy_file(source, s.work / "a" / "p.csv");
  fs::copy_file(source, s.work / "a_p.csv");
  fs::copy_file(source, s.work / "crowned_pad.csv");  // the base scene's, valid on its own
  json scene = json::parse(std::ifstream(source.parent_path() / "crowned_pad.json"));
  scene["grid"]["cells"] = 256;
  scene["output"] = {{"dir", (s.work / "out").string()}, {"plots", false}};
  s.write("pad.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", "pad.json", "--vary", "profile.file=a/p.csv,a_p.csv", "--jobs", "2", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const auto rows = csv_rows(s.work / "out" / "sweep" / "sweep.csv", "timings.total_s");
  REQUIRE(rows.size() == 3);
  CHECK(rows[1][2] != rows[2][2]);  // the name column
  const std::vector<std::string> folders = run_folders(s.work / "out");
  REQUIRE(folders.size() == 2);
  for (const auto& row : rows)
    if (row[0] != "profile.file") {
      const json resolved = json::parse(read_file(s.work / "out" / "sweep" / "runs" / row[2] / "scene.resolved.json"));
      const std::string file = resolved["profile"]["file"].get<std::string>();  // made absolute
      CHECK_MESSAGE(file.ends_with("/" + row[0]), file);
    }
}

TEST_CASE("a key into a list varies that entry: profile.terms.1.amplitude, and an index past the end is refused") {
  // A sum profile's terms are a list: the index names an entry (it once replaced the whole list by an object, and
  // every run was refused as "profile.terms: ... is an object").
  Scratch s;
  json scene = {{"name", "sum"},
                {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                {"profile",
                 {{"type", "sum"},
                  {"terms",
                   {{{"type", "cylinder"}, {"R", 0.01}},
                    {{"type", "wavy"}, {"amplitude", 1e-7}, {"wavelength", 5e-5}}}}}},
                {"load", {{"P", 1e5}}},
                {"grid", {{"cells", 256}}},
                {"output", {{"dir", (s.work / "out").string()}, {"plots", false}}}};
  const fs::path file = s.write("sum.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", file.string(), "--vary", "profile.terms.1.amplitude=1e-7,2e-7", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const json resolved = json::parse(
      read_file(s.work / "out" / "sweep" / "runs" / "sum__profile.terms.1.amplitude_2e-07" / "scene.resolved.json"));
  CHECK(resolved["profile"]["terms"].size() == 2);
  CHECK(resolved["profile"]["terms"][1]["amplitude"] == 2e-7);
  CHECK(resolved["profile"]["terms"][0]["R"] == 0.01);
  const std::string csv = read_file(s.work / "out" / "sweep" / "sweep.csv");
  CHECK(csv.rfind("profile.terms.1.amplitude_m,", 0) == 0);
  fs::remove_all(s.work / "out");
  for (const auto& [vary, said] :
       {std::pair{"profile.terms.2.R=0.01,0.02", "--vary profile.terms.2.R: profile.terms holds 2 entries (0 to 1), "
                                                 "so 2 is past its end"},
        std::pair{"profile.terms.x.R=0.01,0.02", "--vary profile.terms.x.R: profile.terms is a list, and \"x\" is "
                                                 "no index into it"}}) {
    CAPTURE(vary);
    const Outcome bad = s.fretwear({"sweep", file.string(), "--vary", vary, "-q"});
    CHECK_MESSAGE(bad.exited(kInvalid), bad.describe());
    CHECK_MESSAGE(bad.err.find(said) != std::string::npos, bad.err);
    const auto once = bad.err.find(said);
    CHECK(bad.err.find(said, once + 1) == std::string::npos);  // said once, not for every run
    CHECK_FALSE(fs::exists(s.work / "out"));
  }
}

TEST_CASE("a sweep of more runs than a sweep may hold is refused at once, exit 2, naming the product") {
  // 1000 x 1000 x 1000 runs would not fit in memory as scenes; 1000 x 101 is 101000, just past the 100000 allowed.
  Scratch s;
  const std::string scene = write_scene(s).string();
  const auto values = [](const char* key, int n, double from) {
    std::string v = std::string(key) + "=";
    for (int k = 0; k < n; ++k) v += fmt::format("{}{}", k ? "," : "", from * (1.0 + 1e-3 * k));
    return v;
  };
  const Outcome huge = s.fretwear({"sweep", scene, "--vary", values("load.P", 1000, 1e5), "--vary",
                                   values("friction", 1000, 0.3), "--vary", values("materials.both.E", 1000, 2e11),
                                   "-q"});
  CHECK_MESSAGE(huge.exited(kInvalid), huge.describe());
  CHECK_MESSAGE(huge.err.find("the sweep would be 1e+09 runs (1000 load.P x 1000 friction x 1000 materials.both.E), "
                              "more than the 100000") != std::string::npos,
                huge.err);
  const Outcome past = s.fretwear({"sweep", scene, "--vary", values("load.P", 1000, 1e5), "--vary",
                                   values("friction", 101, 0.3), "-q"});
  CHECK_MESSAGE(past.exited(kInvalid), past.describe());
  CHECK_MESSAGE(past.err.find("1.01e+05 runs") != std::string::npos, past.err);
  CHECK_FALSE(fs::exists(s.work / "out"));
}

TEST_CASE("a sweep refuses a key varied twice, and keys inside one another, exit 2, nothing written") {
  Scratch s;
  const std::string scene = write_scene(s).string();
  const Outcome twice = s.fretwear({"sweep", scene, "--vary", "load.P=1e5", "--vary", "load.P=2e5", "-q"});
  CHECK_MESSAGE(twice.exited(kInvalid), twice.describe());
  CHECK_MESSAGE(twice.err.find("--vary load.P is given twice") != std::string::npos, twice.err);
  const Outcome inside =
      s.fretwear({"sweep", scene, "--vary", "load.Q={\"ratio\":0.3}", "--vary", "load.Q.ratio=0.2,0.4", "-q"});
  CHECK_MESSAGE(inside.exited(kInvalid), inside.describe());
  CHECK_MESSAGE(inside.err.find("--vary load.Q.ratio") != std::string::npos, inside.err);
  CHECK_FALSE(fs::exists(s.work / "out"));
}

TEST_CASE("--vary name and --vary output are refused (the sweep names and places its runs), all problems at once") {
  Scratch s;
  const std::string scene = write_scene(s).string();
  const Outcome r = s.fretwear({"sweep", scene, "--vary", "name=a,b", "--vary", "output.dir=x,y", "--vary",
                                "output.plots=true,false", "--vary", "load.P=1e5,-1", "-q"});
  CHECK_MESSAGE(r.exited(kInvalid), r.describe());
  for (const std::string said : {"--vary name: the sweep names", "--vary output.dir: the sweep places",
                           "--vary output.plots: the sweep places", "load.P"})
    CHECK_MESSAGE(r.err.find(said) != std::string::npos, said << "\n" << r.err);
  CHECK_FALSE(fs::exists(s.work / "out"));
}

TEST_CASE("a scene named with 128 characters sweeps, its run names cut to fit, and a longer name is refused, saying so") {
  Scratch s;
  json scene = json::parse(read_file(write_scene(s)));
  scene["name"] = std::string(120, 'n') + "_long.xy";
  REQUIRE(scene["name"].get<std::string>().size() == 128);
  s.write("long.json", scene.dump());
  const Outcome r = s.fretwear({"sweep", "long.json", "--vary", "load.Q.ratio=0.2,0.4", "--vary", "load.P=1e5,2e5",
                                "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const std::vector<std::string> folders = run_folders(s.work / "out");
  CHECK(folders.size() == 4);
  for (const auto& f : folders) CHECK_MESSAGE(f.size() <= 128, f);
  CHECK(csv_rows(s.work / "out" / "sweep" / "sweep.csv", "timings.total_s").size() == 5);

  scene["name"] = std::string(129, 'n');
  s.write("longer.json", scene.dump());
  const Outcome longer = s.fretwear({"validate", "longer.json"});
  CHECK_MESSAGE(longer.exited(kInvalid), longer.describe());
  CHECK_MESSAGE(longer.all().find("129 characters") != std::string::npos, longer.all());
  CHECK_MESSAGE(longer.all().find("at most 128") != std::string::npos, longer.all());
}

TEST_CASE("each run's scene.resolved.json names the run's own folder as output.dir, not the sweep's staging folder") {
  Scratch s;
  const std::string scene = write_scene(s).string();
  const Outcome r = s.fretwear({"sweep", scene, "--vary", "load.Q.ratio=0.2,0.4", "-q"});
  REQUIRE_MESSAGE(r.exited(kDone), r.describe());
  const std::vector<std::string> folders = run_folders(s.work / "out");
  REQUIRE(folders.size() == 2);
  for (const auto& name : folders) {
    const fs::path folder = s.work / "out" / "sweep" / "runs" / name;
    const json resolved = json::parse(read_file(folder / "scene.resolved.json"));
    CHECK(resolved["output"]["dir"] == folder.generic_string());
  }
}

TEST_CASE("a run that does not converge: sweep.csv's status and message are those of fretwear run's summary.json") {
  // The test hook FRETWEAR_NORMAL_MAX_ITERATIONS=6 stops the normal solve on 4096 cells short (it converges from a
  // cap of 10), not on 64 (from 4). The failed run writes no folder; its row says what `fretwear run` of its variant
  // writes.
  Scratch s;
  const Env cap = {{"FRETWEAR_NORMAL_MAX_ITERATIONS", "6"}};
  const std::string scene = write_scene(s).string();
  const Outcome sweep = s.fretwear({"sweep", scene, "--vary", "grid.cells=64,4096", "-q"}, cap);
  CHECK_MESSAGE(sweep.exited(kNotConverged), sweep.describe());
  const auto rows = csv_rows(s.work / "out" / "sweep" / "sweep.csv", "timings.total_s");
  REQUIRE(rows.size() == 3);
  REQUIRE(rows[0][1] == "status");
  REQUIRE(rows[0].back() == "message");
  const json completed = json::parse(read_file(s.work / "out" / "sweep" / "runs" / rows[1][2] / "summary.json"));
  CHECK(rows[1][1] == completed["status"]);
  CHECK(rows[1].back().empty());
  CHECK_FALSE(fs::exists(s.work / "out" / "sweep" / "runs" / rows[2][2]));

  json variant = json::parse(read_file(scene));
  variant["grid"]["cells"] = 4096;
  variant["output"]["dir"] = (s.work / "alone").string();
  s.write("alone.json", variant.dump());
  const Outcome alone = s.fretwear({"run", "alone.json", "-q"}, cap);
  REQUIRE_MESSAGE(alone.exited(kNotConverged), alone.describe());
  const json summary = json::parse(read_file(s.work / "alone" / "summary.json"));
  CHECK(rows[2][1] == summary["status"]);
  CHECK(rows[2].back() == summary["message"]);
}

TEST_CASE("a sweep says which runs warned: stderr, sweep.csv's warnings column and sweep.json, as each run's summary") {
  // 64 cells: at Q/fP = 0.2 the slip zones span a few cells each, at 0.9 the stick zone; at 0.7 both resolve.
  Scratch s;
  const std::string scene = write_scene(s).string();
  json j = json::parse(read_file(scene));
  j["grid"]["cells"] = 64;
  s.write("w.json", j.dump());
  const Outcome sweep = s.fretwear({"sweep", "w.json", "--vary", "load.Q.ratio=0.2,0.7,0.9"});
  REQUIRE_MESSAGE(sweep.exited(kDone), sweep.describe());
  const fs::path dir = s.work / "out" / "sweep";
  const auto rows = csv_rows(dir / "sweep.csv", "timings.total_s");
  REQUIRE(rows.size() == 4);
  REQUIRE(rows[0][rows[0].size() - 2] == "warnings");
  const json table = json::parse(read_file(dir / "sweep.json"))["runs"];
  int warned = 0;
  for (std::size_t k = 1; k < rows.size(); ++k) {
    const std::string name = rows[k][2];
    CAPTURE(name);
    const json summary = json::parse(read_file(dir / "runs" / name / "summary.json"));
    std::vector<std::string> codes;
    for (const json& w : summary["warnings"]) codes.push_back(w["code"].get<std::string>());
    std::string joined;
    for (const std::string& c : codes) joined += (joined.empty() ? "" : " ") + c;
    CHECK(rows[k][rows[k].size() - 2] == joined);
    CHECK(table[k - 1]["warnings"] == json(codes));
    if (!codes.empty()) {
      ++warned;
      CHECK(sweep.err.find(name + ": done, warned: " + codes.front()) != std::string::npos);
    }
  }
  CHECK(warned == 2);
}
