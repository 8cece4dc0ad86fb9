// Between Python objects and JSON: a scene given as a dict, and the summaries and scenes handed back as dicts.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace fretwear::python {

// A scene as JSON from nested dicts (str keys), lists, tuples, str, bool, int, float and None, and numpy's scalars.
// Anything else, a key that is not a str, an int beyond 64 bits or nesting deeper than kMaxSceneDepth is a problem
// "path: what is wrong; what is allowed", appended to `problems`, as the scene parser words its own. Such a value is
// null in the JSON returned, and its path ("load.P", "(top)") is appended to `nulled`; a key that is not a str is
// left out.
nlohmann::json to_json(pybind11::handle value, std::vector<std::string>& problems, std::vector<std::string>& nulled);

// JSON as Python objects: objects as dicts, arrays as lists. A float that is not finite becomes None, as summary.json
// writes it, so that a summary in memory equals the file read back with json.load.
pybind11::object to_python(const nlohmann::json& j);

}  // namespace fretwear::python
