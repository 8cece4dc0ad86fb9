#include "python/convert.hpp"

#include <cmath>
#include <limits>
#include <optional>

#include <fmt/format.h>

#include "engine/scene.hpp"

namespace py = pybind11;
using nlohmann::json;

namespace fretwear::python {
namespace {

std::string type_name(py::handle value) { return py::str(py::type::handle_of(value).attr("__name__")); }

// The path of a member as the scene parser writes it: "load.Q.ratio", "profile.parts[1].radius".
std::string member(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }

// A str as UTF-8; none for one holding surrogates (os.fsdecode's of bytes that were not UTF-8).
std::optional<std::string> utf8(py::handle s) {
  Py_ssize_t size = 0;
  const char* data = PyUnicode_AsUTF8AndSize(s.ptr(), &size);
  if (!data) {
    PyErr_Clear();
    return std::nullopt;
  }
  return std::string(data, std::size_t(size));
}

struct Problems {
  std::vector<std::string>& text;
  std::vector<std::string>& nulled;
};

json convert(py::handle value, const std::string& path, std::size_t depth, Problems& problems) {
  const std::string where = path.empty() ? "(top)" : path;
  const auto null_with = [&](std::string problem) {
    problems.text.push_back(std::move(problem));
    problems.nulled.push_back(where);
    return json(nullptr);
  };
  if (depth > kMaxSceneDepth) {
    return null_with(fmt::format("{}: nested deeper than {} levels; a scene needs about 20", where, kMaxSceneDepth));
  }
  if (value.is_none()) return nullptr;
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) {
    // Within 64 bits, signed or not; beyond, no JSON reader of ours holds it.
    int overflow = 0;
    const long long v = PyLong_AsLongLongAndOverflow(value.ptr(), &overflow);
    if (overflow == 0) return v;
    if (overflow > 0) {
      const unsigned long long u = PyLong_AsUnsignedLongLong(value.ptr());
      if (!PyErr_Occurred()) return u;
      PyErr_Clear();
    }
    // Its digits when they are few (Python refuses to print an int of over 4300 digits at all).
    const auto bits = value.attr("bit_length")().cast<long long>();
    return null_with(bits <= 256 ? fmt::format("{}: the integer {} does not fit in 64 bits; give a float", where,
                                               std::string(py::str(value)))
                                 : fmt::format("{}: an integer of {} bits does not fit in 64 bits; give a float",
                                               where, bits));
  }
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) {
    if (const std::optional<std::string> text = utf8(value)) return *text;
    return null_with(fmt::format("{}: the string {} is not UTF-8 text; give text", where, std::string(py::repr(value))));
  }
  if (py::isinstance<py::dict>(value)) {
    json object = json::object();
    for (const auto& [k, v] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(k)) {
        problems.text.push_back(fmt::format("{}: the key {} is a {}; keys are str", where, std::string(py::repr(k)),
                                            type_name(k)));
        continue;
      }
      const std::optional<std::string> key = utf8(k);
      if (!key) {
        problems.text.push_back(fmt::format("{}: the key {} is not UTF-8 text; give text", where,
                                            std::string(py::repr(k))));
        continue;
      }
      object[*key] = convert(v, member(path, *key), depth + 1, problems);
    }
    return object;
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    json array = json::array();
    std::size_t i = 0;
    for (const auto& v : value) array.push_back(convert(v, fmt::format("{}[{}]", path, i++), depth + 1, problems));
    return array;
  }
  // numpy's scalars (numpy.float64, numpy.int64, numpy.bool_, numpy.longdouble) by what they are, as Python's own
  // int and float (a longdouble rounded to double: item() would give a longdouble back).
  const py::module_ numpy = py::module_::import("numpy");
  if (py::isinstance(value, numpy.attr("bool_"))) return value.attr("item")().cast<bool>();
  // numpy's timedelta64 is one of its integers, and a duration, not a number of the scene's units.
  if (py::isinstance(value, numpy.attr("integer")) && !py::isinstance(value, numpy.attr("timedelta64"))) return convert(py::int_(py::reinterpret_borrow<py::object>(value)), path, depth + 1, problems);
  if (py::isinstance(value, numpy.attr("floating"))) return convert(py::float_(py::reinterpret_borrow<py::object>(value)), path, depth + 1, problems);
  return null_with(fmt::format("{}: a {} is not a JSON value; give a dict, list, str, number, bool or None", where,
                               type_name(value)));
}

}  // namespace

json to_json(py::handle value, std::vector<std::string>& problems, std::vector<std::string>& nulled) {
  Problems p{problems, nulled};
  return convert(value, "", 0, p);
}

py::object to_python(const json& j) {
  switch (j.type()) {
    case json::value_t::object: {
      py::dict d;
      for (const auto& [k, v] : j.items()) d[py::str(k)] = to_python(v);
      return d;
    }
    case json::value_t::array: {
      py::list l;
      for (const auto& v : j) l.append(to_python(v));
      return l;
    }
    case json::value_t::string:
      return py::str(j.get_ref<const std::string&>());
    case json::value_t::boolean:
      return py::bool_(j.get<bool>());
    case json::value_t::number_integer:
      return py::int_(j.get<std::int64_t>());
    case json::value_t::number_unsigned:
      return py::int_(j.get<std::uint64_t>());
    case json::value_t::number_float: {
      const double v = j.get<double>();
      if (!std::isfinite(v)) return py::none();
      return py::float_(v);
    }
    default:
      return py::none();
  }
}

}  // namespace fretwear::python
