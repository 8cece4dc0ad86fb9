// Writing a command's results (docs/SCENES.md, "Output folders"). fretwear writes only into folders it made, each
// marked by a file kOutputMarker inside that lists what fretwear wrote there: output_dir_problems() refuses every
// other target, and every folder holding an entry fretwear did not write, before anything is computed. Everything
// goes into a staging folder beside the target, made at the first write, which replaces the target only when all of
// it is written: a failed or interrupted command leaves no half-written folder and no stray file.
#pragma once

#include <array>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"

namespace fretwear {

// The file that marks a folder as fretwear's own. It holds a JSON object, "format": "fretwear-folder", and
//   "kind": "results": a folder of results, with "entries": every path fretwear wrote in it, relative to it,
//     '/'-separated, a folder with a trailing '/' (a subfolder holding a marker of its own is listed, not entered:
//     its marker lists its entries); fretwear replaces the folder only while it holds nothing else;
//   "kind": "staging": a folder a command is writing (or, the earlier results, replacing), with the process doing
//     it: "pid", "host" (its host name), "boot_id" (the kernel's, /proc/sys/kernel/random/boot_id) and
//     "start_time" (the process's start in clock ticks after boot, field 22 of /proc/<pid>/stat; -1 unknown); a
//     replaced folder keeps its "entries".
// A marker that is not such an object (a marker of the first format: one line of text) counts as "kind": "results"
// without "entries": its folder may hold only the names fretwear writes (written_name()).
inline constexpr const char* kOutputMarker = ".fretwear";

// The names fretwear writes into a folder of results (OutputFolder::path() takes no other): these files, any file
// with one of these extensions (tables, gnuplot's scripts, data and images), and the folder kRunsFolder of a sweep,
// which holds a marked folder a run. A run's folder keeps the marked subfolders of the other commands (subfolder()).
// By these names fretwear judges a folder whose marker lists no entries: a staging folder, or results of the first
// marker format.
inline constexpr std::array<std::string_view, 5> kWrittenFiles = {"summary.json", "scene.resolved.json",
                                                                  "sweep.json", "index.html", "gnuplot.log"};
inline constexpr std::array<std::string_view, 5> kWrittenExtensions = {".csv", ".dat", ".gp", ".png", ".svg"};
inline constexpr const char* kRunsFolder = "runs";
bool written_name(const std::string& file);  // a name of kWrittenFiles or with an extension of kWrittenExtensions

// The entries of the marked folder `dir` that fretwear did not write, judged by its marker (kOutputMarker): paths
// relative to it, a folder with a trailing '/', a folder not entered once found foreign. Top-level names in
// `carried` are left out (a run's commit moves them into the new folder, whatever they hold). A marked subfolder
// named like a command's (subfolder()) at the top, and each marked folder the listing (or, without one, kRunsFolder)
// holds, is judged by its own marker.
std::vector<std::string> foreign_entries(const std::filesystem::path& dir,
                                         const std::vector<std::string>& carried = {});

// True when `dir` holds the marker kOutputMarker: a folder fretwear made.
bool has_marker(const std::filesystem::path& dir);

// True when `dir`, named as the staging folder of process `pid` (<name>.partial-<pid>, <name>.old-<pid>), is one a
// killed command left, which a command writing beside it may remove: the rule below kStagingSuffix. When it is one
// but for entries of the user's in it, and `foreign` is given, those entries are put there.
bool killed_leftover(const std::filesystem::path& dir, long pid, std::vector<std::string>* foreign = nullptr);

// The commands that write results, each into its own folder: run into output.dir, convergence and sweep into their
// subfolders of it (output_folder()), so that no command removes another's results.
enum class OutputCommand { run, convergence, sweep };
const char* subfolder(OutputCommand command);  // "" for run, "convergence", "sweep"
std::filesystem::path output_folder(const Scene& scene, OutputCommand command);

// Why `command` may not write its results for the scene read from scene_file (empty: it may). Refused: a path that
// names `.` or `..`; a folder named like a staging folder (staging_like()); a symbolic link, or a path through a
// dangling or looping one; a name too long for the file system once kStagingSuffix is added; the working folder or
// any folder above it; the scene file's folder or any folder above it; an existing file; an existing folder, not
// empty, without kOutputMarker; the folder the command replaces (output_folder()) when it holds an entry fretwear
// did not write (foreign_entries(), a run's folder without the subfolders it carries over), each such entry named;
// a folder whose parent (where the staging folder is made) cannot be written. Each problem names output.dir.
std::vector<std::string> output_dir_problems(const std::filesystem::path& dir, const std::filesystem::path& scene_file,
                                             OutputCommand command);
// The same for the scene's output.dir.
inline std::vector<std::string> output_dir_problems(const Scene& scene, const std::filesystem::path& scene_file,
                                                    OutputCommand command) {
  return output_dir_problems(scene.output_dir, scene_file, command);
}

// The names fretwear gives its staging folders beside a target `<name>`: `<name>.partial-<pid>` while a command
// writes, `<name>.old-<pid>` while it replaces. A process id has at most kPidDigits digits (Linux: pid_max <= 2^22).
// A command removes such a folder beside its target, left by a process that was killed, only when its marker says
// "kind": "staging" with that pid, the host is this one, the process has ended (no process has the pid, or the one
// that has it started at another time, or the host has booted since), and it holds nothing but what a command
// writes (foreign_entries()); or, killed between making the folder and its marker, when it is empty and no process
// has that pid. An empty, unmarked folder so named inside a folder being judged counts as fretwear's
// (foreign_entries()). Anything else so named is left alone.
inline constexpr int kPidDigits = 7;
inline constexpr const char* kStagingSuffix = ".partial-";
// True when `name` ends like a staging folder: `.partial-` or `.old-` and one digit or more. Such names are kept for
// staging folders, so that a folder's name tells them from results.
bool staging_like(const std::string& name);
// The longest file name the file system holding `p` (or the nearest folder above it that exists) takes.
long name_max(const std::filesystem::path& p);

// What the stages wrote into a folder, for the run's index.html: the tables (CSV) and the plots, in order.
struct Written {
  std::vector<std::string> tables, plots;
};

// A result file that cannot be written (a full disk, a quota, a file size limit): a problem of output.dir, under
// the heading "the results cannot be written". The command keeps nothing of its run (exit status 2).
class ResultsNotWritten : public SceneError {
 public:
  using SceneError::SceneError;
};

class OutputFolder {
 public:
  // dir: the target of `command`, checked by output_dir_problems(). A commit of the run's folder carries over the
  // convergence and sweep subfolders of the previous one; a command's subfolder whose parent (the run's folder) does
  // not exist yet makes it, marked (listing no entries). Nothing is created before the first write.
  explicit OutputFolder(std::filesystem::path dir, OutputCommand command = OutputCommand::run);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // `file` (written_name(), kRunsFolder, or "" for the folder itself) inside the staging folder, made with its
  // parents and its "staging" marker on the first call, when the leftovers of killed commands beside it are removed;
  // throws SceneError naming output.dir when it cannot be made.
  std::filesystem::path path(const std::string& file) const;
  void write(const std::string& file, const std::string& content) const;
  void write_json(const std::string& file, const nlohmann::json& j) const;
  // Replaces dir by the staging folder, its marker listing what the command wrote, carrying over the kept
  // subfolders of the previous dir, which is removed only while it holds nothing fretwear did not write. The two
  // are exchanged in one step (renameat2, RENAME_EXCHANGE; two renames where the file system lacks it), so that
  // dir never goes missing. Throws
  // SceneError naming output.dir when dir has changed since it was checked (an entry of the user's in it, or no
  // longer a folder of fretwear's), with nothing of it touched; Error when the file system refuses a step. Either
  // way the results stay in the staging folder, marked as results, and the message names it.
  void commit();
  // Removes the staging folder and the folders made for it, as the destructor of an uncommitted one does: nothing of
  // the command is left. The object writes nothing more after it.
  void discard();
  const std::filesystem::path& dir() const { return dir_; }

 private:
  void stage() const;
  void keep_staging();  // after a failed commit: the staging folder stays, marked as results
  std::filesystem::path dir_, staging_;
  OutputCommand command_;
  mutable bool staged_ = false;
  mutable std::vector<std::filesystem::path> made_parents_;  // folders made for the staging folder, deepest last
  bool committed_ = false, kept_ = false;
};

}  // namespace fretwear
