// A gross-slip wear run without grid.window was refused before it started, told to "widen grid.window" that the user
// never gave: fretwear chose the window for the unworn contact, and in gross slip the contact wears flat and widens
// without limit (the gross-slip example with 2e6 cycles, refused as reaching ±0.6 mm at about 2.66e5 cycles). The
// default window now holds the flat the run wears at its first cycle's rate, kFlatMargin more, and 20 % to spare
// (engine/setup.cpp, sliding_reach; contact/worn_flat.hpp), so `validate` passes it and the run completes with its worn
// contact inside the window. A given window is still refused so (regression_silent_nonsense.cpp). Just past the stick
// limit the wear speeds up as the contact flattens, so the rates are taken again on the flat.
#include <filesystem>
#include <string>

#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "engine/scene.hpp"
#include "engine/setup.hpp"
#include "engine/simulation.hpp"
#include "program.hpp"
#include "worn_span.hpp"

using namespace fretwear;
using namespace fretwear::test;

namespace {

// The gross-slip example (R = 6 mm, P = 18.5 kN/m, f = 0.9, δ = 25 µm) on 256 cells without a window; `load` replaces
// its load's control and δ.
std::string gross_slip(const std::string& cycles, double pad_fraction,
                       const std::string& load = R"("control": "displacement", "delta": 25e-6)") {
  return R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}}, "profile": {"type": "cylinder", "R": 6e-3},
    "friction": 0.9, "load": {"P": 18500, )" +
         load + R"(}, "grid": {"cells": 256, "reference_depth": 6e-3}, "output": {"plots": false},
    "effects": {"wear": {"k": 5e-14, "pad_fraction": )" +
         std::to_string(pad_fraction) + R"(, "cycles": )" + cycles + "}}}";
}

// The run's worn contact (where either body wore, at the last record) ends inside the window with between a tenth
// and 0.35 of its half-width to spare each side: held, and not by a window much wider than the flat it wore. The
// window is fretwear's, widened for the flat beyond the unworn contact's (by more than `widened` times);
// `validate` passes the scene. `coarse`: the unworn contact spans too few of the run's cells.
void holds_its_worn_flat(const std::string& text, double widened = 1.5, bool coarse = true) {
  Scratch scratch{"flat_window"};
  write_file(scratch.path / "s.json", text);
  const Outcome valid = run_program(scratch.path, {"validate", "s.json"});
  CAPTURE(valid.all());
  CHECK(valid.status == 0);

  const Scene scene = parse_scene_text(text);
  const Model model = make_model(scene);
  CAPTURE(model.window.method);
  CHECK(model.window.method.ends_with("+worn_flat"));
  Scene unworn = scene;
  unworn.wear.reset();
  unworn.blocks.clear();
  unworn.control = LoadControl::force, unworn.delta.reset();
  const Grid old = make_model(unworn).grid;
  CHECK(model.grid.x_max > widened * old.x_max);

  const RunResult r = Simulation(scene).run();
  REQUIRE(r.wear);
  REQUIRE(r.wear->cycles_reached == scene.wear->cycles);
  const Grid& grid = model.grid;
  const auto span = test::worn_span(grid, r.wear->records.back().w);
  REQUIRE(span);
  const auto [left, right] = *span;
  const double half = 0.5 * (grid.x_max - grid.x_min);
  CAPTURE(left);
  CAPTURE(right);
  CAPTURE(grid.x_min);
  CAPTURE(grid.x_max);
  CHECK((left - grid.x_min) / half >= 0.1);
  CHECK((grid.x_max - right) / half >= 0.1);
  CHECK((left - grid.x_min) / half <= 0.35);
  CHECK((grid.x_max - right) / half <= 0.35);
  // The unworn contact spans a few of these cells; the warning says so, and does not advise the narrower window that
  // would stop the run.
  bool resolution = false;
  for (const Warning& w : r.warnings) {
    if (w.code != "contact_under_resolved") continue;
    resolution = true;
    CHECK(w.message.find("widened to hold the worn contact") != std::string::npos);
    CHECK(w.message.find("narrower grid.window around") == std::string::npos);
  }
  CHECK(resolution == coarse);
}

}  // namespace

TEST_CASE("a gross-slip wear run without a window gets one that holds its worn flat") {
  holds_its_worn_flat(gross_slip("2e6", 1.0));
}

TEST_CASE("a gross-slip wear run of both bodies without a window holds the specimen's scar too") {
  // Each body in its own frame: the specimen's scar reaches the sliding amplitude (about 24 µm) beyond the contact.
  holds_its_worn_flat(gross_slip("2e6", 0.5));
}

TEST_CASE("gross-slip wear under load blocks without a window holds the flat all its sliding blocks wear") {
  // A partial-slip block (δ = 0.5 µm, wearing towards a limit) and two sliding ones of 10^6 cycles each: the second
  // starts where the first left the flat.
  holds_its_worn_flat(gross_slip("2.001e6", 1.0,
                                 R"("blocks": [{"delta": 0.5e-6, "cycles": 1000}, {"delta": 25e-6, "cycles": 1e6},
                                    {"delta": 25e-6, "cycles": 1e6}])"));
}

TEST_CASE("a gross-slip wear run whose wear speeds up as it flattens gets a window that holds it") {
  // A rounded wedge (2°, R = 10 mm) at δ = 2.25 µm, 2.5 % past its stick limit of 2.196 µm: the first cycle slides
  // 54 nm each way, and as the apex wears flat the stick limit falls and more of δ slides. Sized by the first cycle's
  // rate alone, the window was reached and the run stopped with exit 2; the rates taken again on the flat hold it.
  holds_its_worn_flat(R"({"name": "s", "materials": {"both": {"E": 2e11, "nu": 0.3}},
    "profile": {"type": "rounded_wedge", "angle_deg": 2, "R": 0.01}, "friction": 0.9,
    "load": {"P": 1e5, "control": "displacement", "delta": 2.2503e-6}, "grid": {"cells": 128},
    "output": {"plots": false}, "effects": {"wear": {"k": 8.92e-15, "pad_fraction": 1.0, "cycles": 288897}}})",
                      1.0, false);
}

TEST_CASE("a gross-slip wear run's window is sized with the run's own displacement datum") {
  // A wedge (3°) of steel on aluminium at δ = 2.34 µm: the first cycle slides 0.96 µm each way, and as the apex
  // wears flat the wear speeds up 1.9 times on average over 1.09e6 cycles. The run keeps the datum of the unworn
  // contact (10 of its half-widths deep); a trial on the flat with its datum 10 of the flat's half-widths deep took
  // it more compliant, put the rate at 1.15 times the first, and the run reached the window's end at 1.05e6 cycles.
  holds_its_worn_flat(R"({"name": "s", "materials": {"pad": {"E": 2e11, "nu": 0.3}, "specimen": {"E": 7.1e10,
    "nu": 0.33}}, "profile": {"type": "wedge", "angle_deg": 3}, "friction": 0.9,
    "load": {"P": 3e4, "control": "displacement", "delta": 2.3393e-6}, "grid": {"cells": 128},
    "output": {"plots": false}, "effects": {"wear": {"k": 1.4151e-14, "pad_fraction": 1.0, "cycles": 1092689}}})");
}

TEST_CASE("a gross-slip wear scene too strained for half-plane elasticity is refused whatever window it gets") {
  // A sharp wedge (8°) of steel on titanium under 100 kN/m: the mean contact strain is 0.07, past the 0.05 allowed.
  // The window widened for the worn flat (±15 mm, a thousand times the contact) left the contact two cells, whose
  // width is the grid's, and the strain measured over them passed; it is now measured on the unworn contact's window.
  Scratch scratch{"strained"};
  write_file(scratch.path / "s.json", R"({"name": "s", "materials": {"pad": {"E": 2e11, "nu": 0.3},
    "specimen": {"E": 1.1e11, "nu": 0.34}}, "profile": {"type": "wedge", "angle_deg": 8}, "friction": 0.6,
    "load": {"P": 1e5, "control": "displacement", "delta": 6.755e-5}, "grid": {"cells": 256},
    "output": {"plots": false}, "effects": {"wear": {"k": 1.79e-13, "pad_fraction": 1.0, "cycles": 4275633}}})");
  for (const char* command : {"validate", "run"}) {
    const Outcome o = run_program(scratch.path, {command, "s.json"});
    CAPTURE(o.all());
    CHECK(o.status == 2);
    CHECK(o.err.find("load.P: the mean contact pressure") != std::string::npos);
    CHECK(!std::filesystem::exists(scratch.path / "output"));
  }
}
