#include "engine/sweep_mpi.hpp"

#include <atomic>
#include <chrono>
#include <cstdlib>
#include <stdexcept>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "engine/scene.hpp"

#ifdef FRETWEAR_HAVE_MPI
#include <mpi.h>
#endif

namespace fretwear {
namespace {

// The variables an MPI launcher sets in every process it starts: Open MPI's mpirun, PMIx (srun --mpi=pmix, Open
// MPI 4 and later), PMI-1/2 (srun --mpi=pmi2, MPICH's hydra).
bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
    if (std::getenv(v)) return true;
  return false;
}

#ifdef FRETWEAR_HAVE_MPI

using nlohmann::json;

// Waiting ranks poll instead of blocking in MPI_Recv: Open MPI's blocking calls spin a core at 100%, which on a
// machine with as many ranks as cores takes it from the runs. A poll every millisecond costs nothing next to runs of
// milliseconds to hours.
constexpr auto kPollEvery = std::chrono::milliseconds(1);
constexpr int kTagResult = 1;  // rank → 0: the outcome of its last run (an empty object before the first), as JSON
constexpr int kTagTask = 2;    // 0 → rank: the index of its next run, or −1: no more
constexpr int kTagShare = 3;   // 0 → rank: share()'s text
constexpr int kTagChecks = 4;  // rank → 0: check_all()'s results of its share, as JSON {"k": [texts], ...}

MPI_Status wait_for(int source, int tag) {
  MPI_Status status;
  for (int flag = 0;;) {
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &status);
    if (flag) return status;
    std::this_thread::sleep_for(kPollEvery);
  }
}

std::string receive_text(const MPI_Status& status) {
  int length = 0;
  MPI_Get_count(&status, MPI_CHAR, &length);
  std::string text(std::size_t(length), '\0');
  MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

void send_text(const std::string& text, int to, int tag) {
  MPI_Send(text.data(), int(text.size()), MPI_CHAR, to, tag, MPI_COMM_WORLD);
}

class OpenMpiSweep final : public MpiSweep {
 public:
  explicit OpenMpiSweep(int jobs) : jobs_(jobs) {
    // Open MPI passes large messages between ranks of one machine by reading the other process's memory (CMA),
    // which needs ptrace permission that containers often withhold; the messages here are summaries of a few kB,
    // copied as cheaply through shared memory. A setting of the user's wins.
    ::setenv("OMPI_MCA_btl_vader_single_copy_mechanism", "none", 0);
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);  // MPI is called from the main thread alone
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
  ~OpenMpiSweep() override {
    if (abandoned_) MPI_Abort(MPI_COMM_WORLD, code_);
    MPI_Request request;
    MPI_Ibarrier(MPI_COMM_WORLD, &request);
    for (int flag = 0; !flag;) {
      MPI_Test(&request, &flag, MPI_STATUS_IGNORE);
      if (!flag) std::this_thread::sleep_for(kPollEvery);
    }
    MPI_Finalize();
  }
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  void abandon(int code) override {
    if (size_ > 1) abandoned_ = true, code_ = code;
  }
  bool root() const override { return rank_ == 0; }

  std::string share(const std::string& text) override {
    if (size_ == 1) return text;
    if (rank_ == 0) {
      for (int r = 1; r < size_; ++r) send_text(text, r, kTagShare);
      return text;
    }
    return receive_text(wait_for(0, kTagShare));
  }

  // Rank r checks every k ≡ r (mod size), in turn; rank 0 gathers the results and shares them. A variant's checks
  // take milliseconds and differ little: a fixed split serves. A check that throws in one rank throws in all, with
  // its message, as when every rank checked every variant: none waits for another that has given up.
  std::vector<std::vector<std::string>> check_all(
      std::size_t n, const std::function<std::vector<std::string>(std::size_t)>& check) override {
    if (size_ == 1) return thread_dispatch(jobs_)->check_all(n, check);
    json mine = {{"texts", json::object()}};
    for (std::size_t k = std::size_t(rank_); k < n; k += std::size_t(size_)) try {
        if (auto texts = check(k); !texts.empty()) mine["texts"][std::to_string(k)] = std::move(texts);
      } catch (const std::exception& e) {
        if (!mine.contains("failure")) mine["failure"] = e.what();
      }
    std::string all;
    if (rank_ != 0) {
      send_text(mine.dump(), 0, kTagChecks);
    } else {
      for (int r = 1; r < size_; ++r) {
        const json theirs = json::parse(receive_text(wait_for(r, kTagChecks)));
        mine["texts"].update(theirs["texts"]);
        if (theirs.contains("failure") && !mine.contains("failure")) mine["failure"] = theirs["failure"];
      }
      all = mine.dump();
    }
    const json shared = json::parse(share(all));
    if (shared.contains("failure")) throw std::runtime_error(shared["failure"].get<std::string>());
    std::vector<std::vector<std::string>> out(n);
    for (const auto& [k, texts] : shared["texts"].items()) out[std::stoul(k)] = texts.get<std::vector<std::string>>();
    return out;
  }

  void run_all(const std::vector<std::size_t>& todo, const std::function<SweepOutcome(std::size_t)>& run,
               const std::function<void(std::size_t, const SweepOutcome&)>& done) override {
    if (size_ == 1) return thread_dispatch(jobs_)->run_all(todo, run, done);
    if (rank_ != 0) return serve(rank_, run);
    std::atomic<std::size_t> next{0};
    std::mutex lock;
    std::vector<std::pair<std::size_t, SweepOutcome>> local;  // finished on rank 0's own thread, not yet reported
    std::atomic<bool> local_done{false};
    std::jthread own([&] {
      for (std::size_t i; (i = next++) < todo.size();) {
        SweepOutcome o = run(todo[i]);
        o.rank = 0;
        const std::lock_guard guard(lock);
        local.emplace_back(todo[i], std::move(o));
      }
      local_done = true;
    });
    auto report_local = [&] {
      std::vector<std::pair<std::size_t, SweepOutcome>> batch;
      {
        const std::lock_guard guard(lock);
        batch.swap(local);
      }
      for (const auto& [k, o] : batch) done(k, o);
    };
    for (int serving = size_ - 1;;) {
      report_local();
      if (serving == 0) {
        if (local_done) break;
        std::this_thread::sleep_for(kPollEvery);
        continue;
      }
      MPI_Status status;
      int flag = 0;
      MPI_Iprobe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &flag, &status);
      if (!flag) {
        std::this_thread::sleep_for(kPollEvery);
        continue;
      }
      const json message = json::parse(receive_text(status));
      if (message.contains("run")) done(message["run"].get<std::size_t>(), outcome_from_json(message["outcome"]));
      const std::size_t i = next++;
      const long long task = i < todo.size() ? static_cast<long long>(todo[i]) : -1;
      MPI_Send(&task, 1, MPI_LONG_LONG, status.MPI_SOURCE, kTagTask, MPI_COMM_WORLD);
      if (task < 0) --serving;
    }
    own.join();
    report_local();
  }

 private:
  // A rank other than 0: asks for a run, runs it, reports it with the next request, until told there are no more.
  static void serve(int rank, const std::function<SweepOutcome(std::size_t)>& run) {
    std::string report = "{}";
    for (;;) {
      send_text(report, 0, kTagResult);
      wait_for(0, kTagTask);
      long long task = -1;
      MPI_Recv(&task, 1, MPI_LONG_LONG, 0, kTagTask, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (task < 0) return;
      const std::size_t k = static_cast<std::size_t>(task);
      SweepOutcome o = run(k);
      o.rank = rank;
      report = json{{"run", k}, {"outcome", to_json(o)}}.dump();
    }
  }

  int jobs_, rank_ = 0, size_ = 1, code_ = 1;
  bool abandoned_ = false;
};

#endif

}  // namespace

std::unique_ptr<MpiSweep> start_mpi_if_launched(int jobs) {
  if (!launched_by_mpi()) return nullptr;
#ifdef FRETWEAR_HAVE_MPI
  return std::make_unique<OpenMpiSweep>(jobs);
#else
  (void)jobs;
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE"})
    if (const char* n = std::getenv(v); n && std::atoi(n) > 1)
      throw InputError(fmt::format("an MPI launcher started {} processes ({}={}), but this fretwear was built without "
                                   "MPI and each would run the whole sweep; install libopenmpi-dev (scripts/setup.sh) "
                                   "and build again, or run fretwear sweep without mpirun",
                                   n, v, n));
  return nullptr;
#endif
}

}  // namespace fretwear
