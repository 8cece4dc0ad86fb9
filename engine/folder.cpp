#include "engine/folder.hpp"

#include <algorithm>
#include <cerrno>
#include <climits>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <sstream>

#include <fcntl.h>
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

constexpr const char* kMarkerFormat = "fretwear-folder";

// A folder's marker as read: `kind` "results" or "staging"; `listed` when it lists its entries; `checksums`, of the
// listed files that have one (a marker written before checksums has none).
struct Marker {
  json j = json::object();
  std::string kind = "results";
  bool listed = false;
  std::set<std::string> entries;
  std::map<std::string, std::string> checksums;
};

// fnv1a64() of the file `p`'s bytes; empty when it cannot be read or is not a regular file (a pipe's opening would
// wait for a writer, a device's reading might never end).
std::string file_checksum(const fs::path& p) {
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(p, ec))) return {};
  std::ifstream in(p, std::ios::binary);
  if (!in) return {};
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return fnv1a64(bytes.str());
}

Marker read_marker(const fs::path& dir) {
  Marker m;
  std::error_code ec;
  if (!fs::is_regular_file(fs::symlink_status(dir / kOutputMarker, ec))) return m;  // fretwear writes a file there
  std::ifstream in(dir / kOutputMarker, std::ios::binary);
  const json j = json::parse(in, nullptr, false);
  if (!j.is_object() || j.value("format", "") != kMarkerFormat) return m;  // the first format: a line of text
  m.j = j;
  if (j.value("kind", "") == "staging") m.kind = "staging";
  if (const auto e = j.find("entries"); e != j.end() && e->is_array()) {
    m.listed = true;
    for (const auto& name : *e)
      if (name.is_string()) m.entries.insert(name.get<std::string>());
  }
  if (const auto c = j.find("checksums"); c != j.end() && c->is_object())
    for (const auto& [name, sum] : c->items())
      if (sum.is_string()) m.checksums[name] = sum.get<std::string>();
  return m;
}

bool write_marker(const fs::path& dir, const json& j) {
  std::ofstream out(dir / kOutputMarker, std::ios::binary | std::ios::trunc);
  out << j.dump(2) << "\n";
  return bool(out.flush());
}

// The marker of the results folder `dir`, listing `entries` (list_entries()) and the checksum of each file among
// them, by which a file edited since is told from the one fretwear wrote.
json results_marker(const fs::path& dir, const std::vector<std::string>& entries) {
  json checksums = json::object();
  for (const std::string& e : entries)
    if (e.back() != '/')
      if (const std::string sum = file_checksum(dir / e); !sum.empty()) checksums[e] = sum;
  return {{"format", kMarkerFormat},
          {"kind", "results"},
          {"note", "results fretwear wrote: fretwear may replace this folder while it holds only these entries, as "
                   "it wrote them"},
          {"entries", entries},
          {"checksums", checksums}};
}

// This process, as a staging folder's marker names it.
struct ProcessIdentity {
  long pid = 0;
  std::string host, boot_id;
  long long start_time = -1;
};

std::string first_line(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// Field 22 of /proc/<pid>/stat, the start in clock ticks after boot; -1 when it cannot be read. The fields are
// counted after the command's name, which is in parentheses and may hold spaces and parentheses itself.
long long start_time_of(long pid) {
  std::ifstream in(fmt::format("/proc/{}/stat", pid));
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto close = stat.rfind(')');
  if (close == std::string::npos) return -1;
  std::istringstream fields(stat.substr(close + 1));
  std::string field;
  for (int k = 3; k <= 22 && fields >> field; ++k)
    if (k == 22) return std::strtoll(field.c_str(), nullptr, 10);
  return -1;
}

const ProcessIdentity& this_process() {
  static const ProcessIdentity id = [] {
    ProcessIdentity p;
    p.pid = long(::getpid());
    char host[256] = {};
    if (::gethostname(host, sizeof host - 1) == 0) p.host = host;
    p.boot_id = first_line("/proc/sys/kernel/random/boot_id");
    p.start_time = start_time_of(p.pid);
    return p;
  }();
  return id;
}

json staging_marker(json j) {
  const ProcessIdentity& p = this_process();
  j["format"] = kMarkerFormat;
  j["kind"] = "staging";
  j["note"] = "a folder fretwear is writing or replacing: fretwear removes it once the process pid on host has "
              "ended without finishing it";
  j["pid"] = p.pid;
  j["host"] = p.host;
  j["boot_id"] = p.boot_id;
  j["start_time"] = p.start_time;
  return j;
}

// True when the process a staging marker names, on this host, has ended: the host has booted since, no process has
// its pid, or the process that has it started at another time.
bool process_ended(const json& m) {
  const ProcessIdentity& self = this_process();
  const long pid = m.value("pid", 0L);
  const std::string boot = m.value("boot_id", "");
  if (!boot.empty() && !self.boot_id.empty() && boot != self.boot_id) return true;
  if (::kill(pid_t(pid), 0) != 0 && errno == ESRCH) return true;
  const long long recorded = m.value("start_time", -1LL), now = start_time_of(pid);
  return recorded >= 0 && now >= 0 && recorded != now;
}

// The paths below `dir` (relative to the folder its walk started in, `rel`), sorted, a folder with a trailing '/';
// a subfolder with a marker of its own is listed, not entered; the top's marker is left out.
void list_entries(const fs::path& dir, const std::string& rel, std::vector<std::string>& entries) {
  std::error_code ec;
  std::set<std::string> names;
  for (auto it = fs::directory_iterator(dir, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
    names.insert(it->path().filename().string());
  for (const std::string& name : names) {
    if (rel.empty() && name == kOutputMarker) continue;
    const fs::path p = dir / name;
    if (!fs::is_directory(fs::symlink_status(p, ec))) {
      entries.push_back(rel + name);
      continue;
    }
    entries.push_back(rel + name + "/");
    if (!has_marker(p)) list_entries(p, rel + name + "/", entries);
  }
}

// True when a marker without a list takes `name` (at `rel` below its folder) as fretwear's: a written_name() file at
// the top, the folder kRunsFolder at the top, a marked folder in it.
bool written_by_name(const std::string& rel, const std::string& name, bool folder, bool marked) {
  if (rel.empty()) return folder ? name == kRunsFolder && !marked : written_name(name);
  return rel == std::string(kRunsFolder) + "/" && folder && marked;
}

void collect_foreign(const fs::path& dir, const std::string& shown, const std::vector<std::string>& carried,
                     std::vector<std::string>& found);

// The walk of collect_foreign() through `folder`, `rel` below the marked folder whose marker `m` judges it.
void walk_foreign(const fs::path& folder, const std::string& rel, const Marker& m, const std::string& shown,
                  const std::vector<std::string>& carried, std::vector<std::string>& found) {
  std::error_code ec;
  std::set<std::string> names;
  auto it = fs::directory_iterator(folder, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec)) names.insert(it->path().filename().string());
  if (ec) {  // what cannot be read cannot be told fretwear's
    found.push_back(shown + rel + (rel.empty() ? "(its entries, which cannot be read)" : ""));
    return;
  }
  for (const std::string& name : names) {
    const bool top = rel.empty();
    if (top && name == kOutputMarker) continue;
    if (top && std::find(carried.begin(), carried.end(), name) != carried.end()) continue;
    const fs::path p = folder / name;
    // fretwear writes no links: one under a name it wrote is the user's, whatever it leads to (a file of the same
    // bytes passes the checksum), and replacing the folder would remove it.
    const fs::file_status status = fs::symlink_status(p, ec);
    if (fs::is_symlink(status)) {
      found.push_back(shown + rel + name + " (a link)");
      continue;
    }
    // Nor pipes, sockets or devices: one is the user's, and never opened (a pipe's opening waits for a writer).
    if (!fs::is_directory(status) && !fs::is_regular_file(status)) {
      found.push_back(shown + rel + name + " (not a regular file)");
      continue;
    }
    const bool is_folder = fs::is_directory(status), marked = is_folder && has_marker(p);
    const std::string path = rel + name + (is_folder ? "/" : "");
    bool own = m.listed ? m.entries.count(path) > 0 : written_by_name(rel, name, is_folder, marked);
    // A staging folder killed between its making and its marker's (a sweep's run, OutputFolder::stage()) is empty:
    // nothing in it to lose.
    if (!own && is_folder && !marked && staging_like(name) && fs::is_empty(p, ec)) own = true;
    // A file fretwear wrote and the user then changed is the user's now.
    if (const auto sum = m.checksums.find(path); own && !is_folder && sum != m.checksums.end() &&
                                                 file_checksum(p) != sum->second) {
      found.push_back(shown + path + " (changed since fretwear wrote it)");
      continue;
    }
    if (top && marked && (name == subfolder(OutputCommand::convergence) || name == subfolder(OutputCommand::sweep)))
      own = true;  // a command's results kept in a run's folder
    if (!own) {
      found.push_back(shown + path);
    } else if (marked) {
      collect_foreign(p, shown + path, {}, found);
    } else if (is_folder) {
      walk_foreign(p, path, m, shown, carried, found);
    }
  }
}

void collect_foreign(const fs::path& dir, const std::string& shown, const std::vector<std::string>& carried,
                     std::vector<std::string>& found) {
  walk_foreign(dir, "", read_marker(dir), shown, carried, found);
}

// Lends the owner every permission on `dir` (removing or moving an entry needs write permission on its folder, and
// moving a folder into another one on the folder itself, whose `..` changes).
void lend_owner_all(const fs::path& dir) {
  std::error_code ec;
  if (fs::is_directory(fs::symlink_status(dir, ec)))
    fs::permissions(dir, fs::perms::owner_all, fs::perm_options::add, ec);
}

// Removes the folder `dir`, whatever permission bits its folders carry. Only for a folder found fretwear's whole.
void remove_folder(const fs::path& dir) {
  std::error_code ec;
  lend_owner_all(dir);
  for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
       it.increment(ec))
    lend_owner_all(it->path());  // before the iterator enters it
  fs::remove_all(dir, ec);
}

// The foreign entries for a message: the first few, and how many more.
std::string entry_list(const std::vector<std::string>& entries) {
  constexpr std::size_t kShown = 10;
  std::string s;
  for (std::size_t i = 0; i < entries.size() && i < kShown; ++i) s += (i ? ", " : "") + entries[i];
  if (entries.size() > kShown) s += fmt::format(" and {} more", entries.size() - kShown);
  return s;
}

// The names a commit of `command` carries over from the folder it replaces.
std::vector<std::string> carried_by(OutputCommand command) {
  if (command != OutputCommand::run) return {};
  return {subfolder(OutputCommand::convergence), subfolder(OutputCommand::sweep)};
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

// The problems with writing into `target` (absolute), the folder `what` names, `shown` as the scene gives it. When
// `replaced` (the command's own folder, not the run's folder above a command's subfolder), an existing target must
// hold nothing fretwear did not write but the names `carried` over.
void check_target(const fs::path& target, const std::string& what, const fs::path& scene_dir,
                  std::vector<std::string>& problems, const fs::path& shown, bool replaced,
                  const std::vector<std::string>& carried) {
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
  } else if (!has_marker(target) && !fs::is_empty(target, ec)) {
    problems.push_back(fmt::format("{}: the folder \"{}\" holds files fretwear did not write (it has no {} marker) "
                                   "and would replace; give a new or an empty folder, or remove this one",
                                   what, target.string(), kOutputMarker));
  } else if (const auto foreign = replaced && has_marker(target) ? foreign_entries(target, carried)
                                                           : std::vector<std::string>{};
             !foreign.empty()) {
    problems.push_back(fmt::format("{}: \"{}\" holds {}, which fretwear did not write and replacing the folder "
                                   "would remove; move them, or choose another output.dir",
                                   what, shown.string(), entry_list(foreign)));
  } else if (::access(target.parent_path().c_str(), W_OK | X_OK) != 0) {
    // The staging folder is made beside the target, and renamed over it.
    problems.push_back(fmt::format("{}: cannot write into \"{}\" ({}), where fretwear puts the new \"{}\"; give a "
                                   "folder in a folder you can write to",
                                   what, target.parent_path().string(), std::strerror(errno), target.string()));
  }
}

}  // namespace

bool written_name(const std::string& file) {
  if (std::find(kWrittenFiles.begin(), kWrittenFiles.end(), file) != kWrittenFiles.end()) return true;
  const std::string ext = fs::path(file).extension().string();
  return file.find('/') == std::string::npos && file.size() > ext.size() &&
         std::find(kWrittenExtensions.begin(), kWrittenExtensions.end(), ext) != kWrittenExtensions.end();
}

bool has_marker(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(dir / kOutputMarker, ec));  // fretwear writes no links
}

bool killed_leftover(const fs::path& dir, long pid, std::vector<std::string>* foreign) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(dir, ec))) return false;
  // Killed between the folder's making and its marker's: empty, its process gone.
  if (!has_marker(dir)) return fs::is_empty(dir, ec) && !ec && ::kill(pid_t(pid), 0) != 0 && errno == ESRCH;
  const Marker m = read_marker(dir);
  if (m.kind != "staging" || m.j.value("pid", -1L) != pid || m.j.value("host", "") != this_process().host)
    return false;
  if (!process_ended(m.j)) return false;
  std::vector<std::string> found = foreign_entries(dir);
  if (found.empty()) return true;
  if (foreign) *foreign = std::move(found);
  return false;
}

std::vector<std::string> foreign_entries(const fs::path& dir, const std::vector<std::string>& carried) {
  std::vector<std::string> found;
  collect_foreign(dir, "", carried, found);
  return found;
}

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

std::vector<std::string> output_dir_problems(const fs::path& dir, const fs::path& scene_file, OutputCommand command) {
  std::vector<std::string> problems;
  // The folder's path is written into summary.json and the report, which hold UTF-8 text only (a Python caller can
  // give any bytes).
  if (!utf8_text(dir.string())) {
    problems.push_back(fmt::format("output.dir: {} is not UTF-8 text, which summary.json and the report hold; give "
                                   "a path in UTF-8",
                                   json(dir.string()).dump(-1, ' ', false, json::error_handler_t::replace)));
    return problems;
  }
  if (holds_nul(dir.native())) {
    problems.push_back(fmt::format("output.dir: {} {}", json(dir.string()).dump(), kHoldsNul));
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
  // The names of staging folders are kept for them (a command beside them may remove them, folder.hpp): a results
  // folder is never named so.
  if (staging_like(last.filename().string())) {
    problems.push_back(fmt::format("output.dir: \"{}\" ends like the staging folders fretwear makes and removes "
                                   "beside a results folder (<name>.partial-<digits>, <name>.old-<digits>); give a "
                                   "name that does not end in .partial- or .old- and digits",
                                   dir.string()));
    return problems;
  }
  if (!link_problems(dir, "output.dir", problems)) return problems;
  const bool no_file = scene_file.empty() || scene_file == kStdinScene;  // nothing of the scene's own to keep safe
  const fs::path scene_dir = no_file ? fs::path() : resolved(scene_file).parent_path();
  const fs::path target = resolved(dir);
  check_target(target, "output.dir", scene_dir, problems, dir, command == OutputCommand::run, carried_by(command));
  if (command != OutputCommand::run && problems.empty()) {
    const std::string sub = subfolder(command);
    const std::string what = fmt::format("output.dir (its subfolder {}/)", sub);
    if (link_problems(dir / sub, what, problems))
      check_target(target / sub, what, scene_dir, problems, dir / sub, true, {});
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
  // Staging folders of commands that were killed are removed (the rule in folder.hpp); this one's name among them.
  const fs::path parent = dir_.parent_path().empty() ? fs::path(".") : dir_.parent_path();
  const std::string name = dir_.filename().string();
  for (const auto& e : fs::directory_iterator(parent, ec)) {
    const std::string entry = e.path().filename().string();
    for (const std::string& prefix : {name + kStagingSuffix, name + ".old-"}) {
      if (entry.rfind(prefix, 0) != 0) continue;
      const std::string pid = entry.substr(prefix.size());
      if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
      if (killed_leftover(e.path(), std::stol(pid))) remove_folder(e.path());
    }
  }
  ec.clear();
  if (fs::exists(fs::symlink_status(staging_, ec)))
    throw SceneError({fmt::format("output.dir: \"{}\" exists and is not a staging folder fretwear may remove; fretwear "
                                  "writes the results there before moving them into \"{}\": move it",
                                  staging_.string(), dir_.string())});
  ec.clear();
  fs::create_directories(staging_, ec);
  if (!ec && !write_marker(staging_, staging_marker(json::object()))) ec = std::make_error_code(std::errc::io_error);
  // A command's subfolder lives in the run's folder, which is fretwear's own from then on: marked when made here or
  // found empty, listing no entries of its own.
  const fs::path run_folder = fs::absolute(dir_).parent_path();
  if (!ec && command_ != OutputCommand::run && !has_marker(run_folder)) {
    int entries = 0;
    for (auto it = fs::directory_iterator(run_folder, ec); !ec && it != fs::directory_iterator(); it.increment(ec))
      entries += it->path().filename() != staging_.filename();
    if (entries == 0) write_marker(run_folder, results_marker(run_folder, {}));
  }
  if (ec || ::access(staging_.c_str(), W_OK) != 0 || !has_marker(staging_)) {
    const std::string why = ec ? ec.message() : "permission denied";
    fs::remove_all(staging_, ec);
    throw SceneError({fmt::format("output.dir: cannot write into \"{}\" ({}); give a folder you can write to",
                                  dir_.string(), why)});
  }
  staged_ = true;
}

OutputFolder::~OutputFolder() { discard(); }

void OutputFolder::discard() {
  if (committed_ || kept_ || !staged_) return;
  std::error_code ec;
  fs::remove_all(staging_, ec);
  for (auto p = made_parents_.rbegin(); p != made_parents_.rend(); ++p) {
    int entries = 0;
    for (auto it = fs::directory_iterator(*p, ec); !ec && it != fs::directory_iterator(); it.increment(ec)) ++entries;
    if (entries == 1) fs::remove(*p / kOutputMarker, ec);  // a marker made here, alone
    fs::remove(*p, ec);                                    // only when empty
  }
  made_parents_.clear();
  staged_ = false;  // nothing left to remove
}

fs::path OutputFolder::path(const std::string& file) const {
  if (!(file.empty() || file == kRunsFolder || written_name(file)))  // the markers judge folders by these names
    throw Error(fmt::format("internal: \"{}\" is not a name fretwear writes (kWrittenFiles, kWrittenExtensions)", file));
  stage();
  return staging_ / file;
}

void OutputFolder::write(const std::string& file, const std::string& content) const {
  errno = 0;
  std::ofstream out(path(file), std::ios::binary);
  out << content;
  out.close();
  if (!out) {  // a full disk, a quota, a file size limit: the staging folder goes with this object, uncommitted
    const std::string why = errno != 0 ? std::strerror(errno) : "the write failed";
    throw ResultsNotWritten("the results cannot be written",
                            {fmt::format("output.dir: cannot write {} into \"{}\" ({}); nothing of this run is kept "
                                         "and the folder is as it was: free some space, or give another output.dir",
                                         file, dir_.string(), why)});
  }
}

void OutputFolder::write_json(const std::string& file, const json& j) const { write(file, j.dump(2) + "\n"); }

void OutputFolder::keep_staging() {
  std::vector<std::string> entries;
  list_entries(staging_, "", entries);
  write_marker(staging_, results_marker(staging_, entries));
  kept_ = true;
}

void OutputFolder::commit() {
  stage();
  std::error_code ec;
  std::vector<std::string> entries;  // what the command wrote, before anything is carried over
  list_entries(staging_, "", entries);
  auto failed = [&](const std::string& why) {
    keep_staging();
    return Error(fmt::format("{}; the results are in {}", why, staging_.string()));
  };
  const auto status = fs::symlink_status(dir_, ec);
  const bool exists = fs::exists(status);
  if (exists) {
    // Checked before the command computed; the user may have changed it since.
    if (!fs::is_directory(status) || (!has_marker(dir_) && !fs::is_empty(dir_, ec))) {
      keep_staging();
      throw SceneError({fmt::format("output.dir: \"{}\" changed while fretwear ran and is no longer a folder of its "
                                    "own; the results are in \"{}\"",
                                    dir_.string(), staging_.string())});
    }
    if (const auto foreign = has_marker(dir_) ? foreign_entries(dir_, carried_by(command_))
                                              : std::vector<std::string>{};
        !foreign.empty()) {
      keep_staging();
      throw SceneError({fmt::format("output.dir: \"{}\" came to hold {} while fretwear ran, which fretwear did not "
                                    "write and replacing the folder would remove; it is left as it was, and the "
                                    "results are in \"{}\"",
                                    dir_.string(), entry_list(foreign), staging_.string())});
    }
  }
  const bool earlier_results = exists && has_marker(dir_);
  if (exists && !earlier_results) {
    fs::remove(dir_, ec);  // empty
    if (ec) throw failed(fmt::format("cannot replace {}: {}", dir_.string(), ec.message()));
  }
  // The new results are marked as results first: a command killed from here on leaves them whole, as results, in
  // the staging folder.
  if (!write_marker(staging_, results_marker(staging_, entries)))
    throw failed(fmt::format("cannot write {} in {}", kOutputMarker, staging_.string()));
  // The target's permission bits stay, set once nothing more is moved into the staging folder.
  auto keep_bits = [&] {
    if (exists) fs::permissions(staging_, status.permissions(), fs::perm_options::replace, ec);
  };
  if (!earlier_results) {
    keep_bits();
    fs::rename(staging_, dir_, ec);
    if (ec) throw failed(fmt::format("cannot move the results into {}: {}", dir_.string(), ec.message()));
    committed_ = true;
    return;
  }
  // The earlier results are marked as a staging folder of this process before they take a staging folder's name,
  // so that a later command may remove them if this one is killed then; a run's folder hands over the other
  // commands' results it keeps.
  const json earlier = read_marker(dir_).j;
  write_marker(dir_, staging_marker(earlier));
  std::vector<OutputCommand> kept;
  if (command_ == OutputCommand::run) kept = {OutputCommand::convergence, OutputCommand::sweep};
  lend_owner_all(dir_);
  for (const OutputCommand other : kept) carry(dir_ / subfolder(other), staging_ / subfolder(other));
  keep_bits();
  auto undo = [&](const std::string& why) {
    lend_owner_all(staging_);
    for (const OutputCommand other : kept) carry(staging_ / subfolder(other), dir_ / subfolder(other));
    write_marker(dir_, earlier);
    return failed(fmt::format("cannot move the results into {}: {}", dir_.string(), why));
  };
  // One step where the file system can: the new results take dir's place and the earlier ones the staging
  // folder's, so that no instant leaves dir missing. Else two renames, through <dir>.old-<pid>.
  // Tests only: FRETWEAR_KILL_AFTER_REPLACING, a kill (SIGKILL) as soon as the first step has moved dir.
  auto killed_here = [] {
    if (std::getenv("FRETWEAR_KILL_AFTER_REPLACING")) std::raise(SIGKILL);
  };
  fs::path replaced = staging_;
  if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, dir_.c_str(), RENAME_EXCHANGE) == 0) {
    killed_here();
  } else {
    const int e = errno;
    if (e != EINVAL && e != ENOSYS) throw undo(std::strerror(e));
    replaced = dir_;
    replaced += fmt::format(".old-{}", ::getpid());
    fs::rename(dir_, replaced, ec);
    if (ec) throw undo(ec.message());
    killed_here();
    fs::rename(staging_, dir_, ec);
    if (ec) {
      std::error_code back;
      fs::rename(replaced, dir_, back);
      throw undo(ec.message());
    }
  }
  committed_ = true;
  if (foreign_entries(replaced).empty()) remove_folder(replaced);
}

}  // namespace fretwear
