// An unknown subcommand was reported as "A subcommand is required", without naming the word typed.
#include <doctest/doctest.h>

#include "program.hpp"

using namespace fretwear::test;

TEST_CASE("an unknown subcommand is named, with the commands there are, exit 2") {
  Scratch scratch{"subcommand"};
  for (const std::vector<std::string>& args : {std::vector<std::string>{"frobnicate", "x.json"},
                                                {"-q", "runn", "x.json"}, {"validat"}}) {
    const Outcome o = run_program(scratch.path, args);
    CAPTURE(o.all());
    CHECK(o.status == 2);
    const std::string& word = args[args[0] == "-q" ? 1 : 0];
    CHECK(o.err.find("\"" + word + "\" is not a command") != std::string::npos);
    CHECK(o.err.find("run, validate, defaults, convergence and sweep") != std::string::npos);
  }
  CHECK(run_program(scratch.path, {}).status == 2);  // no command at all: the usage, exit 2
}
