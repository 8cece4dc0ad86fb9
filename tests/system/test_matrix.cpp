// Every effect with every load and every body pair (docs/SCENES.md, "What runs with what"): each combination of
// body pair (similar, dissimilar) × load (force, displacement, history) × effect (cycle, wear, stress, crack, life)
// either runs (exit 0) or is refused with exit 2 by both `fretwear validate` and `fretwear run` with a message
// naming the reason, and nothing written. The table below is the contract: a combination that becomes supported is
// a one-line change of its row.
#include <fstream>
#include <map>
#include <string>
#include <tuple>

#include <doctest/doctest.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// The small base of the suite (256 cells) with a pair, a load and an effect.
json matrix_scene(const std::string& pair, const std::string& load, const std::string& effect) {
  json j = base_scene();
  j["name"] = pair + "_" + load + "_" + effect;
  j["friction"] = 0.5;
  if (pair == "dissimilar")  // steel on titanium, β = −0.0516
    j["materials"] = {{"pad", {{"E", 2e11}, {"nu", 0.3}}}, {"specimen", {{"E", 1.1e11}, {"nu", 0.34}}}};
  if (load == "force") j["load"]["Q"] = {{"ratio", 0.5}};
  if (load == "displacement") j["load"]["control"] = "displacement", j["load"]["delta"] = 0.5e-6;
  if (load == "history")  // P and σ out of phase with Q, partial slip throughout
    j["load"]["history"] = {{0, 1e5, 2.5e4, 0}, {1, 7e4, 0, -1e8}, {2, 1e5, -2.5e4, 0}, {3, 1.3e5, 0, 1e8},
                            {4, 1e5, 2.5e4, 0}};
  json effects = {{"tangential", {{"increments", 20}}}};
  if (effect == "wear") effects["wear"] = {{"k", 1e-15}, {"cycles", 1e3}, {"record", 2}};
  if (effect == "stress") effects["stress"] = {{"nx", 21}, {"ny", 11}};
  if (effect == "crack") effects["crack"] = {{"at", "trailing_edge"}, {"lengths", {1e-5, 2e-5}}};
  if (effect == "life")
    effects["life"] = {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52}, {"critical_distance", 2e-5}}},
                       {"growth", {{"C", 5e-30}, {"m", 3.0}, {"dK_th", 2e6}, {"a_final", 1e-4}}}};
  j["effects"] = effects;
  return j;
}

// What a combination does: "" runs; otherwise refused, with words the message must hold ('|' for alternatives).
using Key = std::tuple<std::string, std::string, std::string>;
const std::map<Key, std::string>& refusals() {
  static const std::map<Key, std::string> table = {
      // Every combination runs; a refusal, when one is needed, is a line here: {{pair, load, effect}, "words"}.
  };
  return table;
}

}  // namespace

TEST_CASE("matrix: every body pair, load and effect runs, or both validate and run refuse it naming why") {
  int runs = 0, refused = 0;
  for (const char* pair : {"similar", "dissimilar"})
    for (const char* load : {"force", "displacement", "history"})
      for (const char* effect : {"cycle", "wear", "stress", "crack", "life"}) {
        const auto it = refusals().find({pair, load, effect});
        const bool refuse = it != refusals().end();
        SceneCase c{std::string(pair) + " × " + load + " × " + effect, matrix_scene(pair, load, effect).dump(),
                    refuse ? Exits{kInvalid} : Exits{kDone}, refuse ? it->second : ""};
        check_scene(c);
        // check_scene holds validate to run's verdict (validate 2 ⇒ run 2, validate 0 ⇒ run 0); a refusal's reason
        // must come from validate itself too.
        if (refuse) {
          Scratch s;
          s.write("s.json", c.text);
          const Outcome v = s.fretwear({"validate", "s.json", "-q"});
          INFO("case: " << c.label);
          CHECK_MESSAGE(v.exited(kInvalid), "validate: " << v.describe());
          CHECK_MESSAGE(names(v.err, c.fragment), "validate should name \"" << c.fragment << "\": " << v.describe());
        }
        (refuse ? refused : runs)++;
      }
  CHECK(runs == 30);
  CHECK(refused == 0);
}

// Sliding under force control leaves no traction (a history) or no coupled pressure (β ≠ 0) at the phases that
// stress, crack and life take: refused before solving, naming the key and the limit.
TEST_CASE("matrix: stress, crack, life refused where force control slides with a history or dissimilar bodies") {
  json history = matrix_scene("similar", "history", "crack");
  history["load"]["history"][2] = {2, 1e5, -6e4, 0};  // |Q| > f P = 5e4 N/m at t = 2
  check_scene({"history sliding × crack", history.dump(), Exits{kInvalid}, "load.history: reaches |Q|"});
  json force = matrix_scene("dissimilar", "force", "stress");
  force["load"]["Q"] = {{"ratio", 1.1}};
  check_scene({"dissimilar sliding × stress", force.dump(), Exits{kInvalid}, "no coupled pressure"});
}

// The cycle alone past the stick limit, for each pair and load: force control and a history that reach |Q| ≥ f P
// are reported as gross slip without fields, displacement control slides by the rest. It crashed for dissimilar
// bodies under force control and a history (no coupled pressure at the top to summarise), and stopped with exit 3
// under displacement control on steel and aluminium (the bounds of the coupled pressure a few ulps short of f P).
TEST_CASE("matrix: the cycle past the stick limit runs for every pair and load, in gross slip") {
  for (const char* pair : {"similar", "dissimilar"})
    for (const char* load : {"force", "displacement", "history"}) {
      json j = matrix_scene(pair, load, "cycle");
      if (std::string(pair) == "dissimilar")  // steel on aluminium, β = −0.11
        j["materials"]["specimen"] = {{"E", 71e9}, {"nu", 0.33}};
      j["grid"]["cells"] = 128;
      if (std::string(load) == "force") j["load"]["Q"] = {{"ratio", 1.3}};
      if (std::string(load) == "displacement") j["load"]["delta"] = 3e-6;
      if (std::string(load) == "history") j["load"]["history"][2] = {2, 1e5, -6e4, 0};  // |Q| > f P = 5e4 N/m
      const std::string label = std::string(pair) + " × " + load + " past the stick limit";
      Scratch s;
      s.write("s.json", j.dump());
      const Outcome r = s.fretwear({"run", "s.json", "-q"});
      INFO("case: " << label);
      REQUIRE_MESSAGE(r.exited(kDone), r.describe());
      const fs::path folder = s.work / "output" / j["name"].get<std::string>();
      const json summary = json::parse(std::ifstream(folder / "summary.json"));
      CHECK(summary["cycle"]["regime"] == "gross_slip");
    }
}
