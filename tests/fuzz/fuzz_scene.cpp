// libFuzzer target: any bytes through the scene parser and the checks before solving. They must report or accept,
// never crash, hang, leak or hit undefined behaviour (built with -fsanitize=fuzzer,address,undefined). Seeds:
// tests/bad_scenes/ and examples/. Run: build-fuzz/tests/fuzz/fuzz_scene -max_total_time=60 CORPUS_DIR
// tests/bad_scenes examples
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/folder.hpp"
#include "engine/preflight.hpp"
#include "engine/scene.hpp"

// The very path `fretwear validate` takes: parse_scene_text (what load_scene hands the file's text to), then the
// output folder's rules and the physics checks before solving (engine/preflight.hpp). Only an InputError (a scene's
// problems) may escape; anything else is a bug for the fuzzer to find. The grid and the cycle's increments are
// capped so that one input takes milliseconds: the checks' logic, not the solvers' cost, is what is fuzzed here. A
// profile's "file" is read relative to the working folder; the parser reads only a regular file, at most
// kMaxSceneBytes of it, so no input can make it block on a device or a pipe or read without end.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    fretwear::Scene scene =
        fretwear::parse_scene_text(std::string_view(reinterpret_cast<const char*>(data), size), "scene");
    (void)scene.to_json();
    (void)fretwear::output_dir_problems(scene, "fuzz/scene.json", fretwear::OutputCommand::run);
    scene.cells = std::min(scene.cells, 256);
    if (scene.tangential) scene.tangential->increments = std::min(scene.tangential->increments, 16);
    if (scene.crack) scene.crack->quadrature = std::min(scene.crack->quadrature, 16);
    (void)fretwear::physics_problems(scene);
  } catch (const fretwear::InputError&) {
  }
  return 0;
}
