// libFuzzer target: any bytes through the scene parser. The parser must report or accept, never crash, hang, leak
// or hit undefined behaviour (built with -fsanitize=fuzzer,address,undefined). Seeds: tests/bad_scenes/ and
// examples/. Run: build-fuzz/tests/fuzz/fuzz_scene -max_total_time=60 CORPUS_DIR tests/bad_scenes examples
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "engine/scene.hpp"

// The very path `fretwear run` takes: load_scene reads the file and hands its text to parse_scene_text. Only an
// InputError (a scene's problems) may escape it; anything else is a bug for the fuzzer to find.
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const fretwear::Scene scene =
        fretwear::parse_scene_text(std::string_view(reinterpret_cast<const char*>(data), size), "scene");
    (void)scene.to_json();
  } catch (const fretwear::InputError&) {
  }
  return 0;
}
