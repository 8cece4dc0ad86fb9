#include "engine/api.hpp"

#include "engine/version.hpp"

namespace fretwear {

nlohmann::json not_converged_summary(const Scene& scene, const std::string& message) {
  return {{"scene", scene.name}, {"version", kVersion}, {"status", "not_converged"}, {"message", message}};
}

}  // namespace fretwear
