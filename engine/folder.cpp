#include "engine/folder.hpp"

#include <cerrno>
#include <climits>
#include <csignal>
#include <cstring>
#include <fstream>
#include <iterator>

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

// Lends the owner every permission on `dir` (removing or moving an entry needs write permission on its folder, and
// moving a folder into another one on the folder itself, whose `..` changes).
void lend_owner_all(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_directory(fs::symlink_status(dir, ec)))
    fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
}

// Removes a folder of fretwear's own (marked), whatever permission bits its folders carry; leaves anything else
// where it is.
void remove_ours(const fs::path& dir) {
  std::error_code ec;
  if (!ours(dir)) return;
  lend_owner_all(dir);
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    lend_owner_all(it->path());  // before the iterator enters it
  fs::remove_all(dir, ec);
}

// Moves the folder `from` to `to` (another folder), keeping its permission bits.
void carry(const fs::path& from, const fs::path& to) {
  std::error_code ec;
  const auto status = fs::symlink_status(from, ec);
  if (!fs::exists(status)) return;
  lend_owner_all(from);
  fs::rename(from, to, ec);
  if (fs::is_directory(status)) fs::permissions(ec ? from : to, status.permissions(), fs::perm_options::replace, ec);
}

// A symbolic link on the way to `given` (the path as the scene gives it), where the command meets it: refused when
// it is the last part (the results folder is replaced as a whole: the link would be, not the folder it points to),
// or when it dangles or loops (no folder can be made through it). False when a problem was found.
bool link_problems(const fs::path& given, const std::string& what, std::vector<std::string>& problems) {
  fs::path path = given;
  if (!path.has_filename()) path = path.parent_path();  // "output/x/" names x
  fs::path prefix;
  for (auto part = path.begin(); part != path.end(); ++part) {
    prefix /= *part;
    struct stat st {};
    if (::lstat(prefix.c_str(), &st) != 0) return true;  // missing from here on (made), or under a file (below)
    if (!S_ISLNK(st.st_mode)) continue;
    std::error_code ec;
    const std::string to = fs::read_symlink(prefix, ec).string();
    if (::stat(prefix.c_str(), &st) != 0) {
      const int e = errno;
      if (e == ENOENT)
        problems.push_back(fmt::format("{}: \"{}\" is a symbolic link to \"{}\", which does not exist; give a path "
                                       "without it, or make the folder it points to",
                                       what, prefix.string(), to));
      else if (e == ELOOP)
        problems.push_back(fmt::format("{}: \"{}\" is a symbolic link that leads back to itself (to \"{}\"); give a "
                                       "path without it",
                                       what, prefix.string(), to));
      else
        problems.push_back(fmt::format("{}: the symbolic link \"{}\" (to \"{}\") cannot be followed ({}); give a path "
                                       "without it",
                                       what, prefix.string(), to, std::strerror(e)));
      return false;
    }
    if (std::next(part) == path.end()) {
      problems.push_back(fmt::format("{}: \"{}\" is a symbolic link (to \"{}\"); fretwear replaces its results folder "
                                     "as a whole, which would replace the link: give the folder it points to, \"{}\"",
                                     what, given.string(), to, resolved(prefix).string()));
      return false;
    }
  }
  return true;
}

// Names the file system takes: each part of `target` (absolute), and the staging folder's beside it.
bool name_problems(const fs::path& target, const std::string& what, std::vector<std::string>& problems) {
  const std::size_t max = std::size_t(name_max(target));
  for (const auto& part : target)
    if (part.native().size() > max) {
      problems.push_back(fmt::format("{}: the name \"{}\" in \"{}\" is {} characters long; this file system takes "
                                     "names of at most {}: give a shorter one",
                                     what, part.string(), target.string(), part.native().size(), max));
      return false;
    }
  const std::size_t n = target.filename().native().size(),
                    staged = n + std::strlen(kStagingSuffix) + std::size_t(kPidDigits);
  if (staged > max) {
    problems.push_back(fmt::format("{}: the folder name \"{}\" is {} characters long; fretwear writes the results "
                                   "beside it into \"<name>{}<process id>\", up to {} characters, and this file "
                                   "system takes names of at most {}: give a name of at most {} characters",
                                   what, target.filename().string(), n, kStagingSuffix, staged, max,
                                   max - (staged - n)));
    return false;
  }
  return true;
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
  if (!name_problems(target, what, problems)) return;
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
  } else if (::access(target.parent_path().c_str(), W_OK | X_OK) != 0) {
    // The staging folder is made beside the target, and renamed over it.
    problems.push_back(fmt::format("{}: cannot write into \"{}\" ({}), where fretwear puts the new \"{}\"; give a "
                                   "folder in a folder you can write to",
                                   what, target.parent_path().string(), std::strerror(errno), target.string()));
  }
}

}  // namespace

bool staging_like(const std::string& name) {
  for (const std::string suffix : {kStagingSuffix, ".old-"}) {
    const auto at = name.rfind(suffix);
    if (at == std::string::npos) continue;
    const std::string digits = name.substr(at + suffix.size());
    if (!digits.empty() && digits.find_first_not_of("0123456789") == std::string::npos) return true;
  }
  return false;
}

long name_max(const fs::path& p) {
  std::error_code ec;
  fs::path above = fs::absolute(p, ec);
  while (!fs::is_directory(above, ec) && above.has_relative_path()) above = above.parent_path();
  const long n = ::pathconf(above.c_str(), _PC_NAME_MAX);
  return n > 0 ? n : NAME_MAX;
}

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
  // Staging folders of a killed command are removed by the next command writing beside them (OutputFolder::stage):
  // a results folder named like one would be.
  if (staging_like(last.filename().string())) {
    problems.push_back(fmt::format("output.dir: \"{}\" ends like the staging folders fretwear makes and removes "
                                   "beside a results folder (<name>.partial-<digits>, <name>.old-<digits>); give a "
                                   "name that does not end in .partial- or .old- and digits",
                                   dir.string()));
    return problems;
  }
  if (!link_problems(dir, "output.dir", problems)) return problems;
  const fs::path scene_dir = scene_file.empty() ? fs::path() : resolved(scene_file).parent_path();
  const fs::path target = resolved(dir);
  check_target(target, "output.dir", scene_dir, problems);
  if (command != OutputCommand::run && problems.empty()) {
    const std::string sub = subfolder(command);
    const std::string what = fmt::format("output.dir (its subfolder {}/)", sub);
    if (link_problems(dir / sub, what, problems)) check_target(target / sub, what, scene_dir, problems);
  }
  return problems;
}

OutputFolder::OutputFolder(fs::path dir, OutputCommand command) : dir_(std::move(dir)), command_(command) {
  if (!dir_.has_filename()) dir_ = dir_.parent_path();
  staging_ = dir_;
  staging_ += fmt::format("{}{}", kStagingSuffix, ::getpid());
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
    for (const std::string& prefix : {name + kStagingSuffix, name + ".old-"}) {
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
  if (const auto status = fs::symlink_status(dir_, ec); fs::exists(status)) {
    if (!fs::is_directory(status) || (!ours(dir_) && !fs::is_empty(dir_, ec)))  // checked before; changed since
      throw Error(fmt::format("{} changed while fretwear ran and is no longer a folder of its own; the results are "
                              "in {}",
                              dir_.string(), staging_.string()));
    fs::path old = dir_;
    old += fmt::format(".old-{}", ::getpid());
    const bool earlier_results = ours(dir_);
    if (earlier_results) {
      fs::rename(dir_, old, ec);
    } else {
      fs::remove(dir_, ec);  // empty
    }
    if (ec) throw Error(fmt::format("cannot replace {}: {}; the results are in {}", dir_.string(), ec.message(),
                                    staging_.string()));
    if (command_ == OutputCommand::run && earlier_results) {  // the other commands' results stay
      lend_owner_all(old);  // discarded below
      for (const OutputCommand other : {OutputCommand::convergence, OutputCommand::sweep})
        carry(old / subfolder(other), staging_ / subfolder(other));
    }
    fs::permissions(staging_, status.permissions(), fs::perm_options::replace, ec);  // the target's bits stay
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
