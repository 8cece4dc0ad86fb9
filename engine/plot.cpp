#include "engine/plot.hpp"

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

}  // namespace fretwear
