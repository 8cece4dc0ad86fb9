// Bad input, tried: every malformed scene in tests/bad_scenes/ makes `fretwear run` exit with status 2, name the
// problem (the fragment listed in expected.tsv: the key and what is allowed), and write nothing. Cases that cannot
// live in the repository (a 100 MB file, a directory, a missing file, an unwritable output folder) are made here.
#include <filesystem>
#include <fstream>
#include <string>

#include <doctest/doctest.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

TEST_CASE("every malformed scene of the corpus: exit 2, the key and what is allowed named, nothing written") {
  const fs::path corpus = fs::path(FRETWEAR_SOURCE_DIR) / "tests" / "bad_scenes";
  std::ifstream list(corpus / "expected.tsv");
  REQUIRE(list);
  Scratch s;
  const Snapshot before = s.snapshot();
  int n = 0;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    const std::string file = line.substr(0, tab), fragment = line.substr(tab + 1);
    CAPTURE(file);
    const Outcome r = s.fretwear({"run", (corpus / file).string()});
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    CHECK_MESSAGE(r.all().find(fragment) != std::string::npos, "expected \"" << fragment << "\" in: " << r.all());
    CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "wrote: " << join(changes(before, s.snapshot())));
    ++n;
  }
  CHECK(n >= 40);
}

TEST_CASE("a 100 MB file, a directory, a missing file, an unwritable output folder: exit 2, nothing written") {
  Scratch s;
  // The scenes lie outside the tree (the program only reads them), so that its snapshot does not hold 100 MB.
  const fs::path big = s.root / "big.json";
  {
    std::ofstream f(big, std::ios::binary);
    f << "{\"name\": \"big\", \"pad\": \"";
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 100; ++i) f << block;
    f << "\"}";
  }
  fs::create_directory(s.root / "dir.json");
  write_file(s.root / "unwritable.json", R"({"name": "u", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "output": {"dir": "/proc/fretwear/out"}})");
  const Snapshot before = s.snapshot();

  for (const auto& [scene, said] : {std::pair{"big.json", "a scene is at most"}, {"dir.json", "is a directory"},
                                    {"missing.json", "no such file"}, {"unwritable.json", "output.dir"}}) {
    CAPTURE(scene);
    const Outcome r = s.fretwear({"run", (s.root / scene).string()});
    CHECK_MESSAGE(r.exited(kInvalid), r.describe());
    CHECK(r.all().find(said) != std::string::npos);
  }
  CHECK_MESSAGE(changes(before, s.snapshot()).empty(), "wrote: " << join(changes(before, s.snapshot())));
}
