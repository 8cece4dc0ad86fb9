#include "engine/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>

#include <fmt/format.h>

namespace fretwear {
namespace fs = std::filesystem;

bool run_gnuplot(const fs::path& dir, const std::string& script_file) {
  if (std::system("command -v gnuplot >/dev/null 2>&1") != 0) {
    std::cerr << "fretwear: gnuplot not found; plots skipped (install it: apt-get install gnuplot-nox)\n";
    return false;
  }
  const std::string cmd = fmt::format("cd '{}' && gnuplot '{}' > gnuplot.log 2>&1", dir.string(), script_file);
  if (std::system(cmd.c_str()) != 0) {
    std::cerr << "fretwear: gnuplot failed on " << script_file << "; see gnuplot.log among the results\n";
    return false;
  }
  std::error_code ec;
  if (fs::file_size(dir / "gnuplot.log", ec) == 0) fs::remove(dir / "gnuplot.log", ec);
  return true;
}

std::string svg_and_png(const std::string& stem, const std::string& plot, int width, int height) {
  return fmt::format("set terminal svg size {0},{1} dynamic font 'sans,12'\nset output '{2}.svg'\n{3}"
                     "set terminal pngcairo size {0},{1} font 'sans,11'\nset output '{2}.png'\nreplot\nunset output\n",
                     width, height, stem, plot);
}

std::string png_only(const std::string& stem, const std::string& plot, int width, int height) {
  return fmt::format("set terminal pngcairo size {0},{1} font 'sans,11'\nset output '{2}.png'\n{3}unset output\n",
                     width, height, stem, plot);
}

std::string csv_number(double v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return fmt::format("{:.10g}", v);
}

std::string viridis_palette() {
  // matplotlib's viridis sampled at k/8, k = 0 ... 8.
  static const char* stops[9] = {"#440154", "#472d7b", "#3b528b", "#2c728e", "#21918c",
                                 "#28ae80", "#5ec962", "#addc30", "#fde725"};
  std::string s = "set palette defined (";
  for (int k = 0; k < 9; ++k) s += fmt::format("{}{} '{}'", k ? ", " : "", k, stops[k]);
  return s + ")\n";
}

std::string colour_map_settings(const std::string& cb_label) {
  return viridis_palette() + "set autoscale xfix\nset autoscale yfix\nset autoscale cbfix\n" +
         fmt::format("set cblabel '{}'\n", cb_label);
}

int map_height(double span_x, double span_y, int width) {
  // The plot area is the image less about 260 px of margins across (labels, colour bar) and 150 down (title, tics,
  // label); with ratio −1 its height is its width times span_y/span_x.
  const double area = double(width - 260) * span_y / span_x;
  return std::clamp(int(std::lround(area)) + 150, 260, 1200);
}

// A colour ramp from dark blue to orange (matplotlib's plasma, up to 0.85): t in [0, 1].
std::string ramp(double t) {
  static const int stops[5][3] = {{13, 8, 135}, {106, 0, 168}, {177, 42, 144}, {225, 100, 98}, {244, 150, 40}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(3, int(t));
  const double u = t - k;
  int c[3];
  for (int j = 0; j < 3; ++j) c[j] = int(std::lround(stops[k][j] + u * (stops[k + 1][j] - stops[k][j])));
  return fmt::format("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
}

// A cycle count for a legend (gnuplot enhanced text): 0, 250, 3.16×10^5.
std::string cycles_label(double c) {
  if (c == 0.0) return "N = 0 (unworn)";
  if (c < 1e4) return fmt::format("N = {:.0f}", c);
  const int e = int(std::floor(std::log10(c) + 1e-12));
  const double m = c / std::pow(10.0, e);
  if (std::abs(m - std::round(m)) < 5e-3) return fmt::format("N = {:.0f}×10^{{{}}}", std::round(m), e);
  return fmt::format("N = {:.3g}×10^{{{}}}", m, e);
}

std::string cycles_text(double c) {
  if (c == 0.0) return "N = 0 (unworn)";
  if (c < 1e4) return fmt::format("N = {:.0f}", c);
  const int e = int(std::floor(std::log10(c) + 1e-12));
  return fmt::format("N = {:.3g}e{}", c / std::pow(10.0, e), e);
}

}  // namespace fretwear
