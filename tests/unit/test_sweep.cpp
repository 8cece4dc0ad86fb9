// run_sweep: the product of variations, run on threads, one folder per run, the table and the map. The command
// `fretwear sweep` is tried in tests/system/test_sweep_cli.cpp.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "engine/folder.hpp"
#include "engine/scene.hpp"
#include "engine/sweep.hpp"

namespace fs = std::filesystem;
using namespace fretwear;
using nlohmann::json;

namespace {
struct Scratch {
  fs::path path = fs::temp_directory_path() / ("fretwear-sweep-" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(path); }
  ~Scratch() { fs::remove_all(path); }
};

fs::path write_scene(const fs::path& dir) {
  const json scene = {{"name", "sw"},
                      {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
                      {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
                      {"friction", 0.5},
                      {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}}},
                      {"grid", {{"cells", 256}}},
                      {"effects", {{"tangential", json::object()}}},
                      {"output", {{"dir", (dir / "out").string()}, {"plots", false}}}};
  std::ofstream(dir / "sw.json") << scene.dump();
  return dir / "sw.json";
}

// A CSV file's records, read as RFC 4180 writes them: a field in double quotes may hold commas, line breaks and
// doubled quotes.
std::vector<std::vector<std::string>> read_csv(const fs::path& file) {
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record{""};
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c != '"')
        record.back() += c;
      else if (i + 1 < text.size() && text[i + 1] == '"')
        record.back() += '"', ++i;
      else
        quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.emplace_back();
    } else if (c == '\n') {
      records.push_back(record);
      record = {""};
    } else {
      record.back() += c;
    }
  }
  return records;
}

// The field of `column` in each record after the header.
std::vector<std::string> column(const std::vector<std::vector<std::string>>& records, const std::string& name) {
  std::vector<std::string> cells;
  const auto& header = records.at(0);
  const auto at = std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
  REQUIRE_MESSAGE(at < header.size(), name);
  for (std::size_t r = 1; r < records.size(); ++r) {
    REQUIRE(records[r].size() == header.size());
    cells.push_back(records[r][at]);
  }
  return cells;
}

json read_json(const fs::path& file) { return json::parse(std::ifstream(file)); }

// The runs on this thread, in order, as the thread dispatch runs them; the run `fail` is not run but reported as
// `outcome`, as a run that failed would be.
class FailOne final : public SweepDispatch {
 public:
  FailOne(std::size_t fail, SweepOutcome outcome) : fail_(fail), outcome_(std::move(outcome)) {}
  bool root() const override { return true; }
  std::string share(const std::string& text) override { return text; }
  void run_all(const std::vector<std::size_t>& todo, const std::function<SweepOutcome(std::size_t)>& run,
               const std::function<void(std::size_t, const SweepOutcome&)>& done) override {
    for (const std::size_t k : todo) done(k, k == fail_ ? outcome_ : run(k));
  }
  std::vector<std::vector<std::string>> check_all(
      std::size_t n, const std::function<std::vector<std::string>(std::size_t)>& check) override {
    std::vector<std::vector<std::string>> out;
    for (std::size_t k = 0; k < n; ++k) out.push_back(check(k));
    return out;
  }

 private:
  std::size_t fail_;
  SweepOutcome outcome_;
};
}  // namespace

TEST_CASE("a 2 x 2 sweep on two threads into output.dir/sweep: runs, folders, table, stick share sqrt(1 - Q/fP)") {
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const SweepResult r = run_sweep(scene, {parse_variation("load.Q.ratio=0.36,0.64"), parse_variation("load.P=1e5,4e5")},
                                  2, nullptr);
  REQUIRE(r.runs.size() == 4);
  for (const SweepRun& run : r.runs) {
    CAPTURE(run.name);
    REQUIRE(run.status == 0);
    CHECK(fs::exists(scratch.path / "out" / "sweep" / "runs" / run.name / "summary.json"));
    // Hertz: c/a = sqrt(1 − Q/fP) at any P; the edges are located to a fraction of a cell (1/170 of the contact).
    const double ratio = run.values[0].get<double>();
    const auto stick = run.summary["cycle"]["stick_zone"], extent = run.summary["contact"]["extent"];
    const double share = (stick[1].get<double>() - stick[0].get<double>()) /
                         (extent[1].get<double>() - extent[0].get<double>());
    CHECK(std::abs(share - std::sqrt(1.0 - ratio)) < 0.01);
  }
  std::ifstream csv(scratch.path / "out" / "sweep" / "sweep.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  CHECK(lines == 5);
  CHECK(fs::exists(scratch.path / "out" / "sweep" / "sweep.json"));
}

TEST_CASE("a sweep with an invalid variant names it and runs nothing") {
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  try {
    run_sweep(scene, {parse_variation("load.P=1e5,-1")}, 1, nullptr);
    FAIL("the sweep should be refused");
  } catch (const SceneError& e) {
    CHECK(std::string(e.what()).find("sw__load.P_-1.0: load.P") != std::string::npos);
  }
  CHECK_FALSE(fs::exists(scratch.path / "out"));
  CHECK_THROWS_AS(parse_variation("load.P"), InputError);
}

TEST_CASE("a varied value JSON cannot hold as a number is refused saying why, never taken for a word") {
  auto message = [](const std::string& text) {
    try {
      parse_variation(text);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  CHECK(message("load.P=1e5,1e400").find("1e400 overflows a double") != std::string::npos);
  CHECK(message("load.P=NaN").find("NaN is not a JSON number") != std::string::npos);
  CHECK(message("load.P=-Infinity").find("-Infinity is not a JSON number") != std::string::npos);
  CHECK(message("load.Q.ratio=.5").find(".5 is a number JSON does not write") != std::string::npos);
  CHECK(message("load.Q.ratio=.5").find("give it as 0.5") != std::string::npos);
  CHECK(message("load.Q.ratio=0.5,abc").empty());  // a word stays a word: the scene's check names the key
  // Opened as a JSON list, refused as one (it was split at its commas into the words "[1e5" and " NaN]").
  CHECK(message("load.P=[1e5, NaN]").find("the values open with [ but are not a JSON list (parse error") !=
        std::string::npos);
  CHECK(message("load.P=[1e5, 1e309]").find("the values open with [ but are not a JSON list (number overflow") !=
        std::string::npos);
  CHECK(message("load.P=[1e5][2e5]").find("not a JSON list") != std::string::npos);
}

TEST_CASE("values given as a JSON array may be lists: a sweep over grid.window runs each window") {
  const Variation windows = parse_variation("grid.window=[[-2e-4, 2e-4], [-3e-4, 3e-4]]");
  REQUIRE(windows.values.size() == 2);
  CHECK(windows.values[1] == json::parse("[-3e-4, 3e-4]"));
  CHECK(parse_variation("load.Q.ratio=[0.2, 0.5]").values == std::vector<json>{json(0.2), json(0.5)});
  CHECK_THROWS_AS(parse_variation("load.Q.ratio=[]"), InputError);
  // Split at its commas, a list is no window: "[-2e-4" is refused as before.
  CHECK(parse_variation("grid.window=[-2e-4,2e-4]").values.size() == 2);
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const SweepResult r = run_sweep(scene, {windows}, 1, nullptr);
  REQUIRE(r.runs.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CAPTURE(r.runs[k].name);
    REQUIRE(r.runs[k].status == 0);
    CHECK(r.runs[k].summary["grid"]["window"] == windows.values[k]);
  }
  // The table names the column with its unit, as every dimensional varied key.
  std::ifstream table(scratch.path / "out" / "sweep" / "sweep.csv");
  std::string header;
  std::getline(table, header);
  CHECK_MESSAGE(header.rfind("grid.window_m,", 0) == 0, header);
}

TEST_CASE("sweep.csv says each run's status in its summary.json's words, and why a failed run failed") {
  // summary.json says "completed"; a variant refused while solving writes no folder and no summary: its row says
  // "refused" and its message, which sweep.json holds too, CSV-quoted (commas, quotes and a line break read back).
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const std::string why = "grid.window: the worn contact reaches the window's end at cycle 5, \"x = 1 mm\"\nwiden it";
  FailOne dispatch(1, SweepOutcome{2, why, nullptr, -1});
  SweepOptions options;
  options.dispatch = &dispatch;
  const SweepResult r = run_sweep(scene, {parse_variation("load.Q.ratio=0.3,0.6,0.9")}, options);
  const fs::path dir = scratch.path / "out" / "sweep";
  const auto records = read_csv(dir / "sweep.csv");
  REQUIRE(records.size() == 4);
  const std::vector<std::string> status = column(records, "status"), message = column(records, "message");
  const std::vector<std::string> names = column(records, "name");
  CHECK(status == std::vector<std::string>{"completed", "refused", "completed"});
  CHECK(message == std::vector<std::string>{"", why, ""});
  for (const std::size_t k : {0, 2})
    CHECK(read_json(dir / "runs" / names[k] / "summary.json")["status"] == status[k]);
  CHECK_FALSE(fs::exists(dir / "runs" / names[1]));
  const json table = read_json(dir / "sweep.json");
  CHECK(table["runs"][0]["status"] == "completed");
  CHECK(table["runs"][1]["status"] == "refused");
  CHECK(table["runs"][1]["message"] == why);
  CHECK_FALSE(table["runs"][0].contains("message"));
  CHECK(r.runs[1].status == 2);
  CHECK(status_word(3) == "not_converged");
  CHECK(status_word(1) == "internal_error");
}

TEST_CASE("without plots a sweep still writes sweep_map.dat: only sweep.gp and the images need plots") {
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);  // output.plots false
  run_sweep(scene, {parse_variation("load.Q.ratio=0.36,0.64"), parse_variation("load.P=1e5,4e5")}, 1, nullptr);
  const fs::path dir = scratch.path / "out" / "sweep";
  std::ifstream dat(dir / "sweep_map.dat");
  int cells = 0;
  for (std::string line; std::getline(dat, line);)
    if (!line.empty()) ++cells;
  CHECK(cells == 4);
  for (const char* drawn : {"sweep.gp", "sweep_map.svg", "sweep_map.png", "sweep_regime.svg", "sweep_regime.png"})
    CHECK_MESSAGE(!fs::exists(dir / drawn), drawn);
}

TEST_CASE("a number names its run folder alike however it is written, and --resume finds the run by it") {
  // 1e5, 100000 and 100000.0 are one value, named 100000.0; −0 and 0 are one value, named 0.0.
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const SweepResult first = run_sweep(
      scene, {parse_variation("load.P=1e5,200000"), parse_variation("load.bulk_stress.amplitude=-0.0")}, 1, nullptr);
  std::vector<std::string> names;
  for (const SweepRun& run : first.runs) names.push_back(run.name);
  CHECK(names == std::vector<std::string>{"sw__load.P_100000.0__load.bulk_stress.amplitude_0.0",
                                          "sw__load.P_200000.0__load.bulk_stress.amplitude_0.0"});
  SweepOptions again;
  again.resume = true;
  const SweepResult second = run_sweep(
      scene, {parse_variation("load.P=100000,2e5"), parse_variation("load.bulk_stress.amplitude=0")}, again);
  REQUIRE(second.runs.size() == 2);
  for (const SweepRun& run : second.runs) {
    CAPTURE(run.name);
    CHECK(run.kept);
    CHECK(fs::exists(scratch.path / "out" / "sweep" / "runs" / run.name / "summary.json"));
  }
}

TEST_CASE("--resume runs again a run whose folder holds a summary that did not complete") {
  // A not-converged summary holds the normal contact's sections too (docs/OUTPUTS.md): only "completed" is kept.
  Scratch scratch;
  const fs::path scene = write_scene(scratch.path);
  const SweepResult first = run_sweep(scene, {parse_variation("load.Q.ratio=0.3,0.6")}, 1, nullptr);
  REQUIRE(first.runs.size() == 2);
  const fs::path failed = scratch.path / "out" / "sweep" / "runs" / first.runs[1].name / "summary.json";
  json summary = read_json(failed);
  summary["status"] = "not_converged";
  std::ofstream(failed) << summary.dump();
  // As fretwear would have written it: the run folder's marker holds the summary's checksum.
  const fs::path marker = failed.parent_path() / kOutputMarker;
  json listing = read_json(marker);
  listing["checksums"]["summary.json"] = fnv1a64(summary.dump());
  std::ofstream(marker) << listing.dump();
  SweepOptions again;
  again.resume = true;
  const SweepResult second = run_sweep(scene, {parse_variation("load.Q.ratio=0.3,0.6")}, again);
  REQUIRE(second.runs.size() == 2);
  CHECK(second.runs[0].kept);
  CHECK_FALSE(second.runs[1].kept);
  CHECK(read_json(failed)["status"] == "completed");
}
