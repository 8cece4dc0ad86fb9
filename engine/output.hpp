// Writing a run's results. Everything goes into a staging folder beside output.dir, which replaces output.dir only
// when the run has written all of it: a failed run never leaves a half-written folder behind.
#pragma once

#include <filesystem>
#include <string>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"

namespace fretwear {

class OutputFolder {
 public:
  // Creates the staging folder; throws SceneError naming output.dir if it cannot be created.
  explicit OutputFolder(std::filesystem::path dir);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  std::filesystem::path path(const std::string& file) const { return staging_ / file; }
  void write(const std::string& file, const std::string& content) const;
  void write_json(const std::string& file, const nlohmann::json& j) const;
  // Replaces output.dir by the staging folder.
  void commit();
  const std::filesystem::path& dir() const { return dir_; }

 private:
  std::filesystem::path dir_, staging_;
  bool committed_ = false;
};

// summary.json, scene.resolved.json, contact.csv, the plots and index.html. Returns the summary written.
nlohmann::json write_results(const Scene& scene, const RunResult& result, OutputFolder& out);

// gnuplot commands that draw `plot` (a plot or splot command with its newline) into <stem>.svg and <stem>.png.
std::string svg_and_png(const std::string& stem, const std::string& plot, int width = 1000, int height = 560);
// The same into <stem>.png alone: for colour maps, whose SVG holds a polygon per grid point (8 MB for 161 × 81).
std::string png_only(const std::string& stem, const std::string& plot, int width = 1000, int height = 560);

// Runs gnuplot on `script` inside `dir`; false (and a note on stderr) when gnuplot is missing or fails.
bool run_gnuplot(const std::filesystem::path& dir, const std::string& script_file);

}  // namespace fretwear
