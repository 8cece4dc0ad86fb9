#include "wear/wear_law.hpp"

#include "common/error.hpp"

namespace fretwear::wear {

std::string to_string(Law law) { return law == Law::archard ? "archard" : "energy"; }

Law law_from_string(std::string_view word) {
  if (word == "archard") return Law::archard;
  if (word == "energy") return Law::energy;
  throw InputError("\"" + std::string(word) + "\" is not a wear law; use \"archard\" or \"energy\"");
}

}  // namespace fretwear::wear
