#include "engine/folder.hpp"

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fstream>

#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

namespace fretwear {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// True when `a` is `b` or a folder above it (both absolute and normalised).
bool is_same_or_above(const fs::path& a, const fs::path& b) {
  auto ia = a.begin(), ib = b.begin();
  for (; ia != a.end() && !ia->empty(); ++ia, ++ib)
    if (ib == b.end() || *ia != *ib) return false;
  return true;
}

// The absolute form of p with symbolic links, `.` and `..` resolved as far as p exists.
fs::path resolved(const fs::path& p) {
  std::error_code ec;
  fs::path r = fs::weakly_canonical(fs::absolute(p, ec), ec);
  if (ec) r = fs::absolute(p, ec).lexically_normal();
  if (!r.has_filename() && r != r.root_path()) r = r.parent_path();
  return r;
}

bool ours(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / kOutputMarker, ec);
}

// Removes a folder of fretwear's own (marked); leaves anything else where it is.
void remove_ours(const fs::path& dir) {
  std::error_code ec;
  if (ours(dir)) fs::remove_all(dir, ec);
}

// 0 when a folder can be made in `dir`, else the errno that says why not. Permissions alone do not tell (root
// passes access() on /proc, where mkdir fails): a probe folder is made and removed at once.
int can_make_folder_in(const fs::path& dir) {
  const fs::path probe = dir / fmt::format(".fretwear-probe-{}", ::getpid());
  if (::mkdir(probe.c_str(), 0700) != 0) return errno == EEXIST ? 0 : errno;
  ::rmdir(probe.c_str());
  return 0;
}

// The problems with writing into `target` (absolute), the folder `what` names.
void check_target(const fs::path& target, const std::string& what, const fs::path& scene_dir,
                  std::vector<std::string>& problems) {
  std::error_code ec;
  const fs::path cwd = resolved(fs::current_path(ec));
  if (is_same_or_above(target, cwd)) {
    problems.push_back(fmt::format("{}: \"{}\" is the working folder or a folder above it, whose files fretwear "
                                   "would replace; give a folder of its own, e.g. output/<name>",
                                   what, target.string()));
    return;
  }
  if (is_same_or_above(target, scene_dir)) {
    problems.push_back(fmt::format("{}: \"{}\" holds the scene file, which fretwear would replace; give a folder of "
                                   "its own, e.g. output/<name>",
                                   what, target.string()));
    return;
  }
  if (target.native().size() >= PATH_MAX) {
    problems.push_back(fmt::format("{}: the path is {} characters long; the system takes at most {}", what,
                                   target.native().size(), PATH_MAX - 1));
    return;
  }
  const auto status = fs::status(target, ec);
  if (!fs::exists(status)) {
    // Made with its parents: the nearest folder that exists must take them.
    fs::path above = target.parent_path();
    while (!above.empty() && !fs::exists(above, ec) && above != above.root_path()) above = above.parent_path();
    if (!fs::is_directory(above, ec))
      problems.push_back(fmt::format("{}: \"{}\" lies under \"{}\", which is a file, not a folder; give a folder "
                                     "path",
                                     what, target.string(), above.string()));
    else if (const int e = can_make_folder_in(above); e != 0)
      problems.push_back(fmt::format("{}: cannot write into \"{}\" ({}), where \"{}\" would be made; give a "
                                     "folder you can write to",
                                     what, above.string(), std::strerror(e), target.string()));
    return;
  }
  if (!fs::is_directory(status)) {
    problems.push_back(fmt::format("{}: \"{}\" is an existing file, which fretwear would replace; give the path of "
                                   "a folder",
                                   what, target.string()));
  } else if (!ours(target) && !fs::is_empty(target, ec)) {
    problems.push_back(fmt::format("{}: the folder \"{}\" holds files fretwear did not write (it has no {} marker) "
                                   "and would replace; give a new or an empty folder, or remove this one",
                                   what, target.string(), kOutputMarker));
  }
}

}  // namespace

const char* subfolder(OutputCommand command) {
  switch (command) {
    case OutputCommand::run: return "";
    case OutputCommand::convergence: return "convergence";
    case OutputCommand::sweep: return "sweep";
  }
  return "";
}

fs::path output_folder(const Scene& scene, OutputCommand command) {
  return command == OutputCommand::run ? scene.output_dir : scene.output_dir / subfolder(command);
}

std::vector<std::string> output_dir_problems(const Scene& scene, const fs::path& scene_file, OutputCommand command) {
  std::vector<std::string> problems;
  const fs::path& dir = scene.output_dir;
  // The folder's path is written into summary.json and the report, which hold UTF-8 text only (a Python caller can
  // give any bytes).
  try {
    (void)json(dir.string()).dump();
  } catch (const json::type_error&) {
    problems.push_back(fmt::format("output.dir: {} is not UTF-8 text, which summary.json and the report hold; give "
                                   "a path in UTF-8",
                                   json(dir.string()).dump(-1, ' ', false, json::error_handler_t::replace)));
    return problems;
  }
  fs::path last = dir;
  if (!last.has_filename()) last = last.parent_path();  // "output/x/" names the folder x
  if (last.filename() == "." || last.filename() == ".." || dir.empty()) {
    problems.push_back(fmt::format("output.dir: \"{}\" names the folder \".\" or \"..\", whose files fretwear would "
                                   "replace; give a folder of its own, e.g. output/<name>",
                                   dir.string()));
    return problems;
  }
  const fs::path scene_dir = scene_file.empty() ? fs::path() : resolved(scene_file).parent_path();
  const fs::path target = resolved(dir);
  check_target(target, "output.dir", scene_dir, problems);
  if (command != OutputCommand::run && problems.empty()) {
    const std::string sub = subfolder(command);
    check_target(target / sub, fmt::format("output.dir (its subfolder {}/)", sub), scene_dir, problems);
  }
  return problems;
}

OutputFolder::OutputFolder(fs::path dir, OutputCommand command) : dir_(std::move(dir)), command_(command) {
  if (!dir_.has_filename()) dir_ = dir_.parent_path();
  staging_ = dir_;
  staging_ += fmt::format(".partial-{}", ::getpid());
}

void OutputFolder::stage() const {
  if (staged_) return;
  std::error_code ec;
  // The folders above the staging folder, made here (deepest last) and removed again if the command fails. A made
  // parent of a command's subfolder is the run's folder: it is marked as fretwear's own.
  for (fs::path p = fs::absolute(staging_, ec).parent_path(); !p.empty() && !fs::exists(p, ec); p = p.parent_path())
    made_parents_.insert(made_parents_.begin(), p);
  // Staging folders of commands that were killed (their process is gone) are removed.
  const fs::path parent = dir_.parent_path().empty() ? fs::path(".") : dir_.parent_path();
  const std::string name = dir_.filename().string();
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string entry = e.path().filename().string();
    for (const std::string& prefix : {name + ".partial-", name + ".old-"}) {
      if (entry.rfind(prefix, 0) != 0) continue;
      const std::string pid = entry.substr(prefix.size());
      if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
      if (::kill(pid_t(std::stol(pid)), 0) != 0 && errno == ESRCH) remove_ours(e.path());
    }
  }
  ec.clear();
  remove_ours(staging_);
  fs::create_directories(staging_, ec);
  if (!ec) std::ofstream(staging_ / kOutputMarker) << "fretwear's results: fretwear may replace this folder\n";
  // A command's subfolder lives in the run's folder, which is fretwear's own from then on: marked when made here or
  // found empty.
  const fs::path run_folder = fs::absolute(dir_).parent_path();
  if (!ec && command_ != OutputCommand::run && !ours(run_folder)) {
    int entries = 0;
    for (auto it = fs::directory_iterator(run_folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      entries += it->path().filename() != staging_.filename();
    if (entries == 0)
      std::ofstream(run_folder / kOutputMarker) << "fretwear's results: fretwear may replace this folder\n";
  }
  if (ec || ::access(staging_.c_str(), W_OK) != 0 || !ours(staging_)) {
    const std::string why = ec ? ec.message() : "permission denied";
    fs::remove_all(staging_, ec);
    throw SceneError({fmt::format("output.dir: cannot write into \"{}\" ({}); give a folder you can write to",
                                  dir_.string(), why)});
  }
  staged_ = true;
}

OutputFolder::~OutputFolder() {
  if (committed_ || !staged_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  for (auto p = made_parents_.rbegin(); p != made_parents_.rend(); ++p) {
    int entries = 0;
    for (auto it = fs::directory_iterator(*p, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) ++entries;
    if (entries == 1) fs::remove(*p / kOutputMarker, ec);  // a marker made here, alone
    fs::remove(*p, ec);                                    // only when empty
  }
}

fs::path OutputFolder::path(const std::string& file) const {
  stage();
  return staging_ / file;
}

void OutputFolder::write(const std::string& file, const std::string& content) const {
  std::ofstream out(path(file), std::ios::binary);
  out << content;
  if (!out) throw Error("cannot write " + path(file).string());
}

void OutputFolder::write_json(const std::string& file, const json& j) const { write(file, j.dump(2) + "\n"); }

void OutputFolder::commit() {
  stage();
  std::error_code ec;
  if (fs::exists(fs::symlink_status(dir_, ec))) {
    if (!fs::is_directory(dir_, ec) || (!ours(dir_) && !fs::is_empty(dir_, ec)))  // checked before; changed since
      throw Error(fmt::format("{} changed while fretwear ran and is no longer a folder of its own; the results are "
                              "in {}",
                              dir_.string(), staging_.string()));
    if (command_ == OutputCommand::run)  // the other commands' results stay
      for (const OutputCommand other : {OutputCommand::convergence, OutputCommand::sweep}) {
        const fs::path sub = dir_ / subfolder(other);
        if (fs::exists(sub, ec)) fs::rename(sub, staging_ / sub.filename(), ec);
      }
    fs::path old = dir_;
    old += fmt::format(".old-{}", ::getpid());
    if (ours(dir_)) {
      fs::rename(dir_, old, ec);
    } else {
      fs::remove(dir_, ec);  // empty
    }
    if (ec) throw Error(fmt::format("cannot replace {}: {}; the results are in {}", dir_.string(), ec.message(),
                                    staging_.string()));
    fs::rename(staging_, dir_, ec);
    if (ec) throw Error(fmt::format("cannot move the results into {}: {}; they are in {}", dir_.string(), ec.message(),
                                    staging_.string()));
    remove_ours(old);
  } else {
    fs::rename(staging_, dir_, ec);
    if (ec) throw Error(fmt::format("cannot move the results into {}: {}; they are in {}", dir_.string(), ec.message(),
                                    staging_.string()));
  }
  committed_ = true;
}

}  // namespace fretwear
