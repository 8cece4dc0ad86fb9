// libFuzzer target: any bytes through the scene parser. The parser must report or accept, never crash, hang, leak
// or hit undefined behaviour (built with -fsanitize=fuzzer,address,undefined). Seeds: tests/bad_scenes/ and
// examples/. Run: build-fuzz/tests/fuzz/fuzz_scene -max_total_time=60 CORPUS_DIR tests/bad_scenes examples
#include <cstddef>
#include <cstdint>

#include <nlohmann/json.hpp>

#include "engine/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto j = nlohmann::json::parse(data, data + size, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded()) return 0;
  try {
    const fretwear::Scene scene = fretwear::parse_scene(j);
    (void)scene.to_json();
  } catch (const fretwear::InputError&) {
  }
  return 0;
}
