// gnuplot, as the writers use it: a plot command drawn into SVG and PNG, run inside the results folder. The
// scripts are written beside the plots, so that a user can edit and re-run them (gnuplot NAME.gp).
#pragma once

#include <filesystem>
#include <string>

namespace fretwear {

// gnuplot commands that draw `plot` (a plot or splot command with its newline) into <stem>.svg and <stem>.png.
std::string svg_and_png(const std::string& stem, const std::string& plot, int width = 1000, int height = 560);
// The same into <stem>.png alone: for colour maps, whose SVG holds a polygon per grid point (8 MB for 161 × 81).
std::string png_only(const std::string& stem, const std::string& plot, int width = 1000, int height = 560);

// Runs gnuplot on `script_file` inside `dir` and waits for it; false (and a note on stderr) when gnuplot is not on
// PATH, cannot be started or fails. gnuplot is started without a shell (any folder name is taken as it is), in a
// process group of its own with SIGINT and SIGTERM at their default: a signal sent to fretwear's group does not end
// it, and fretwear's own handling decides what the signal means. What gnuplot says goes to <dir>/gnuplot.log, which
// is removed when it is empty.
bool run_gnuplot(const std::filesystem::path& dir, const std::string& script_file);

// The settings every colour map (pm3d map) shares: the viridis palette, perceptually uniform and legible in grey
// and to the colour-blind (van der Walt and Smith 2015, matplotlib's default since 2.0), the axes cropped to the data
// (no margin past the first and last grid points), and the colour bar's label (enhanced text).
std::string colour_map_settings(const std::string& cb_label);
// gnuplot's `set palette defined (...)` for viridis, 9 stops (matplotlib's table at 0, 1/8, ..., 1).
std::string viridis_palette();
// The PNG height (px) that fits a map of span_x by span_y (any one unit) drawn with `set size ratio -1` into a
// `width`-px image without bands of white above and below it.
int map_height(double span_x, double span_y, int width = 1000);

// A colour along a ramp from t = 0 (first record) to 1 (last), as gnuplot's rgb '#rrggbb'.
std::string ramp(double t);
// A cycle count for a plot's key (enhanced text): "N = 1×10^{6}" and the like.
std::string cycles_label(double cycles);
// The same in plain text, for a noenhanced title: "N = 1e6", "N = 2.5e6", "N = 0 (unworn)".
std::string cycles_text(double cycles);

// `text` as a gnuplot string literal that holds it as it is: in single quotes, each of its own doubled (gnuplot reads
// no backslash escapes there), so that quotes, backslashes and JSON text in a label cannot end it.
std::string gnuplot_text(const std::string& text);

// A number for a CSV cell: 10 significant digits, ±inf spelled out.
std::string csv_number(double v);

}  // namespace fretwear
