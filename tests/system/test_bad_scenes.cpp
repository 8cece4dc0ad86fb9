// Bad input, tried (issue 6): every malformed scene in tests/bad_scenes/ makes `fretwear run` exit with status 2,
// name the problem (the fragment listed in expected.tsv: the key and what is allowed), and write nothing. Cases
// that cannot live in the repository (a 100 MB file, a directory, a missing file, an unwritable output folder)
// are made here.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct Scratch {
  fs::path path = fs::temp_directory_path() / ("fretwear-bad-" + std::to_string(::getpid()));
  Scratch() { fs::create_directories(path); }
  ~Scratch() { fs::remove_all(path); }
};

// Runs `fretwear run scene` inside dir; the exit status, and stdout+stderr in out.
int run_in(const fs::path& dir, const fs::path& scene, std::string& out) {
  const fs::path log = dir.parent_path() / "bad.log";
  const std::string cmd =
      "cd '" + dir.string() + "' && '" FRETWEAR_EXE "' run '" + scene.string() + "' > '" + log.string() + "' 2>&1";
  const int status = std::system(cmd.c_str());
  std::ifstream in(log);
  out.assign(std::istreambuf_iterator<char>(in), {});
  fs::remove(log);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool empty_dir(const fs::path& dir) { return fs::is_empty(dir); }

}  // namespace

TEST_CASE("every malformed scene of the corpus: exit 2, the key and what is allowed named, nothing written") {
  const fs::path corpus = fs::path(FRETWEAR_SOURCE_DIR) / "tests" / "bad_scenes";
  std::ifstream list(corpus / "expected.tsv");
  REQUIRE(list);
  Scratch scratch;
  const fs::path work = scratch.path / "work";
  int n = 0;
  for (std::string line; std::getline(list, line);) {
    if (line.empty() || line[0] == '#') continue;
    const auto tab = line.find('\t');
    REQUIRE(tab != std::string::npos);
    const std::string file = line.substr(0, tab), fragment = line.substr(tab + 1);
    CAPTURE(file);
    fs::create_directories(work);
    std::string out;
    CHECK(run_in(work, corpus / file, out) == 2);
    CHECK_MESSAGE(out.find(fragment) != std::string::npos, "expected \"" << fragment << "\" in: " << out);
    CHECK(empty_dir(work));
    fs::remove_all(work);
    ++n;
  }
  CHECK(n >= 40);
}

TEST_CASE("a 100 MB file, a directory, a missing file, an unwritable output folder: exit 2, nothing written") {
  Scratch scratch;
  const fs::path work = scratch.path / "work";
  fs::create_directories(work);
  std::string out;

  const fs::path big = scratch.path / "big.json";
  {
    std::ofstream f(big, std::ios::binary);
    f << "{\"name\": \"big\", \"pad\": \"";
    const std::string block(1 << 20, 'x');
    for (int i = 0; i < 100; ++i) f << block;
    f << "\"}";
  }
  CHECK(run_in(work, big, out) == 2);
  CHECK(out.find("a scene is at most") != std::string::npos);

  fs::create_directory(scratch.path / "dir.json");
  CHECK(run_in(work, scratch.path / "dir.json", out) == 2);
  CHECK(out.find("is a directory") != std::string::npos);

  CHECK(run_in(work, scratch.path / "missing.json", out) == 2);
  CHECK(out.find("no such file") != std::string::npos);

  const fs::path unwritable = scratch.path / "unwritable.json";
  std::ofstream(unwritable) << R"({"name": "u", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "output": {"dir": "/proc/fretwear/out"}})";
  CHECK(run_in(work, unwritable, out) == 2);
  CHECK(out.find("output.dir") != std::string::npos);
  CHECK(empty_dir(work));
}
