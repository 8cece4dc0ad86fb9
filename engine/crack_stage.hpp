// The crack stage: the stress intensity factors of a crack at the contact (contact/crack_solver.hpp) at the top and
// the bottom of the load cycle, for the initial contact and every recorded wear state.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "contact/crack_solver.hpp"
#include "contact/grid.hpp"
#include "engine/cycle_stage.hpp"
#include "engine/folder.hpp"
#include "engine/normal_stage.hpp"
#include "engine/scene.hpp"
#include "engine/stop.hpp"
#include "engine/wear_stage.hpp"

namespace fretwear {

struct SifSet {
  std::string phase;
  double cycles = 0.0;
  CrackResult result;
};

// SIFs at x_c for each phase.
std::vector<SifSet> crack_sifs(const Grid& grid, const std::vector<Phase>& phases, double x_c,
                               const CrackEffect& effect, double cycles);

// Where the crack is (m): an end of the contact under P alone, or the position given.
double crack_position(const CrackEffect& effect, const NormalResult& normal);

// The stage: the SIFs at crack_position() for the unworn contact, or for every wear record; `stop` is asked before
// each state's and after the last, with the records done (stop_point()).
std::vector<SifSet> run_crack(const Scene& scene, const Model& model, const NormalResult& normal,
                              const CycleStage* cycle, const WearStage* wear, const StopCheck& stop = {});

// How far the SIFs of the last state move from half the scene's quadrature points to all of them (from all of them
// to twice as many, for 2 or 3 points): the largest change of K_I or K_II over the lengths and phases, as a share of
// the largest |K| there, and whether a length opens or closes between the two. The SIFs converge at first to second
// order in the points near a contact's edge, so the change bounds about the error left at the scene's points. Empty
// without SIFs; `settled` false when the face contact does not settle on the other points (no estimate).
struct QuadratureCheck {
  int points = 0, other = 0;
  bool settled = true;
  double change = 0.0;     // share of the largest |K|
  bool opens_or_closes = false;
  double at_l = 0.0;       // the length where the change is largest (m)
  std::string phase;       // and its phase
};
std::optional<QuadratureCheck> quadrature_check(const Scene& scene, const Model& model, const NormalResult& normal,
                                                const CycleStage* cycle, const WearStage* wear,
                                                const std::vector<SifSet>& sifs);

// Its part of summary.json: "crack" (the SIFs of the last state, one per length, at the top and the bottom).
nlohmann::json summarise_crack(const Scene& scene, const std::vector<SifSet>& sifs, double x);

// sif.csv and, with plots, crack.gp with K_I and K_II against the crack length.
void write_crack(const Scene& scene, const std::vector<SifSet>& sifs, double x, bool worn, OutputFolder& out,
                 Written& written);

}  // namespace fretwear
