#include "engine/checkpoint.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <utility>

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include "common/error.hpp"
#include "engine/deferred_signals.hpp"
#include "engine/folder.hpp"
#include "engine/version.hpp"

namespace fretwear {

using nlohmann::json;

std::filesystem::path checkpoint_path(const Scene& scene) {
  std::filesystem::path p = scene.output_dir;
  if (!p.has_filename()) p = p.parent_path();  // "output/x/" names the folder x
  p += ".checkpoint";
  return p;
}

namespace {

// Reads a CBOR document until its top-level key `format` has given its value; stops at anything else.
class FormatProbe : public nlohmann::json_sax<json> {
 public:
  bool is_checkpoint = false;

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t, const string_t&) override { return value(); }
  bool string(string_t& s) override {
    if (depth_ == 1 && at_format_) {
      is_checkpoint = s == "fretwear-checkpoint";
      return false;
    }
    return value();
  }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    if (depth_ == 1) at_format_ = false;
    ++depth_;
    return true;
  }
  bool key(string_t& k) override {
    if (depth_ == 1) at_format_ = k == "format";
    return true;
  }
  bool end_object() override { return --depth_ > 0; }
  bool start_array(std::size_t) override {
    if (depth_ == 0) return false;  // a checkpoint is a map
    if (depth_ == 1) at_format_ = false;
    ++depth_;
    return true;
  }
  bool end_array() override { return --depth_ > 0; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::detail::exception&) override { return false; }

 private:
  // A value at the top is no map; a value of another top-level key moves on.
  bool value() {
    if (depth_ == 0) return false;
    if (depth_ == 1) at_format_ = false;
    return true;
  }
  int depth_ = 0;
  bool at_format_ = false;
};

}  // namespace

bool is_checkpoint_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  FormatProbe probe;
  json::sax_parse(in, &probe, json::input_format_t::cbor, false);
  return probe.is_checkpoint;
}

std::vector<std::string> checkpoint_problems(const Scene& scene) {
  if (!scene.wear) return {};
  const std::filesystem::path path = checkpoint_path(scene);
  std::vector<std::string> problems;
  const std::string beside = fmt::format("\"{}\", where a wear run into output.dir \"{}\" keeps its checkpoint "
                                         "(<output.dir>.checkpoint)",
                                         path.string(), scene.output_dir.string());
  const std::size_t n = path.filename().native().size(), tmp = n + std::strlen(".tmp-") + std::size_t(kPidDigits);
  if (const long max = name_max(path); tmp > std::size_t(max)) {
    problems.push_back(fmt::format("output.dir: the checkpoint of a wear run into \"{}\", \"{}\", is written first "
                                   "as \"<its name>.tmp-<process id>\", up to {} characters, and this file system "
                                   "takes names of at most {}: give an output.dir whose last name is at most {} "
                                   "characters",
                                   scene.output_dir.string(), path.string(), tmp, max,
                                   std::size_t(max) - (tmp - n) - std::strlen(".checkpoint")));
    return problems;
  }
  std::error_code ec;
  const auto status = std::filesystem::symlink_status(path, ec);
  if (!std::filesystem::exists(status)) return problems;
  if (!std::filesystem::is_regular_file(status))
    problems.push_back(fmt::format("output.dir: {}, is {}, which the run would replace; move it away, or give "
                                   "another output.dir",
                                   beside,
                                   std::filesystem::is_directory(status) ? "a folder"
                                   : std::filesystem::is_symlink(status) ? "a symbolic link"
                                                                         : "not a regular file"));
  else if (!is_checkpoint_file(path))
    problems.push_back(fmt::format("output.dir: {}, is a file fretwear did not write (not a fretwear checkpoint), "
                                   "which the run would overwrite and then delete; move it away, or give another "
                                   "output.dir",
                                   beside));
  return problems;
}

std::uint64_t scene_hash(const Scene& scene) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (const unsigned char c : scene.to_json().dump()) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

// The CBOR of a document read back is the CBOR it was read from (its keys in order, each number in the form its value
// takes), so a checkpoint whose bytes changed after it was written no longer has its checksum.
std::string checkpoint_checksum(json j) {
  j.erase("checksum");
  const std::vector<std::uint8_t> bytes = json::to_cbor(j);
  return fnv1a64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

std::optional<json> read_checkpoint(const std::filesystem::path& path, const Scene& scene) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return std::nullopt;
  std::ifstream in(path, std::ios::binary);
  const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), {});
  json j = json::from_cbor(bytes, true, false);
  // A checkpoint is written whole and renamed into place; one cut short (copied, or its disk full) is recognised by its
  // format key when that is in the part left, and a run without --resume then overwrites it. Otherwise the file is
  // not known for fretwear's, and a run without --resume refuses it too (checkpoint_problems()).
  if (j.is_discarded() || !j.is_object() || j.value("format", "") != "fretwear-checkpoint")
    throw InputError(is_checkpoint_file(path)
                         ? fmt::format("{}: a fretwear checkpoint that is damaged or cut short ({} bytes that do not "
                                       "read as one); delete it, or run without --resume, which starts afresh and "
                                       "overwrites it",
                                       path.string(), bytes.size())
                         : fmt::format("{}: not a fretwear checkpoint, or one cut short before its format; move it "
                                       "away (a run without --resume refuses it as well, as a file it did not write)",
                                       path.string()));
  if (j.value("format_version", 0) != kCheckpointFormat || j.value("fretwear", "") != std::string(kVersion))
    throw InputError(fmt::format("{}: written by fretwear {} (checkpoint format {}); this is fretwear {} (format {}): "
                                 "it cannot be resumed. Delete it, or run without --resume",
                                 path.string(), j.value("fretwear", "?"), j.value("format_version", 0), kVersion,
                                 kCheckpointFormat));
  if (!j.contains("checksum") || j["checksum"] != checkpoint_checksum(j))
    throw InputError(fmt::format("{}: damaged: its content no longer has the checksum it was written with, so "
                                 "what it holds cannot be trusted; delete it and run without --resume",
                                 path.string()));
  const std::string want = fmt::format("{:016x}", scene_hash(scene));
  if (j.value("scene_hash", "") != want)
    throw InputError(fmt::format("{}: the checkpoint belongs to another scene (\"{}\", hash {}; this scene \"{}\" "
                                 "resolves to hash {}): refused. Delete it, or run without --resume",
                                 path.string(), j.value("scene", "?"), j.value("scene_hash", "?"), scene.name, want));
  return j;
}

void write_checkpoint(const std::filesystem::path& path, const json& j) {
  json sealed = j;
  sealed["checksum"] = checkpoint_checksum(j);
  const std::vector<std::uint8_t> bytes = json::to_cbor(sealed);
  const DeferredStopSignals hold;  // no temporary file left by a signal
  if (path.has_parent_path()) {
    std::error_code ec;
    std::filesystem::create_directories(path.parent_path(), ec);  // an error shows at open()
  }
  const std::filesystem::path folder = path.parent_path().empty() ? "." : path.parent_path();
  std::filesystem::path tmp = path;
  tmp += fmt::format(".tmp-{}", ::getpid());
  // The bytes go first into a file without a name (O_TMPFILE), which a SIGKILL or a crash during the write leaves
  // nowhere: it is named tmp only once written and synced, and renamed over the checkpoint at once. Where the file
  // system has no O_TMPFILE (or /proc is not there to name it), tmp is written directly; the signals above are held
  // either way.
  auto write_all = [&](int fd) {
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t k = ::write(fd, bytes.data() + done, bytes.size() - done);
      if (k < 0 && errno == EINTR) continue;
      if (k <= 0) return false;
      done += std::size_t(k);
    }
    // FRETWEAR_CHECKPOINT_PAUSE_MS (tests only): a pause with the bytes written, so that a test's signals land
    // while the checkpoint is being put in place.
    if (const char* pause = std::getenv("FRETWEAR_CHECKPOINT_PAUSE_MS"))
      std::this_thread::sleep_for(std::chrono::milliseconds(std::atoi(pause)));
    return ::fsync(fd) == 0;
  };
  bool named = false;
  if (const int fd = ::open(folder.c_str(), O_TMPFILE | O_WRONLY | O_CLOEXEC, 0644); fd >= 0) {
    if (write_all(fd)) {
      ::unlink(tmp.c_str());  // a file of this name is this process id's own, left by an earlier process
      const std::string self = fmt::format("/proc/self/fd/{}", fd);
      named = ::linkat(AT_FDCWD, self.c_str(), AT_FDCWD, tmp.c_str(), AT_SYMLINK_FOLLOW) == 0;
    }
    ::close(fd);
  }
  if (!named) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throw Error(fmt::format("cannot write the checkpoint {}: {}", tmp.string(), std::strerror(errno)));
    const bool written = write_all(fd);
    const int e = errno;
    if (::close(fd) != 0 || !written) {
      ::unlink(tmp.c_str());
      throw Error(fmt::format("cannot write the checkpoint {}: {}", tmp.string(), std::strerror(written ? errno : e)));
    }
  }
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot move the checkpoint into {}: {}", path.string(), std::strerror(errno)));
  }
  const int dir = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dir >= 0) {
    ::fsync(dir);
    ::close(dir);
  }
}

json wear_checkpoint(const Scene& scene, std::uint64_t hash, const DriveState& at, double cycles_total,
                     const std::vector<double>& w, const std::vector<WearRecord>& records, json contact,
                     json stepper_state) {
  json j = {{"format", "fretwear-checkpoint"},
            {"format_version", kCheckpointFormat},
            {"fretwear", kVersion},
            {"scene", scene.name},
            {"scene_hash", fmt::format("{:016x}", hash)},
            {"stepper", to_string(scene.wear->stepper)},
            {"cells", int(w.size())},
            {"cycles", at.N},
            {"cycles_total", cycles_total},
            {"dN", at.dt},
            {"next_record", at.next},
            {"steps", at.steps},
            {"w", blob(w)},
            {"records", json::array()},
            {"contact", std::move(contact)},
            {"stepper_state", std::move(stepper_state)}};
  for (const WearRecord& r : records) j["records"].push_back(record_json(r));
  return j;
}

DriveState resume_wear(const json& j, const Scene& scene, std::vector<double>& w, std::vector<WearRecord>& records) {
  if (j.at("stepper").get<std::string>() != to_string(scene.wear->stepper) || j.at("cells").get<int>() != int(w.size()))
    throw InputError("checkpoint: written by another stepper or grid");
  const DriveState at{j.at("cycles").get<double>(), j.at("dN").get<double>(), j.at("next_record").get<std::size_t>(),
                      j.at("steps").get<long>()};
  const std::size_t n = w.size();
  w = unblob(j.at("w"));
  records.clear();
  for (const json& r : j.at("records")) records.push_back(record_from(r));
  // What the checksum cannot vouch for, since anyone can write one: the vectors on this grid, the counts in range.
  // The state w may hold more than one value a cell (each body's wear in its own frame); a record's fields, one.
  const std::size_t cells = std::size_t(scene.cells);
  auto per_cell = [cells](const std::vector<double>& v) { return v.size() == cells; };
  bool fits = w.size() == n && std::all_of(w.begin(), w.end(), [](double wi) { return std::isfinite(wi); }) &&
              std::isfinite(at.N) && at.N >= 0.0 && std::isfinite(at.dt) && at.dt > 0.0 && at.steps >= 0;
  for (const WearRecord& r : records)
    fits = fits && per_cell(r.w) && per_cell(r.p) && per_cell(r.s) && (r.q.empty() || per_cell(r.q)) &&
           r.cycles >= 0.0 && r.cycles <= at.N;
  if (!fits)
    throw InputError("checkpoint: damaged: its wear, its records or its counts do not fit this scene's grid of " +
                     std::to_string(cells) + " cells");
  return at;
}

json save_implicit(const wear::ImplicitWearStepper& stepper) {
  const wear::ImplicitStepperState st = stepper.state();
  return json{{"accepted", st.stats.accepted},
              {"rejected", st.stats.rejected},
              {"implicit_solves", st.stats.implicit_solves},
              {"responses", st.stats.responses},
              {"last_error", st.stats.last_error},
              {"unconverged", st.stats.unconverged},
              {"p_full", blob(st.p_full)},
              {"p_half", blob(st.p_half)}};
}

void restore_implicit(const json& j, wear::ImplicitWearStepper& stepper, std::size_t cells) {
  wear::ImplicitStepperState st;
  st.stats.accepted = j.at("accepted").get<int>();
  st.stats.rejected = j.at("rejected").get<int>();
  st.stats.implicit_solves = j.at("implicit_solves").get<int>();
  st.stats.responses = j.at("responses").get<int>();
  st.stats.last_error = j.at("last_error").get<double>();
  st.stats.unconverged = j.value("unconverged", 0);
  st.p_full = cell_vector(j.at("p_full"), cells, "the stepper's warm start");
  st.p_half = cell_vector(j.at("p_half"), cells, "the stepper's half-step warm start");
  stepper.restore(st);
}

json save_explicit(const wear::ExplicitWearStepper& stepper, const wear::WearRateSystem& rate) {
  const auto& st = stepper.stats();
  const auto& last = rate.last_response();
  return json{{"accepted", st.accepted}, {"rejected", st.rejected}, {"max_step", st.max_step},
              {"evaluations", rate.evaluations()}, {"p", blob(last.p)}, {"s", blob(last.s)},
              {"stick", {last.has_stick, last.stick_left, last.stick_right}}, {"stick_zones", last.stick_zones}};
}

void restore_explicit(const json& j, wear::ExplicitWearStepper& stepper, wear::WearRateSystem& rate,
                      const std::vector<double>& w) {
  wear::CycleResponse last;
  last.p = cell_vector(j.at("p"), w.size(), "the last response's pressure", false);
  last.s = cell_vector(j.at("s"), w.size(), "the last response's slip", false);
  last.has_stick = j.at("stick")[0].get<bool>();
  last.stick_left = j.at("stick")[1].get<double>();
  last.stick_right = j.at("stick")[2].get<double>();
  if (j.contains("stick_zones")) last.stick_zones = j.at("stick_zones").get<std::vector<std::pair<double, double>>>();
  rate.restore(j.at("evaluations").get<long>(), std::move(last));
  // The derivative dopri5 carries at a step boundary is the rate of its last stage, at the state reached.
  const std::vector<double> dwdN = rate.last_rate();
  const int accepted = j.at("accepted").get<int>();
  stepper.restore({accepted, j.at("rejected").get<int>(), j.at("max_step").get<double>()}, w,
                  accepted > 0 ? &dwdN : nullptr);
}

json save_cycle_by_cycle(const wear::WearRateSystem& rate) { return json{{"evaluations", rate.evaluations()}}; }

void restore_cycle_by_cycle(const json& j, wear::WearRateSystem& rate) {
  rate.restore(j.at("evaluations").get<long>(), {});
}

// Vectors travel as raw doubles (exact, ±inf included), little-endian on every platform fretwear builds on.
json blob(const std::vector<double>& v) {
  std::vector<std::uint8_t> bytes(v.size() * sizeof(double));
  if (!v.empty()) std::memcpy(bytes.data(), v.data(), bytes.size());
  return json::binary(std::move(bytes));
}

std::vector<double> unblob(const json& j) {
  const auto& bytes = j.get_binary();
  if (bytes.size() % sizeof(double) != 0) throw InputError("checkpoint: a vector of the wrong size");
  std::vector<double> v(bytes.size() / sizeof(double));
  if (!v.empty()) std::memcpy(v.data(), bytes.data(), bytes.size());
  return v;
}

std::vector<double> cell_vector(const json& j, std::size_t cells, const std::string& what, bool empty) {
  const std::vector<double> v = j.is_binary() ? unblob(j) : j.get<std::vector<double>>();
  if (!(v.size() == cells || (empty && v.empty())))
    throw InputError(fmt::format("checkpoint: damaged: {} holds {} values, where this scene's grid has {} cells", what,
                                 v.size(), cells));
  if (std::any_of(v.begin(), v.end(), [](double x) { return std::isnan(x); }))
    throw InputError(fmt::format("checkpoint: damaged: {} holds a value that is not a number", what));
  return v;
}

json contact_state_json(const ContactState& s) {
  return {{"p", blob(s.p)}, {"gap", blob(s.gap)}, {"approach", s.approach}};
}

void contact_state_from(const json& j, ContactState& s, std::size_t cells, const std::string& what) {
  s.p = cell_vector(j.at("p"), cells, what + "'s pressure");
  s.gap = cell_vector(j.at("gap"), cells, what + "'s gap");
  s.approach = j.at("approach").get<double>();
}

json record_json(const WearRecord& r) {
  return {{"cycles", r.cycles},
          {"worn_area", r.worn_area},
          {"max_depth", r.max_depth},
          {"p_max", r.p_max},
          {"Q_max", r.Q_max},
          {"stick_zone", r.stick_zone ? json{r.stick_zone->first, r.stick_zone->second} : json(nullptr)},
          {"stick_zones", r.stick_zones},
          {"contact", {r.contact.first, r.contact.second}},
          {"touching", {r.touching.first, r.touching.second}},
          {"fraction", r.fraction},
          {"w", blob(r.w)},
          {"p", blob(r.p)},
          {"s", blob(r.s)},
          {"q", blob(r.q)},
          {"block", r.block},
          {"w_pad", blob(r.w_pad)},
          {"w_specimen", blob(r.w_specimen)}};
}

WearRecord record_from(const json& j) {
  WearRecord r;
  r.cycles = j.at("cycles").get<double>();
  r.worn_area = j.at("worn_area").get<double>();
  r.max_depth = j.at("max_depth").get<double>();
  r.p_max = j.at("p_max").get<double>();
  r.Q_max = j.value("Q_max", 0.0);
  if (!j.at("stick_zone").is_null()) r.stick_zone = Interval{j["stick_zone"][0], j["stick_zone"][1]};
  if (j.contains("stick_zones")) r.stick_zones = j.at("stick_zones").get<std::vector<Interval>>();
  else if (r.stick_zone) r.stick_zones = {*r.stick_zone};  // a checkpoint written before the zones were recorded
  r.contact = {j.at("contact")[0].get<double>(), j.at("contact")[1].get<double>()};
  if (j.contains("touching"))  // absent from checkpoints written before it was recorded
    r.touching = {j.at("touching")[0].get<double>(), j.at("touching")[1].get<double>()};
  r.fraction = j.at("fraction").get<double>();
  r.w = unblob(j.at("w"));
  r.p = unblob(j.at("p"));
  r.s = unblob(j.at("s"));
  r.q = unblob(j.at("q"));
  r.block = j.value("block", -1);
  if (j.contains("w_pad")) r.w_pad = unblob(j.at("w_pad")), r.w_specimen = unblob(j.at("w_specimen"));
  return r;
}

}  // namespace fretwear
