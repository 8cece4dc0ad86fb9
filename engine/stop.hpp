// A stop asked for while a run computes, outside the wear stage's own step boundaries (WearControl::stop_now): the
// stages ask it between their parts, and a yes ends the run with StopRequested.
#pragma once

#include <functional>
#include <string>

#include "common/error.hpp"

namespace fretwear {

// Asked with the stage's name ("normal", "tangential", "wear", "stress", "crack", "life"); true: stop now. May be
// empty (never stops).
using StopCheck = std::function<bool(const char* stage)>;

// Throws StopRequested naming `stage` when `stop` asks to.
inline void stop_point(const StopCheck& stop, const char* stage) {
  if (stop && stop(stage)) throw StopRequested(std::string("stopped in the ") + stage + " stage");
}

}  // namespace fretwear
