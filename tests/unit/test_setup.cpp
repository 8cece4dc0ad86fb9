// The setup (engine/setup.hpp): the plan of the load cycle and the effects to run, decided from the scene and the
// bodies before any solve, and the cycle stage running by that plan.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/preflight.hpp"
#include "engine/simulation.hpp"

using namespace fretwear;
using nlohmann::json;

namespace {

json cycle_scene() {
  return {{"name", "setup"},
          {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
          {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
          {"friction", 0.5},
          {"load", {{"P", 1e5}, {"Q", {{"ratio", 0.5}}}, {"bulk_stress", {{"amplitude", 1e8}}}}},
          {"grid", {{"cells", 256}}},
          {"effects", {{"tangential", json::object()}}}};
}

CyclePlan plan_of(const json& j) {
  const Scene s = parse_scene(j);
  return plan_cycle(s, ElasticPair(s.pad, s.specimen, s.plane));
}

}  // namespace

TEST_CASE("the plan holds the cyclic load with the bulk strain of the pair") {
  const Scene s = parse_scene(cycle_scene());
  const ElasticPair pair(s.pad, s.specimen, s.plane);
  const CyclePlan plan = plan_cycle(s, pair);
  CHECK(plan.load.P == 1e5);
  CHECK(plan.load.Q_max == 0.5 * 0.5 * 1e5);
  CHECK(plan.load.f == 0.5);
  CHECK(plan.load.bulk_strain == pair.bulk_strain(1e8));
  CHECK(plan.load.bulk_strain > 0.0);
  CHECK(plan.beta == 0.0);
}

TEST_CASE("under auto, force control on similar bodies tries the analogy first") {
  const CyclePlan plan = plan_of(cycle_scene());
  CHECK(plan.analogy_first());
  CHECK(plan.asked == TangentialRoute::automatic);
}

TEST_CASE("under auto, displacement control, a history and dissimilar bodies go to the incremental route, saying why") {
  json d = cycle_scene();
  d["load"] = {{"P", 1e5}, {"control", "displacement"}, {"delta", 1e-6}};
  CHECK(plan_of(d).incremental_because == "incremental (auto: displacement control)");

  json h = cycle_scene();
  h["load"] = {{"P", 1e5}, {"history", {{0, 1e5, 2e4, 0}, {1, 1e5, -2e4, 0}, {2, 1e5, 2e4, 0}}}};
  CHECK(plan_of(h).incremental_because == "incremental (auto: load history)");

  json b = cycle_scene();
  b["materials"] = {{"pad", {{"E", 2e11}, {"nu", 0.3}}}, {"specimen", {{"E", 7e10}, {"nu", 0.33}}}};
  const CyclePlan dissimilar = plan_of(b);
  CHECK(dissimilar.incremental_because == "incremental (auto: dissimilar bodies)");
  CHECK(dissimilar.dissimilar());

  json asked = cycle_scene();
  asked["effects"]["tangential"]["route"] = "incremental";
  CHECK(plan_of(asked).incremental_because == "incremental");
}

TEST_CASE("the analogy asked for under displacement control is refused by the plan") {
  json d = cycle_scene();
  d["load"] = {{"P", 1e5}, {"control", "displacement"}, {"delta", 1e-6}};
  Scene s = parse_scene(d);
  s.tangential->route = TangentialRoute::analogy;  // the scene's checks refuse this too; the plan must on its own
  CHECK_THROWS_AS(plan_cycle(s, ElasticPair(s.pad, s.specimen, s.plane)), UnsupportedError);
}

TEST_CASE("the cycle stage runs the plan it is given, not the scene's route") {
  const Scene s = parse_scene(cycle_scene());
  const Setup setup = make_setup(s);
  const NormalResult normal = solve_normal(s, setup.model);
  CyclePlan incremental = *setup.cycle;
  incremental.incremental_because = "incremental";
  const CycleStage a = solve_cycle(s, setup.model, *setup.cycle, normal);
  const CycleStage b = solve_cycle(s, setup.model, incremental, normal);
  CHECK(a.ran == TangentialRoute::analogy);
  CHECK(b.ran == TangentialRoute::incremental);
  CHECK(b.route == "incremental");
  CHECK(b.plan.incremental_because == "incremental");
}

TEST_CASE("the effects: the fatigue measures run with stress under a cycle only") {
  json j = cycle_scene();
  j["effects"]["stress"] = json::object();
  const Setup with_cycle = make_setup(parse_scene(j));
  CHECK(with_cycle.effects.cycle);
  CHECK(with_cycle.effects.stress);
  CHECK(with_cycle.effects.fatigue);
  CHECK_FALSE(with_cycle.effects.wear);
  CHECK_FALSE(with_cycle.effects.crack);

  json n = {{"name", "setup"},
            {"materials", {{"both", {{"E", 2e11}, {"nu", 0.3}}}}},
            {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
            {"load", {{"P", 1e5}}},
            {"grid", {{"cells", 256}}},
            {"effects", {{"stress", json::object()}}}};
  const Setup normal_only = make_setup(parse_scene(n));
  CHECK(normal_only.effects.stress);
  CHECK_FALSE(normal_only.effects.fatigue);
  CHECK_FALSE(normal_only.cycle.has_value());
}

TEST_CASE("a run takes the normal contact and the first cycle the checks solved, as if it had solved them") {
  // The checks before solving solve both for a wear scene (the wear run's cost comes from the first cycle);
  // Simulation::run given them solves neither again, and its results are those of a run that solves them.
  json j = cycle_scene();
  j["effects"]["wear"] = {{"law", "archard"}, {"k", 1e-12}, {"cycles", 1e5}, {"record", 2}};
  const Scene s = parse_scene(j);
  Preflight checked;
  REQUIRE(physics_problems(s, &checked).empty());
  REQUIRE(checked.solved.normal);
  REQUIRE(checked.solved.cycle);
  const RunResult given = Simulation(s).run(nullptr, &checked.solved);
  const RunResult own = Simulation(s).run();
  CHECK(given.normal.state.p == own.normal.state.p);
  CHECK(given.cycle->result.q_top == own.cycle->result.q_top);
  CHECK(given.cycle->result.dissipated_energy == own.cycle->result.dissipated_energy);
  REQUIRE(given.wear);
  CHECK(given.wear->records.back().w == own.wear->records.back().w);
  CHECK(make_summary(s, given)["wear"] == make_summary(s, own)["wear"]);
  // Their times are the stages'.
  CHECK(given.timings.normal >= checked.solved.normal_seconds);
  CHECK(*given.timings.tangential == checked.solved.cycle_seconds);
  CHECK(given.timings.total >= checked.solved.normal_seconds + checked.solved.cycle_seconds);

  // Taken, not solved again: a stage given with a mark on it carries the mark into the results.
  SolvedStages marked = checked.solved;
  CycleStage cycle = *checked.solved.cycle;
  cycle.route += " (given)";
  marked.cycle = std::make_shared<const CycleStage>(cycle);
  NormalResult normal = *checked.solved.normal;
  normal.summary.iterations += 1000;
  marked.normal = std::make_shared<const NormalResult>(normal);
  const RunResult taken = Simulation(s).run(nullptr, &marked);
  CHECK(taken.cycle->route == cycle.route);
  CHECK(taken.normal.summary.iterations == normal.summary.iterations);
}
