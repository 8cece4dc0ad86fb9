// Hostile scenes: bytes no scene should hold, numbers JSON barely holds, magnitudes no contact has. Whatever the
// file, `fretwear run` ends with 0 (finite results), 2 (the problem named by its JSON path, nothing written) or,
// where the contract allows it, 3; never 1 and never a signal; `validate` agrees with it; nothing of the user's
// is touched. Each table row is one case (check_scene in program.hpp holds it to all of that).
#include <string>
#include <vector>

#include <doctest/doctest.h>
#include <sys/stat.h>

#include "system/program.hpp"

using namespace fretwear::system_test;

namespace {

// `n` arrays nested in one another, and `n` objects ({"a": {"a": ... 1}}).
std::string arrays(int n) { return std::string(std::size_t(n), '[') + std::string(std::size_t(n), ']'); }
std::string objects(int n) {
  std::string s;
  for (int i = 0; i < n; ++i) s += "{\"a\": ";
  return s + "1" + std::string(std::size_t(n), '}');
}

// The text as UTF-16 with its byte order mark (the scene is ASCII, so each character is one code unit).
std::string utf16(const std::string& ascii, bool little_endian) {
  std::string s = little_endian ? "\xff\xfe" : "\xfe\xff";
  for (char c : ascii) s += little_endian ? std::string{c, '\0'} : std::string{'\0', c};
  return s;
}

// A scene whose `name` value is the given raw bytes (between the quotes), the rest the base.
std::string named(const std::string& raw) { return with(base_scene(), {{"name", "\"" + raw + "\""}}); }

// What a message names for a problem of the whole file: the file, or the top of the document.
const std::string kWholeFile = "s.json|(top)";

const std::string kTable = R"({"type": "table", "x": [-1e-3, 0, 1e-3], "h": [1e-5, 0, 1e-5]})";
const std::string kHistory = R"([[0, 1e5, 2e4, 0], [1, 1e5, -2e4, 0], [2, 1e5, 2e4, 0]])";

// The base as written by hand, for edits below the level of JSON values (a key twice, a byte anywhere).
const std::string kBaseText = R"({"name": "h", "materials": {"both": {"E": 2e11, "nu": 0.3}},
  "profile": {"type": "cylinder", "R": 0.01}, "load": {"P": 1e5}, "grid": {"cells": 256}})";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  REQUIRE(at != std::string::npos);
  return text.replace(at, from.size(), to);
}

}  // namespace

TEST_CASE("numbers past a double: exit 2 naming the path, never an internal error") {
  const json base = base_scene(), cycle = cycle_scene(), wear = wear_scene();
  json history = cycle;  // the cycle given as a history of (t, P, Q, σ_bulk) instead of Q
  history["load"].erase("Q");
  const std::vector<SceneCase> cases = {
      {"1e309 as the load", with(base, {{"load.P", "1e309"}}), {2}, "load.P"},
      {"-1e309 as the load", with(base, {{"load.P", "-1e309"}}), {2}, "load.P"},
      {"1e309 as a modulus", with(base, {{"materials.both.E", "1e309"}}), {2}, "materials.both.E"},
      {"1e309 as Poisson's ratio", with(base, {{"materials.both.nu", "1e309"}}), {2}, "materials.both.nu"},
      {"1e309 as the radius", with(base, {{"profile.R", "1e309"}}), {2}, "profile.R"},
      {"1e309 in a table of heights",
       with(base, {{"profile", replaced(kTable, "\"h\": [1e-5, 0, 1e-5]", "\"h\": [1e-5, 0, 1e309]")}}), {2},
       "profile.h"},
      {"1e309 in a table of positions",
       with(base, {{"profile", replaced(kTable, "\"x\": [-1e-3, 0, 1e-3]", "\"x\": [-1e-3, 0, 1e309]")}}), {2},
       "profile.x"},
      {"1e309 as a tangential load in a history",
       with(history, {{"load.history", replaced(kHistory, "-2e4", "1e309")}}), {2},
       "load.history"},
      {"1e309 as a time in a history",
       with(history, {{"load.history", replaced(kHistory, "[2, ", "[1e309, ")}}), {2},
       "load.history"},
      {"1e309 as the friction coefficient", with(cycle, {{"friction", "1e309"}}), {2}, "friction"},
      {"-1e309 as a window bound", with(base, {{"grid.window", "[-1e309, 1e-3]"}}), {2}, "grid.window"},
      {"1e309 wear cycles", with(wear, {{"effects.wear.cycles", "1e309"}}), {2}, "effects.wear.cycles"},
      {"a twenty-digit exponent as the load", with(base, {{"load.P", "1e99999999999999999999"}}), {2}, "load.P"},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("numbers at the edges of JSON: -0, underflow, huge integers") {
  const json base = base_scene();
  const std::vector<SceneCase> cases = {
      {"-0 as the load", with(base, {{"load.P", "-0"}}), {2}, "load.P"},
      {"-0.0 as the modulus", with(base, {{"materials.both.E", "-0.0"}}), {2}, "materials.both.E"},
      {"-0 as Poisson's ratio (a valid 0)", with(base, {{"materials.both.nu", "-0"}}), {0, 2}, "materials.both.nu"},
      {"1e-400 as the load (underflows to 0)", with(base, {{"load.P", "1e-400"}}), {2}, "load.P"},
      {"1e-400 as the modulus", with(base, {{"materials.both.E", "1e-400"}}), {2}, "materials.both.E"},
      {"a 400-digit fraction as the load", with(base, {{"load.P", "0." + std::string(399, '0') + "1"}}), {2},
       "load.P"},
      {"123456789012345678901234567890 as the load", with(base, {{"load.P", "123456789012345678901234567890"}}),
       {2}, "load.P"},
      {"-123456789012345678901234567890 as the load", with(base, {{"load.P", "-123456789012345678901234567890"}}),
       {2}, "load.P"},
      {"a 400-digit integer as the load", with(base, {{"load.P", "1" + std::string(400, '0')}}), {2}, "load.P"},
      {"123456789012345678901234567890 cells", with(base, {{"grid.cells", "123456789012345678901234567890"}}), {2},
       "grid.cells"},
      {"2^64 cells", with(base, {{"grid.cells", "18446744073709551616"}}), {2}, "grid.cells"},
      {"2^63 - 1 cells", with(base, {{"grid.cells", "9223372036854775807"}}), {2}, "grid.cells"},
      {"-2^63 cells", with(base, {{"grid.cells", "-9223372036854775808"}}), {2}, "grid.cells"},
      {"2^32 + 256 cells", with(base, {{"grid.cells", "4294967552"}}), {2}, "grid.cells"},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("duplicate keys: exit 2 naming the key, at the top and nested") {
  const std::vector<SceneCase> cases = {
      {"the name twice", replaced(kBaseText, "\"name\": \"h\"", "\"name\": \"h\", \"name\": \"g\""), {2}, "name"},
      {"the load object twice",
       replaced(kBaseText, "\"load\": {\"P\": 1e5}", "\"load\": {\"P\": 1e5}, \"load\": {\"P\": 2e5}"), {2}, "load"},
      {"a modulus twice", replaced(kBaseText, "\"E\": 2e11", "\"E\": 2e11, \"E\": 1e11"), {2}, "materials.both.E"},
      {"a key twice with the same value", replaced(kBaseText, "\"R\": 0.01", "\"R\": 0.01, \"R\": 0.01"), {2},
       "profile.R"},
      {"a wear coefficient twice",
       with(wear_scene(), {{"effects.wear", R"({"k": 1e-15, "cycles": 1e4, "k": 1e-12})"}}), {2}, "effects.wear.k"},
      {"a key twice in a profile of a sum",
       with(base_scene(), {{"profile", R"({"type": "sum", "terms": [{"type": "cylinder", "R": 0.01, "R": 0.02}]})"}}),
       {2}, "profile.terms[0].R"},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("deep nesting: 10 000 levels of arrays and objects, exit 2") {
  const json base = base_scene();
  const std::vector<SceneCase> cases = {
      {"10 000 nested arrays as the scene", arrays(10000), {2}, kWholeFile},
      {"10 000 nested objects as the scene", objects(10000), {2}, kWholeFile + "|a:"},
      {"100 000 nested arrays as the scene", arrays(100000), {2}, kWholeFile},
      {"10 000 unclosed arrays", std::string(10000, '['), {2}, kWholeFile},
      {"10 000 nested arrays as the load", with(base, {{"load.P", arrays(10000)}}), {2}, "load.P"},
      {"10 000 nested objects as the load", with(base, {{"load.P", objects(10000)}}), {2}, "load.P"},
      {"10 000 nested arrays under an unknown key", with(base, {{"zz", arrays(10000)}}), {2}, "zz"},
      {"10 000 nested objects as the effects", with(base, {{"effects", objects(10000)}}), {2}, "effects"},
      {"10 000 nested arrays as the window", with(base, {{"grid.window", arrays(10000)}}), {2}, "grid.window"},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("bytes that are not a UTF-8 scene: exit 2 naming the file or the path") {
  const std::string ok = base_scene().dump();
  const std::vector<SceneCase> cases = {
      {"an invalid UTF-8 byte in the name", named("h\xff"), {2}, "name"},
      {"an overlong UTF-8 encoding in the name", named("h\xc0\xaf"), {2}, "name"},
      {"an encoded surrogate (CESU-8) in the name", named("h\xed\xa0\x80"), {2}, "name"},
      {"a lone surrogate escape in the name", named("h\\ud800"), {2}, "name"},
      {"a UTF-8 sequence cut short at the end of the file", ok.substr(0, ok.size() - 1) + "\xe2\x82", {2},
       kWholeFile},
      {"a UTF-16 file (little-endian) with its BOM", utf16(ok, true), {2}, kWholeFile},
      {"a UTF-16 file (big-endian) with its BOM", utf16(ok, false), {2}, kWholeFile},
      {"a UTF-32 file with its BOM", std::string("\xff\xfe\0\0{\0\0\0}\0\0\0", 12), {2}, kWholeFile},
      {"a UTF-8 BOM before a valid scene (accepted or refused)", "\xef\xbb\xbf" + ok, {0, 2}, kWholeFile},
      {"a UTF-8 BOM alone", "\xef\xbb\xbf", {2}, kWholeFile},
      {"a NUL byte in the name", named(std::string("h\0g", 3)), {2}, "name"},
      {"a NUL byte after the scene", ok + std::string(1, '\0'), {2}, kWholeFile},
      {"a NUL byte before the scene", std::string(1, '\0') + ok, {2}, kWholeFile},
      {"a NUL byte between two keys", replaced(ok, ",", std::string(",\0", 2)), {2}, kWholeFile},
      {"an empty file", "", {2}, kWholeFile},
      {"only whitespace", " \n\t\r\n   \n", {2}, kWholeFile},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("huge strings: exit 2 naming the path, in a message of sane size") {
  const json base = base_scene();
  const std::string mb(1 << 20, 'x');
  const std::vector<SceneCase> cases = {
      {"a 1 MB name", named(mb), {2}, "name"},
      {"a 1 MB profile type", with(base, {{"profile.type", "\"" + mb + "\""}}), {2}, "profile.type"},
      {"a 1 MB unknown key", with(base, {{mb, "1"}}), {2}, "unknown key"},
      {"a 15 MB string under an unknown key", with(base, {{"note", "\"" + std::string(15u << 20, 'x') + "\""}}), {2},
       "note"},
      {"a 1 MB output folder", with(base, {{"output.dir", "\"" + mb + "\""}}), {2}, "output.dir"},
      {"a name of 4096 slashes", named(std::string(4096, '/')), {2}, "name"},
  };
  for (const auto& c : cases) check_scene(c);
  // Echoing a megabyte back helps no one; the contract does not say so, hence a warning, not a failure.
  Scratch s;
  s.write("s.json", named(mb));
  const Outcome r = s.fretwear({"run", "s.json"});
  WARN_MESSAGE(r.err.size() < 10000, "the message for a 1 MB name is " << r.err.size() << " bytes");
}

TEST_CASE("absurd magnitudes: refused naming the key, or run to finite results") {
  const json base = base_scene(), cycle = cycle_scene(), wear = wear_scene();
  json two_bodies = base;
  two_bodies["materials"] = {{"pad", {{"E", 2e11}, {"nu", 0.3}}}, {"specimen", {{"E", 2e11}, {"nu", 0.3}}}};
  const std::vector<SceneCase> cases = {
      {"a window of ±1e200 m", with(base, {{"grid.window", "[-1e200, 1e200]"}}), {0, 2}, "grid.window"},
      {"a window of ±1e30 m", with(base, {{"grid.window", "[-1e30, 1e30]"}}), {0, 2}, "grid.window"},
      {"a window from -1e200 m to 1 mm", with(base, {{"grid.window", "[-1e200, 1e-3]"}}), {0, 2}, "grid.window"},
      {"a window of ±1e-300 m", with(base, {{"grid.window", "[-1e-300, 1e-300]"}}), {0, 2}, "grid.window"},
      {"a window of ±1e200 m on 16 cells", with(base, {{"grid.window", "[-1e200, 1e200]"}, {"grid.cells", "16"}}),
       {0, 2}, "grid.window"},
      {"a radius of 1e-308 m", with(base, {{"profile.R", "1e-308"}}), {0, 2}, "profile.R"},
      {"a radius of 1e-12 m", with(base, {{"profile.R", "1e-12"}}), {0, 2}, "profile.R"},
      {"a radius of 1e12 m", with(base, {{"profile.R", "1e12"}}), {0, 2}, "profile.R"},
      {"a modulus of 1e-310 Pa (denormal)", with(base, {{"materials.both.E", "1e-310"}}), {0, 2}, "materials.both.E"},
      {"a modulus of 1e30 Pa", with(base, {{"materials.both.E", "1e30"}}), {0, 2}, "materials.both.E"},
      {"a pad of 1e-310 Pa on a steel specimen", with(two_bodies, {{"materials.pad.E", "1e-310"}}), {0, 2},
       "materials.pad.E"},
      {"Poisson's ratio 0.4999999999", with(base, {{"materials.both.nu", "0.4999999999"}}), {0, 2},
       "materials.both.nu"},
      {"a load of 1e-300 N/m", with(base, {{"load.P", "1e-300"}}), {0, 2}, "load.P"},
      {"a load of 1e300 N/m", with(base, {{"load.P", "1e300"}}), {0, 2}, "load.P"},
      {"Q/fP = 1e-300", with(cycle, {{"load.Q.ratio", "1e-300"}}), {0, 2}, "load.Q.ratio"},
      {"Q/fP = 1e300", with(cycle, {{"load.Q.ratio", "1e300"}}), {0, 2}, "load.Q.ratio"},
      {"a tangential amplitude of 1e-300 N/m", with(cycle, {{"load.Q", R"({"amplitude": 1e-300})"}}), {0, 2},
       "load.Q.amplitude"},
      {"a tangential amplitude of 1e300 N/m", with(cycle, {{"load.Q", R"({"amplitude": 1e300})"}}), {0, 2},
       "load.Q.amplitude"},
      {"a bulk stress of 1e300 Pa", with(cycle, {{"load.bulk_stress", R"({"amplitude": 1e300})"}}), {0, 2},
       "load.bulk_stress.amplitude"},
      {"a friction coefficient of 1e-300", with(cycle, {{"friction", "1e-300"}}), {0, 2}, "friction"},
      {"a reference depth of 1e300 m", with(cycle, {{"grid.reference_depth", "1e300"}}), {0, 2},
       "grid.reference_depth"},
      {"a reference depth of 1e-300 m", with(cycle, {{"grid.reference_depth", "1e-300"}}), {0, 2},
       "grid.reference_depth"},
      {"a crack a metre long", with(cycle, {{"effects.crack", R"({"lengths": [1.0]})"}}), {0, 2},
       "effects.crack.lengths"},
      {"a crack a metre outside the window", with(cycle, {{"effects.crack", R"({"lengths": [1e-5], "at": 1.0})"}}),
       {0, 2}, "effects.crack.at"},
      {"a crack a metre outside on the other side",
       with(cycle, {{"effects.crack", R"({"lengths": [1e-5], "at": -1.0})"}}), {0, 2}, "effects.crack.at"},
      {"a crack 1e-300 m long", with(cycle, {{"effects.crack", R"({"lengths": [1e-300]})"}}), {0, 2},
       "effects.crack.lengths"},
      {"a crack at 1e200 m", with(cycle, {{"effects.crack", R"({"lengths": [1e-5], "at": 1e200})"}}), {0, 2},
       "effects.crack.at"},
      {"1e12 wear cycles", with(wear, {{"effects.wear.cycles", "1e12"}}), {0, 2}, "effects.wear.cycles"},
      {"a wear coefficient of 1e-300 1/Pa", with(wear, {{"effects.wear.k", "1e-300"}}), {0, 2}, "effects.wear.k"},
      {"a wavy profile of amplitude 1e200 m",
       with(base, {{"profile", R"({"type": "wavy", "amplitude": 1e200, "wavelength": 1e-3})"},
                   {"grid.window", "[-5e-4, 5e-4]"}}),
       {0, 2}, "profile.amplitude"},
      {"a wavy profile of wavelength 1e-300 m",
       with(base, {{"profile", R"({"type": "wavy", "amplitude": 1e-6, "wavelength": 1e-300})"},
                   {"grid.window", "[-5e-4, 5e-4]"}}),
       {0, 2}, "profile.wavelength"},
      {"16 cells, the fewest", with(base, {{"grid.cells", "16"}}), {0, 2}, "grid.cells"},
      {"15 cells, one too few", with(base, {{"grid.cells", "15"}}), {2}, "grid.cells"},
      {"1048577 cells, one too many", with(base, {{"grid.cells", "1048577"}}), {2}, "grid.cells"},
  };
  for (const auto& c : cases) check_scene(c);
}

TEST_CASE("the most cells a grid may have: runs or is refused naming grid.cells") {
  // The upper bound of grid.cells, 1048576: about 15 s on one core, so a case of its own (ctest runs it beside
  // the others).
  check_scene({"1048576 cells, the most", with(base_scene(), {{"grid.cells", "1048576"}}), {0, 2}, "grid.cells"});
}

// ---------------------------------------------------------------------------------------------------------------
// The command line

namespace {

// A command line: the arguments, what it may exit with, and words stderr must hold. Runs in a tree holding a valid
// scene s.json, a FIFO fifo.json and an empty file empty.json.
struct CommandCase {
  std::string label;
  std::vector<std::string> args;
  Exits exits;
  std::string fragment;
};

void check_command(const CommandCase& c) {
  INFO("case: " << c.label);
  Scratch s;
  s.write("s.json", base_scene().dump());
  s.write("empty.json", "");
  REQUIRE(::mkfifo((s.work / "fifo.json").c_str(), 0644) == 0);
  const Snapshot before = s.snapshot();
  const Outcome r = s.fretwear(c.args, {}, 20.0);
  const Snapshot after = s.snapshot();
  CHECK_MESSAGE(!r.crashed(), r.describe());
  CHECK_MESSAGE(c.exits.has(r.status), "want exit " << c.exits.text() << ", got " << r.describe());
  if (r.exited(kInvalid)) {
    CHECK_MESSAGE(names(r.err, c.fragment), "the message should name \"" << c.fragment << "\": " << r.describe());
    CHECK_MESSAGE(changes(before, after).empty(), "refused, but wrote: " << join(changes(before, after)));
  }
  std::vector<std::string> touched;
  for (const auto& line : changes(before, after))
    if (line.rfind("new ", 0) != 0) touched.push_back(line);
  CHECK_MESSAGE(touched.empty(), "the user's files were touched: " << join(touched));
  CHECK_MESSAGE(leftovers(before, after).empty(), "left behind: " << join(leftovers(before, after)));
}

}  // namespace

TEST_CASE("an unknown subcommand or option exits 2 and names the word") {
  const std::vector<CommandCase> cases = {
      {"an unknown subcommand with a scene", {"frobnicate", "s.json"}, {2}, "frobnicate"},
      {"an unknown subcommand alone", {"frobnicate"}, {2}, "frobnicate"},
      {"an unknown option", {"--frobnicate"}, {2}, "frobnicate"},
      {"an unknown option of run", {"run", "s.json", "--frobnicate"}, {2}, "frobnicate"},
      {"no subcommand", {}, {2}, ""},
      {"run without a scene", {"run"}, {2}, "scene"},
      {"run with two scenes", {"run", "s.json", "s.json"}, {2}, "s.json"},
  };
  for (const auto& c : cases) check_command(c);
}

TEST_CASE("hostile scene paths and option values: exit 2, never 1") {
  const std::vector<CommandCase> cases = {
      {"a missing scene", {"run", "missing.json"}, {2}, "missing.json"},
      {"an empty path", {"run", ""}, {2}, ""},
      {"a folder as the scene", {"run", "keep"}, {2}, "keep"},
      {"a FIFO as the scene (must not wait for a writer)", {"run", "fifo.json"}, {2}, "fifo.json"},
      {"/dev/zero as the scene (endless)", {"run", "/dev/zero"}, {2}, "/dev/zero"},
      {"/dev/null as the scene (empty)", {"run", "/dev/null"}, {2}, "/dev/null"},
      {"an empty scene file", {"validate", "empty.json"}, {2}, "empty.json"},
      {"a path of 100 000 characters", {"run", std::string(100000, 'a') + ".json"}, {2}, ""},
      {"a negative checkpoint interval", {"run", "s.json", "--checkpoint-every", "-1"}, {2}, "checkpoint-every"},
      {"a checkpoint interval of nan", {"run", "s.json", "--checkpoint-every", "nan"}, {2}, "checkpoint-every"},
      {"a convergence study from 1e9 cells", {"convergence", "s.json", "--from", "1000000000"}, {2}, "--from"},
      {"a convergence study from 64 down to 32", {"convergence", "s.json", "--from", "64", "--to", "32"}, {0, 2},
       "--to"},
      {"a sweep without --vary", {"sweep", "s.json"}, {2}, "--vary"},
      {"a sweep varying a key without values", {"sweep", "s.json", "--vary", "load.P"}, {2}, "load.P"},
      {"a sweep varying nothing", {"sweep", "s.json", "--vary", "=1"}, {2}, "=1"},
      {"a sweep with an empty value", {"sweep", "s.json", "--vary", "load.P=1e5,,2e5"}, {2}, "load.P"},
      {"a sweep varying an unknown key", {"sweep", "s.json", "--vary", "nokey=1,2"}, {2}, "nokey"},
      {"a sweep to 1e309", {"sweep", "s.json", "--vary", "load.P=1e5,1e309"}, {2}, "load.P"},
      {"a sweep on 0 cores", {"sweep", "s.json", "--vary", "load.P=1e5", "--jobs", "0"}, {2}, "jobs"},
      {"a sweep on a million cores", {"sweep", "s.json", "--vary", "load.P=1e5", "--jobs", "1000000"}, {2}, "jobs"},
  };
  for (const auto& c : cases) check_command(c);
}
