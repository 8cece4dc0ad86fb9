// A stop asked for while a run computes, outside the wear stage's own step boundaries (WearControl::stop_now): the
// stages ask it between their parts, and a yes ends the run with StopRequested. The same call says how far the stage
// has come, so that whoever asks can show progress.
#pragma once

#include <functional>
#include <string>

#include "common/error.hpp"

namespace fretwear {

// Where a stage stands when it asks: its name ("normal", "tangential", "wear", "stress", "crack", "life"), and the
// parts it has done of all it has, counted in `unit` ("map columns", "records", "parts"); total 0 when it does not
// count them.
struct StagePart {
  const char* stage = "";
  double done = 0.0, total = 0.0;
  const char* unit = "";
};

// Asked at each part; true: stop now. May be empty (never stops).
using StopCheck = std::function<bool(const StagePart&)>;

// Throws StopRequested naming the stage when `stop` asks to.
inline void stop_point(const StopCheck& stop, const StagePart& part) {
  if (stop && stop(part)) throw StopRequested(std::string("stopped in the ") + part.stage + " stage");
}
inline void stop_point(const StopCheck& stop, const char* stage) { stop_point(stop, StagePart{stage}); }

// `stop` for a part of a stage that counts its own parts from 0 to its share: it reports them offset by what came
// before (*before, updated by the caller) within the stage's whole count.
inline StopCheck offset_parts(const StopCheck& stop, const double* before, double total) {
  if (!stop) return {};
  return [stop, before, total](const StagePart& p) {
    return stop(StagePart{p.stage, *before + p.done, total, p.unit});
  };
}

}  // namespace fretwear
