// Writing a command's results (docs/SCENES.md, "Output folders"). fretwear writes only into folders it made, each
// marked by a file kOutputMarker inside: output_dir_problems() refuses every other target before anything is computed.
// Everything goes into a staging folder beside the target, made at the first write, which replaces the target only
// when all of it is written: a failed or interrupted command leaves no half-written folder and no stray file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"

namespace fretwear {

// The file that marks a folder as fretwear's own (its results, safe for fretwear to replace).
inline constexpr const char* kOutputMarker = ".fretwear";

// The commands that write results, each into its own folder: run into output.dir, convergence and sweep into their
// subfolders of it (output_folder()), so that no command removes another's results.
enum class OutputCommand { run, convergence, sweep };
const char* subfolder(OutputCommand command);  // "" for run, "convergence", "sweep"
std::filesystem::path output_folder(const Scene& scene, OutputCommand command);

// Why `command` may not write its results for the scene read from scene_file (empty: it may). Refused: a path that
// names `.` or `..`; a folder named like a staging folder (staging_like()); a symbolic link, or a path through a
// dangling or looping one; a name too long for the file system once kStagingSuffix is added; the working folder or
// any folder above it; the scene file's folder or any folder above it; an existing file; an existing folder, not
// empty, without kOutputMarker; a folder whose parent (where the staging folder is made) cannot be written. Each
// problem names output.dir.
std::vector<std::string> output_dir_problems(const Scene& scene, const std::filesystem::path& scene_file,
                                             OutputCommand command);

// The names fretwear gives its staging folders beside a target `<name>`: `<name>.partial-<pid>` while a command
// writes, `<name>.old-<pid>` while it replaces. A process id has at most kPidDigits digits (Linux: pid_max <= 2^22).
inline constexpr int kPidDigits = 7;
inline constexpr const char* kStagingSuffix = ".partial-";
// True when `name` ends like a staging folder: `.partial-` or `.old-` and one digit or more.
bool staging_like(const std::string& name);
// The longest file name the file system holding `p` (or the nearest folder above it that exists) takes.
long name_max(const std::filesystem::path& p);

// What the stages wrote into a folder, for the run's index.html: the tables (CSV) and the plots, in order.
struct Written {
  std::vector<std::string> tables, plots;
};

class OutputFolder {
 public:
  // dir: the target of `command`, checked by output_dir_problems(). A commit of the run's folder carries over the
  // convergence and sweep subfolders of the previous one; a command's subfolder whose parent (the run's folder) does
  // not exist yet makes it, marked. Nothing is created before the first write.
  explicit OutputFolder(std::filesystem::path dir, OutputCommand command = OutputCommand::run);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  // `file` inside the staging folder (made, with its parents, on the first call); throws SceneError naming
  // output.dir when it cannot be made.
  std::filesystem::path path(const std::string& file) const;
  void write(const std::string& file, const std::string& content) const;
  void write_json(const std::string& file, const nlohmann::json& j) const;
  // Replaces dir by the staging folder, carrying over the kept subfolders of the previous dir.
  void commit();
  const std::filesystem::path& dir() const { return dir_; }

 private:
  void stage() const;
  std::filesystem::path dir_, staging_;
  OutputCommand command_;
  mutable bool staged_ = false;
  mutable std::vector<std::filesystem::path> made_parents_;  // folders made for the staging folder, deepest last
  bool committed_ = false;
};

}  // namespace fretwear
