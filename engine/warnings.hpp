// Warnings (docs/SCENES.md, "Warnings"): a run that completes but whose results the grid cannot resolve, or that
// misses a closed form it has, or that will take long, says so. Each has a code a script can test and a sentence
// for a person; the program prints them on stderr ("warning: <code>: <message>") and writes them in summary.json.
#pragma once

#include <string>
#include <vector>

namespace fretwear {

struct Scene;
struct RunResult;

struct Warning {
  std::string code;     // e.g. "contact_under_resolved"
  std::string message;  // what is wrong, with the numbers, and what to do
};

// The fewest cells a contact zone, a stick zone and a slip zone must span to be resolved, the share by which a closed
// form may be missed, and the run time past which a warning is given (s). A stick zone's ends are located within a
// cell or so (by the shear's margin to f p), and the wear limit is the complete contact over the stick zones: 16
// cells leave them within a few per cent, as a contact zone's ends. The dissipated energy is off by about 1 % with a
// slip zone of 7 cells (Hertz at Q/fP = 0.02: 15 %, 2 %, 0.9 %, 0.2 % at 1.75, 3.5, 6.9, 13.8 cells, against 131 072
// cells) and by 5 to 7 % with 4 or 5 cells at a rounded punch's sharp corner: 8 cells.
inline constexpr int kMinContactCells = 16;
inline constexpr int kMinStickCells = 16;
inline constexpr int kMinSlipCells = 8;
inline constexpr double kClosedFormTolerance = 0.05;
// contact.p_max changing by more than this share from half the cells (engine/normal_stage.hpp, check_peak) is warned.
inline constexpr double kPeakChangeShare = 0.05;
inline constexpr double kLongRunSeconds = 3600.0;
// A warning of too few cells advises a narrower grid.window only where the window used is at least this many times
// as wide as the least window around the contact (warnings.cpp, resolution_advice): narrowed to it, the same cells are
// at least twice as fine. A window fretwear chooses is that least window already, and zones far apart keep any
// window that holds them wide.
inline constexpr double kNarrowerWindowGain = 2.0;
// The largest change of the SIFs from half the crack's quadrature points to all of them, as a share of the largest
// |K|, before a warning (QuadratureCheck). From 30 to the default 60 points they move by 0.05 to 0.25 % on the
// examples, and by 1.25 % at a sharp punch's edge (paper000_fig6_ab_1, where 60 points are 0.4 % from 240: between
// first and second order).
inline constexpr double kCrackQuadratureShare = 0.02;
// How far a wear run may pass the directly computed asymptote from the grid alone (its stick zones' ends at cell
// boundaries, WearAsymptote::cells_worn_area) before a warning: what one zone aligned to the cells leaves on the
// default grid is below 0.1 % (hertz_wear), so 0.5 % flags a grid whose other zones' ends cost several times that.
inline constexpr double kWearAgreement = 5e-3;
// A worn profile zigzags where three consecutive second differences alternate in sign, each above this share of the
// deepest wear (warnings.cpp, worn_zigzag).
inline constexpr double kZigzagShare = 0.01;
// A load history's dissipated energy may change by this share from half the increments to the scene's before a
// warning (CycleStage::history_energy: first order, so about the error left).
inline constexpr double kHistoryEnergyShare = 0.01;

// What the results of a completed run cannot be trusted for: under-resolved contact and slip zones, a closed form
// missed by more than kClosedFormTolerance (Hertz, the punches, the Mindlin stick zone), a crack longer than the
// window or outside it, a worn area past the directly computed asymptote by more than the grid's share of the
// difference (kWearAgreement) or past the limit of its own grid, a worn profile that zigzags from cell to cell.
std::vector<Warning> result_warnings(const Scene& scene, const RunResult& result);

}  // namespace fretwear
