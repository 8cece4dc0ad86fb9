#include "engine/plot.hpp"

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

extern char** environ;

namespace fretwear {
namespace fs = std::filesystem;

namespace {

// Starts `gnuplot <script>` (found on PATH) inside `dir`, with stdin from /dev/null and stdout and stderr onto the
// open file `log`. No shell stands between: the folder's name and the script's reach gnuplot as they are, never as
// commands. The child leads a process group of its own, so that a signal sent to fretwear's group (a terminal's
// Ctrl-C, `timeout -s INT`) reaches fretwear alone, which decides what a stop means; SIGINT, SIGTERM and SIGQUIT are
// at their default and no signal is blocked (fretwear blocks SIGINT and SIGTERM while it writes results).
// Returns 0 with `pid` set, or the error number of the failure: ENOENT when gnuplot is not on PATH.
int spawn_gnuplot(const fs::path& dir, const std::string& script, int log, pid_t& pid) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log, STDERR_FILENO);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (const int sig : {SIGINT, SIGTERM, SIGQUIT}) sigaddset(&defaults, sig);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &defaults);
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  std::string program = "gnuplot", file = script;
  char* argv[] = {program.data(), file.data(), nullptr};
  const int failed = posix_spawnp(&pid, "gnuplot", &actions, &attributes, argv, environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  return failed;
}

// Waits for the child `pid` to end and puts its wait status in `status` (a signal that interrupts the wait is let
// through and the wait resumed); false when it cannot be waited for.
bool wait_for(pid_t pid, int& status) {
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return false;
  return true;
}

}  // namespace

bool run_gnuplot(const fs::path& dir, const std::string& script_file) {
  // Tests only: FRETWEAR_PLOT_PAUSE_MS, a pause before each gnuplot starts, so that a test's signal lands while the
  // results are being drawn.
  if (const char* pause = std::getenv("FRETWEAR_PLOT_PAUSE_MS"); pause && std::atoi(pause) > 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(std::atoi(pause)));
  // One log for all the scripts of a folder, each appending to it: a later script that runs clean keeps an earlier
  // one's failure.
  const fs::path log_file = dir / "gnuplot.log";
  const int log = ::open(log_file.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (log < 0) {
    std::cerr << fmt::format("fretwear: gnuplot.log could not be made in {} ({}); {} not drawn\n", dir.string(),
                             std::strerror(errno), script_file);
    return false;
  }
  struct stat opened {};
  const auto logged_before = ::fstat(log, &opened) == 0 ? std::uintmax_t(opened.st_size) : std::uintmax_t(0);
  pid_t pid = -1;
  const int failed = spawn_gnuplot(dir, script_file, log, pid);
  ::close(log);
  int status = 0;
  const bool waited = !failed && wait_for(pid, status);
  std::error_code ec;
  const auto logged = fs::file_size(log_file, ec);
  const bool said_nothing = ec || logged == logged_before;
  if (!ec && logged == 0) fs::remove(log_file, ec);
  if (failed == ENOENT) {  // said once a process: every later script finds the same PATH
    static std::atomic<bool> said{false};
    if (!said.exchange(true))
      std::cerr << "fretwear: gnuplot not found; plots skipped (install it: apt-get install gnuplot-nox)\n";
    return false;
  }
  if (failed) {
    std::cerr << fmt::format("fretwear: gnuplot could not be started on {} ({}); plots skipped\n", script_file,
                             std::strerror(failed));
    return false;
  }
  if (!waited || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    if (said_nothing)
      std::cerr << fmt::format("fretwear: gnuplot failed on {} ({}) and said nothing\n", script_file,
                               !waited               ? std::string("not waited for")
                               : WIFSIGNALED(status) ? fmt::format("ended by signal {}", WTERMSIG(status))
                                                     : fmt::format("exit status {}", WEXITSTATUS(status)));
    else
      std::cerr << "fretwear: gnuplot failed on " << script_file << "; see gnuplot.log among the results\n";
    return false;
  }
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

std::string gnuplot_text(const std::string& text) {
  std::string q = "'";
  for (const char c : text) {
    if (c == '\'') q += '\'';
    q += c == '\n' || c == '\r' ? ' ' : c;
  }
  return q + "'";
}

}  // namespace fretwear
