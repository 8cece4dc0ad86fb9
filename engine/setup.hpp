// What every stage of a scene shares, resolved once before any stage runs (docs/METHODS.md, "The stage layer"):
// the bodies, the profile, and the grid over the window chosen for them, with the initial gap and the kernel.
#pragma once

#include <memory>
#include <vector>

#include "contact/elastic_pair.hpp"
#include "contact/grid.hpp"
#include "contact/half_plane_kernel.hpp"
#include "contact/profile.hpp"
#include "contact/window.hpp"
#include "engine/scene.hpp"

namespace fretwear {

// The bodies, the profile and the discretisation of a scene: what every stage shares.
struct Model {
  ElasticPair pair;
  Profile profile;
  Grid grid;
  WindowChoice window;
  std::vector<double> g0;  // initial gap per cell (m)
  std::unique_ptr<HalfPlaneKernel> kernel;
};

// The model of a scene on `cells` cells (the scene's own when 0).
Model make_model(const Scene& scene, int cells = 0);

}  // namespace fretwear
