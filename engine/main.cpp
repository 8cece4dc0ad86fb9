// fretwear: the command line. Exit status 0 done, 2 invalid scene (nothing written), 3 a solver did not converge.
#include <iostream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "engine/convergence.hpp"
#include "engine/output.hpp"
#include "engine/scene.hpp"
#include "engine/simulation.hpp"
#include "engine/version.hpp"

namespace {

using namespace fretwear;

constexpr int kExitInvalid = 2;
constexpr int kExitNoConvergence = 3;

int run(const std::string& path, bool quiet, bool verbose) {
  const Scene scene = load_scene(path);
  OutputFolder out(scene.output_dir);
  if (!quiet) std::cerr << fmt::format("fretwear: {}: normal contact on {} cells\n", scene.name, scene.cells);
  try {
    const RunResult result = Simulation(scene).run();
    const auto summary = write_results(scene, result, out);
    out.commit();
    if (!quiet) {
      const auto& c = summary["contact"];
      std::cout << fmt::format("{}: contact [{:.6e}, {:.6e}] m in {} zone(s), p_max {:.6e} Pa ({})\n", scene.name,
                               c["extent"][0].get<double>(), c["extent"][1].get<double>(), c["zones"].size(),
                               c["p_max"].get<double>(), result.normal.summary.brief());
      if (verbose && c.contains("closed_form"))
        std::cout << fmt::format("  against the closed form ({}): extent {:.2e}, p_max {:.2e}, rms {:.2e}\n",
                                 c["closed_form"]["kind"].get<std::string>(),
                                 c["closed_form"]["extent_error"].get<double>(),
                                 c["closed_form"]["p_max_error"].get<double>(),
                                 c["closed_form"]["rms_error"].get<double>());
      if (summary.contains("cycle")) {
        const auto& cy = summary["cycle"];
        std::cout << fmt::format("  cycle ({}, {} route): Q/fP = {:.4g}", cy["regime"].get<std::string>(),
                                 cy["route"].get<std::string>(), cy["Q_over_fP"].get<double>());
        if (!cy["stick_zone"].is_null())
          std::cout << fmt::format(", stick zone [{:.6e}, {:.6e}] m, slip range {:.4e} m, energy {:.4e} J/m",
                                   cy["stick_zone"][0].get<double>(), cy["stick_zone"][1].get<double>(),
                                   cy["slip_max"].get<double>(), cy["dissipated_energy"].get<double>());
        if (cy.contains("message")) std::cout << "\n  " << cy["message"].get<std::string>();
        std::cout << "\n";
      }
      std::cout << "results in " << scene.output_dir.string() << "/\n";
    }
  } catch (const ConvergenceError& e) {
    out.write_json("summary.json", {{"scene", scene.name}, {"version", kVersion}, {"status", "not_converged"},
                                    {"message", e.what()}});
    out.commit();
    throw;
  }
  return 0;
}

int convergence(const std::string& path, int from, int to, bool quiet) {
  const Scene scene = load_scene(path);
  OutputFolder out(scene.output_dir);
  const ConvergenceStudy study = run_convergence(scene, from, to, quiet ? nullptr : &std::cerr);
  std::cout << study.table();
  out.write("convergence.csv", study.csv());
  out.write_json("scene.resolved.json", scene.to_json());
  out.commit();
  if (!quiet) std::cout << "table in " << (scene.output_dir / "convergence.csv").string() << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"fretwear: fretting in plane elastic contacts, from one JSON scene.\n"
               "Exit status: 0 done, 2 invalid scene (nothing written), 3 a solver did not converge."};
  app.set_version_flag("--version", std::string("fretwear ") + kVersion);
  app.require_subcommand(1);
  bool quiet = false, verbose = false;
  app.add_flag("-q,--quiet", quiet, "print nothing but errors");
  app.add_flag("-v,--verbose", verbose, "print more detail");

  std::string scene_path;
  auto* run_cmd = app.add_subcommand("run", "run a scene and write its results into output.dir");
  run_cmd->add_option("scene", scene_path, "scene file (JSON)")->required();
  auto* validate_cmd = app.add_subcommand("validate", "check a scene and report every problem; writes nothing");
  validate_cmd->add_option("scene", scene_path, "scene file (JSON)")->required();
  app.add_subcommand("defaults", "print a scene with every default filled in");
  int from = 128, to = 65536;
  auto* conv_cmd = app.add_subcommand("convergence", "solve the scene's normal problem on grids of doubling size");
  conv_cmd->add_option("scene", scene_path, "scene file (JSON)")->required();
  conv_cmd->add_option("--from", from, "coarsest grid (cells)")->check(CLI::Range(16, 1 << 20));
  conv_cmd->add_option("--to", to, "finest grid (cells)")->check(CLI::Range(16, 1 << 20));
  for (auto* sub : {run_cmd, validate_cmd, conv_cmd}) {
    sub->add_flag("-q,--quiet", quiet, "print nothing but errors");
    sub->add_flag("-v,--verbose", verbose, "print more detail");
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version, or the usage error
    return code == 0 ? 0 : kExitInvalid;
  }
  try {
    if (*run_cmd) return run(scene_path, quiet, verbose);
    if (*validate_cmd) {
      const Scene scene = load_scene(scene_path);
      if (!quiet) std::cout << scene_path << ": valid scene \"" << scene.name << "\"\n";
      if (verbose) std::cout << scene.to_json().dump(2) << "\n";
      return 0;
    }
    if (app.got_subcommand("defaults")) {
      std::cout << default_scene_json().dump(2) << "\n";
      return 0;
    }
    if (*conv_cmd) return convergence(scene_path, from, to, quiet);
  } catch (const InputError& e) {
    std::cerr << "fretwear: " << e.what() << "\n";
    return kExitInvalid;
  } catch (const ConvergenceError& e) {
    std::cerr << "fretwear: " << e.what() << "\n";
    return kExitNoConvergence;
  } catch (const std::exception& e) {
    std::cerr << "fretwear: internal error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
