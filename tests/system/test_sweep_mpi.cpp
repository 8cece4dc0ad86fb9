// `mpirun -n 2 fretwear sweep ...` (ARCHITECTURE.md, "Beyond one machine"): the runs spread over two ranks, both of
// which run some, and the same sweep.csv as one process writes, timings aside; killed under mpirun, the sweep is
// finished by --resume under mpirun. Built only when fretwear is built with MPI (CI installs it).
#ifdef FRETWEAR_MPIEXEC
#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <unistd.h>

#include "system/program.hpp"
#include "system/sweep_support.hpp"

using namespace fretwear::system_test;

namespace {

// A run that takes longer than this is hung (an MPI job waiting for a rank that is gone).
constexpr int kMpiTimeLimit = 120;  // s

struct MpiOutcome {
  int status = -1;  // mpirun's exit status; 124: killed at the time limit
  std::string err;
};

// `mpirun -n <ranks> fretwear <args>` in `dir` (with the flags CI needs: more ranks than cores, and root), under
// `timeout`, its stderr kept; `env` ("NAME=value") passed to every rank. Each word reaches mpirun as it is.
MpiOutcome mpirun(const fs::path& dir, int ranks, const std::vector<std::string>& args, const std::string& env = {}) {
  fretwear::test::Command command{
      {"timeout", std::to_string(kMpiTimeLimit), FRETWEAR_MPIEXEC, "-n", std::to_string(ranks), "--oversubscribe"}};
  if (::geteuid() == 0) command.words.push_back("--allow-run-as-root");
  Env vars;
  if (!env.empty()) {
    const std::string name = env.substr(0, env.find('='));
    vars.emplace_back(name, env.substr(env.find('=') + 1));
    command.words.insert(command.words.end(), {"-x", name});
  }
  command.words.push_back(FRETWEAR_EXE);
  command.words.insert(command.words.end(), args.begin(), args.end());
  // The runner's own limit only backs up timeout's, which lets mpirun end its ranks.
  const Outcome o = fretwear::test::run_program(command, dir, vars, kMpiTimeLimit + 60);
  MpiOutcome m;
  m.status = o.signal == 0 && !o.timed_out ? o.status : -1;
  m.err = o.err;
  return m;
}

std::vector<std::string> args(const std::string& scene, std::vector<std::string> extra = {}) {
  std::vector<std::string> a{"sweep", scene};
  a.insert(a.end(), kSweepVary.begin(), kSweepVary.end());
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

}  // namespace

TEST_CASE("mpirun -n 2 fretwear sweep: both ranks run runs, and sweep.csv equals the one-process sweep's") {
  Scratch s;
  s.write("one.json", sweep_scene(s.work / "one", 2048).dump());
  s.write("mpi.json", sweep_scene(s.work / "mpi", 2048).dump());
  const Outcome one = s.fretwear(args("one.json", {"--jobs", "1", "-q"}));
  REQUIRE_MESSAGE(one.exited(kDone), one.describe());
  const MpiOutcome mpi = mpirun(s.work, 2, args("mpi.json"));
  REQUIRE_MESSAGE(mpi.status == kDone, mpi.err);
  // Rank 0 runs runs on a thread of its own beside handing them out; rank 1 asks for its first at once.
  CHECK_MESSAGE(mpi.err.find("(rank 0)") != std::string::npos, mpi.err);
  CHECK_MESSAGE(mpi.err.find("(rank 1)") != std::string::npos, mpi.err);
  const auto rows = csv_rows(s.work / "mpi" / "sweep" / "sweep.csv", "timings.total_s");
  CHECK(rows.size() == 13);
  CHECK(rows == csv_rows(s.work / "one" / "sweep" / "sweep.csv", "timings.total_s"));
  for (const auto& row : rows)
    if (row.size() > 3 && row[2] == "completed")
      CHECK(fs::exists(s.work / "mpi" / "sweep" / "runs" / row[3] / "summary.json"));
}

TEST_CASE("a sweep killed under mpirun is finished by --resume under mpirun, its table as if never stopped") {
  Scratch s;
  s.write("one.json", sweep_scene(s.work / "one").dump());
  s.write("mpi.json", sweep_scene(s.work / "mpi").dump());
  const Outcome one = s.fretwear(args("one.json", {"--jobs", "1", "-q"}));
  REQUIRE_MESSAGE(one.exited(kDone), one.describe());
  const MpiOutcome killed = mpirun(s.work, 2, args("mpi.json", {"-q"}), "FRETWEAR_SWEEP_KILL_AFTER_RUNS=4");
  REQUIRE_MESSAGE(killed.status != kDone, killed.err);
  CHECK_FALSE(fs::exists(s.work / "mpi" / "sweep"));
  const MpiOutcome resumed = mpirun(s.work, 2, args("mpi.json", {"--resume"}));
  REQUIRE_MESSAGE(resumed.status == kDone, resumed.err);
  CHECK_MESSAGE(resumed.err.find("0 kept") == std::string::npos, resumed.err);
  CHECK(csv_rows(s.work / "mpi" / "sweep" / "sweep.csv", "timings.total_s") ==
        csv_rows(s.work / "one" / "sweep" / "sweep.csv", "timings.total_s"));
}

TEST_CASE("a sweep's variants under mpirun are checked a share per rank, and every problem is said once, in order") {
  // Four of the six variants are refused by their physics (load.P past what half-plane elasticity carries, found
  // once the contact is solved); the three ranks check two variants each, and rank 0 says all four, in the runs'
  // order, as one process does.
  Scratch s;
  s.write("mpi.json", sweep_scene(s.work / "mpi").dump());
  const std::vector<std::string> sweep{"sweep", "mpi.json", "--vary", "load.P=1e5,3e10,1e11", "--vary",
                                       "friction=0.4,0.5", "-q"};
  const Outcome one = s.fretwear(sweep);
  REQUIRE_MESSAGE(one.exited(kInvalid), one.describe());
  const MpiOutcome three = mpirun(s.work, 3, sweep);
  CHECK_MESSAGE(three.status == kInvalid, three.err);
  // mpirun adds its own lines after the program's.
  CHECK_MESSAGE(three.err.rfind(one.err, 0) == 0, three.err, "\n-- one process:\n", one.err);
  CHECK(one.err.find("the mean contact pressure") != std::string::npos);
  CHECK_FALSE(fs::exists(s.work / "mpi"));
}

TEST_CASE("an invalid sweep under mpirun exits 2, said once, nothing written") {
  Scratch s;
  s.write("mpi.json", sweep_scene(s.work / "mpi").dump());
  const MpiOutcome bad = mpirun(s.work, 2, {"sweep", "mpi.json", "--vary", "load.P=1e5,-1", "-q"});
  CHECK_MESSAGE(bad.status == kInvalid, bad.err);
  const auto first = bad.err.find("load.P"), second = bad.err.find("sw__load.P_-1.0", bad.err.find("sw__load.P_-1.0") + 1);
  CHECK(first != std::string::npos);
  CHECK_MESSAGE(second == std::string::npos, bad.err);
  CHECK_FALSE(fs::exists(s.work / "mpi"));
}
#endif
