#include "engine/scene.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <span>

#include <fmt/format.h>

#include "contact/crack_solver.hpp"
#include "contact/window.hpp"

namespace fretwear {

using nlohmann::json;

namespace {

std::string join(const std::vector<std::string>& v, const char* sep = ", ") {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

// Appends j to s as compact JSON, stopping once s is longer than limit: every level writes a character before it
// descends, so however deep j nests, the recursion is at most limit deep.
void write_short(const json& j, std::string& s, std::size_t limit) {
  // JSON has no NaN or infinity (a Python scene can hold them): named as they are, not as the null dump() writes.
  const auto scalar = [](const json& v) -> std::string {
    if (v.is_number_float() && !std::isfinite(v.get<double>()))
      return std::isnan(v.get<double>()) ? "nan" : v.get<double>() > 0 ? "inf" : "-inf";
    return v.dump(-1, ' ', true, json::error_handler_t::replace);
  };
  if (j.is_array() || j.is_object()) {
    s += j.is_array() ? '[' : '{';
    bool first = true;
    for (auto it = j.begin(); it != j.end() && s.size() <= limit; ++it, first = false) {
      if (!first) s += ',';
      if (j.is_object()) s += scalar(json(it.key())) + ':';
      write_short(*it, s, limit);
    }
    s += j.is_array() ? ']' : '}';
  } else {
    s += scalar(j);
  }
}

std::string describe(const json& j) {
  std::string s;
  write_short(j, s, 60);
  if (s.size() > 60) s = s.substr(0, 57) + "...";
  return s;
}

const char* type_name(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "not a value";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::binary: return "binary";
    case json::value_t::discarded: return "nothing";
    default: return "a number";
  }
}

// Levenshtein distance, for "did you mean" on typos.
std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

struct Bound {
  std::function<bool(double)> ok;
  std::string allowed;  // e.g. "a radius in [1e-9, 100] m"
};
const Bound kAny{[](double) { return true; }, "a finite number"};

// v written short for a message: 1e-9, 1000, 1e12.
std::string short_number(double v) {
  const std::string s = fmt::format("{:g}", v);
  const auto e = s.find('e');
  if (e == std::string::npos) return s;
  const bool negative = s[e + 1] == '-';
  const std::string digits = s.substr(e + 2);  // "09" of 1e-09, "12" of 1e+12
  const std::size_t first = std::min(digits.find_first_not_of('0'), digits.size() - 1);
  return s.substr(0, e) + (negative ? "e-" : "e") + digits.substr(first);
}

// "[1e-9, 1000] m", or "[1e-9, 1) m" when hi_open.
std::string interval(double lo, double hi, const std::string& unit, bool hi_open = false) {
  return fmt::format("[{}, {}{}{}", short_number(lo), short_number(hi), hi_open ? ")" : "]",
                     unit.empty() ? "" : " " + unit);
}

// A number in [lo, hi], or [lo, hi) when hi_open, named for the message: "a radius in [1e-9, 1000] m".
Bound within(double lo, double hi, const std::string& what, const std::string& unit, bool hi_open = false) {
  return {[=](double v) { return v >= lo && (hi_open ? v < hi : v <= hi); },
          what + " in " + interval(lo, hi, unit, hi_open)};
}
// The spans of scene.hpp, for each kind of number.
Bound length(const std::string& what) { return within(spans::kMinLength, spans::kMaxLength, what, "m"); }
Bound position(const std::string& what = "a position") {
  return within(-spans::kMaxPosition, spans::kMaxPosition, what, "m");
}
Bound stress(const std::string& what = "a stress") { return within(-spans::kMaxStress, spans::kMaxStress, what, "Pa"); }
Bound normal_load() { return within(spans::kMinLoad, spans::kMaxLoad, "a normal load", "N/m"); }
Bound tangential_load(double lo = -spans::kMaxLoad) { return within(lo, spans::kMaxLoad, "a tangential load", "N/m"); }
Bound time_point() { return within(-spans::kMaxTime, spans::kMaxTime, "a time", "s"); }
Bound displacement_amplitude() {
  return within(spans::kMinLength, spans::kMaxDelta, "a displacement amplitude", "m", true);
}

// Collects problems while reading one JSON object; every read names the full JSON path.
class Reader {
 public:
  Reader(const json& obj, std::string path, std::vector<std::string>& problems)
      : obj_(obj), path_(std::move(path)), problems_(problems) {}

  std::string at(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  void problem(const std::string& path, const std::string& what) { problems_.push_back(path + ": " + what); }
  std::vector<std::string>& problems() { return problems_; }

  const json* find(const std::string& key) {
    if (std::find(seen_.begin(), seen_.end(), key) == seen_.end()) seen_.push_back(key);
    auto it = obj_.find(key);
    return it == obj_.end() ? nullptr : &*it;
  }

  std::optional<double> number(const std::string& key, std::optional<double> def, const Bound& bound = kAny) {
    const json* v = find(key);
    if (!v) {
      if (!def) problem(at(key), "missing; give " + bound.allowed);
      return def;
    }
    if (!v->is_number()) {
      problem(at(key), fmt::format("{} is {}; give {}", describe(*v), type_name(*v), bound.allowed));
      return std::nullopt;
    }
    const double x = v->get<double>();
    if (!std::isfinite(x) || !bound.ok(x)) {
      problem(at(key), fmt::format("{} is not allowed; give {}", describe(*v), bound.allowed));
      return std::nullopt;
    }
    return x;
  }

  std::optional<std::string> string(const std::string& key, std::optional<std::string> def,
                                    const std::string& allowed) {
    const json* v = find(key);
    if (!v) {
      if (!def) problem(at(key), "missing; give " + allowed);
      return def;
    }
    if (!v->is_string()) {
      problem(at(key), fmt::format("{} is {}; give {}", describe(*v), type_name(*v), allowed));
      return std::nullopt;
    }
    return v->get<std::string>();
  }

  std::optional<bool> boolean(const std::string& key, bool def) {
    const json* v = find(key);
    if (!v) return def;
    if (!v->is_boolean()) {
      problem(at(key), fmt::format("{} is {}; give true or false", describe(*v), type_name(*v)));
      return std::nullopt;
    }
    return v->get<bool>();
  }

  // An object member; reports a missing required one or a wrong type.
  const json* object(const std::string& key, bool required) {
    const json* v = find(key);
    if (!v) {
      if (required) problem(at(key), "missing; give an object");
      return nullptr;
    }
    if (!v->is_object()) {
      problem(at(key), fmt::format("{} is {}; give an object", describe(*v), type_name(*v)));
      return nullptr;
    }
    return v;
  }

  // Reports keys not read, and keys of capabilities that are not built yet.
  void finish(const std::vector<std::pair<std::string, std::string>>& not_yet = {}) {
    for (const auto& item : obj_.items()) {
      const std::string& key = item.key();  // not a structured binding: clang 14 cannot capture those
      auto ny = std::find_if(not_yet.begin(), not_yet.end(), [&](const auto& p) { return p.first == key; });
      if (ny != not_yet.end()) {
        problem(at(key), "not supported yet (" + ny->second + ")");
      } else if (std::find(seen_.begin(), seen_.end(), key) == seen_.end()) {
        std::vector<std::string> known = seen_;
        for (const auto& p : not_yet) known.push_back(p.first);
        std::string hint;
        for (const auto& k : known)
          if (edit_distance(key, k) <= 2) hint = " (did you mean \"" + k + "\"?)";
        problem(at(key), "unknown key" + hint + "; the keys here are " + join(known));
      }
    }
  }

 private:
  const json& obj_;
  std::string path_;
  std::vector<std::string>& problems_;
  std::vector<std::string> seen_;
};

constexpr int kMaxProfileDepth = 8;

// The units a table's x and h may be given in, with their size in metres.
constexpr std::pair<const char*, double> kTableUnits[] = {{"m", 1.0}, {"mm", 1e-3}, {"um", 1e-6}, {"nm", 1e-9}};
const std::string kTableUnitWords = "\"m\", \"mm\", \"um\" or \"nm\"";

// A measured profile's CSV (SCENES.md, "Measured profiles"): a header row naming the two columns, then one row x, h
// per point, x increasing strictly; blank lines and lines starting with '#' are skipped; a row's fields are
// separated by a comma and may carry spaces, and double quotes around the whole field (no comma inside); a UTF-8
// byte order mark before the first row is skipped. Reports
// each problem as "path: file, line n: what is wrong"; returns false when there are any.
bool read_table_csv(std::string_view text, const std::string& path, const std::string& file, double x_scale,
                    double h_scale, ProfileSpec& s, std::vector<std::string>& problems) {
  constexpr std::size_t kMaxProblemsNamed = 10;
  const std::size_t before = problems.size();
  std::size_t n_problems = 0;
  const auto problem = [&](std::size_t line, const std::string& what) {
    if (++n_problems <= kMaxProblemsNamed) problems.push_back(fmt::format("{}: {}, line {}: {}", path, file, line, what));
  };
  const auto trim = [](std::string_view v) {
    const auto first = v.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return std::string_view();
    return v.substr(first, v.find_last_not_of(" \t\r") - first + 1);
  };
  const Bound x_span = position("a position x"), h_span = position("a height h");
  // A UTF-8 byte order mark (as some spreadsheets write it) is not part of the first row, which else would not read
  // as two numbers and pass for a header.
  if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
  bool header = false;
  std::size_t line_no = 0, x_line = 0;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t eol = std::min(text.find('\n', at), text.size());
    const std::string_view line = trim(text.substr(at, eol - at));
    at = eol + 1;
    ++line_no;
    if (line.empty() || line.front() == '#') continue;
    std::vector<std::string_view> fields;
    for (std::size_t from = 0;;) {
      const std::size_t comma = line.find(',', from);
      std::string_view field =
          trim(line.substr(from, comma == std::string_view::npos ? std::string_view::npos : comma - from));
      // A field in double quotes (RFC 4180, as spreadsheets export numbers and headers) is read without them.
      if (field.size() >= 2 && field.front() == '"' && field.back() == '"')
        field = trim(field.substr(1, field.size() - 2));
      fields.push_back(field);
      if (comma == std::string_view::npos) break;
      from = comma + 1;
    }
    if (fields.size() != 2) {
      problem(line_no, fmt::format("has {} column{}; give two, x and h, separated by a comma", fields.size(),
                                   fields.size() == 1 ? "" : "s"));
      if (!header) header = true;
      continue;
    }
    std::array<double, 2> v{};
    std::array<bool, 2> number{};
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string_view f = fields[k];
      const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v[k]);
      number[k] = ec == std::errc() && end == f.data() + f.size() && std::isfinite(v[k]);
    }
    if (!header) {
      header = true;
      if (number[0] && number[1])
        problem(line_no, "holds two numbers, not a header; the first row names the columns (x, h)");
      continue;
    }
    bool ok = true;
    for (std::size_t k = 0; k < 2; ++k) {
      const char* column = k == 0 ? "x" : "h";
      if (!number[k]) {
        problem(line_no, fmt::format("\"{}\" in column {} is not a finite number",
                                     fields[k].size() > 40 ? std::string(fields[k].substr(0, 37)) + "..." :
                                                             std::string(fields[k]),
                                     column));
        ok = false;
        continue;
      }
      const double metres = v[k] * (k == 0 ? x_scale : h_scale);
      const Bound& span = k == 0 ? x_span : h_span;
      if (!span.ok(metres)) {
        problem(line_no, fmt::format("{} = {} m is not allowed; give {}", column, metres, span.allowed));
        ok = false;
      }
    }
    if (!ok) continue;
    const double x = v[0] * x_scale, h = v[1] * h_scale;
    if (!s.x.empty() && !(x > s.x.back())) {
      problem(line_no, fmt::format("x = {} does not exceed x = {} on line {}; x must increase strictly", fields[0],
                                   s.x.back() / x_scale, x_line));
      continue;
    }
    s.x.push_back(x), s.h.push_back(h), x_line = line_no;
  }
  if (n_problems > kMaxProblemsNamed)
    problems.push_back(fmt::format("{}: {}: {} more problems", path, file, n_problems - kMaxProblemsNamed));
  if (n_problems == 0 && !header)
    problems.push_back(fmt::format("{}: {}: is empty; give a header row naming the columns, then a row x, h per "
                                   "point (at least two)",
                                   path, file));
  else if (n_problems == 0 && s.x.size() < 2)
    problems.push_back(fmt::format("{}: {}, line {}: {}; a table needs at least two rows x, h below the header row",
                                   path, file, line_no, s.x.empty() ? "has no data rows" : "has one data row"));
  return problems.size() == before;
}

// Reads the file of a table: a regular file of at most kMaxSceneBytes (never a device or a pipe, which could hang
// or stream without end); its text goes to read_table_csv and its checksum to s.source.
bool read_table_file(const std::filesystem::path& file, const std::string& path, double x_scale, double h_scale,
                     ProfileSpec& s, std::vector<std::string>& problems) {
  namespace fs = std::filesystem;
  const std::string name = "\"" + file.string() + "\"";
  std::error_code ec;
  const auto status = fs::status(file, ec);
  if (ec || !fs::exists(status)) {
    problems.push_back(fmt::format("{}: {}: no such file (a relative path is read from the scene's folder)", path, name));
    return false;
  }
  if (!fs::is_regular_file(status)) {
    problems.push_back(fmt::format("{}: {}: is not a regular file; give a CSV file of x, h", path, name));
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  std::string text(kMaxSceneBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  if (in.bad() || (!in && !in.eof())) {
    problems.push_back(fmt::format("{}: {}: cannot be read", path, name));
    return false;
  }
  text.resize(std::size_t(in.gcount()));
  if (text.size() > kMaxSceneBytes) {
    problems.push_back(fmt::format("{}: {}: is larger than {} bytes, the most a table's file may be", path, name,
                                   kMaxSceneBytes));
    return false;
  }
  if (text.find('\0') != std::string::npos) {
    problems.push_back(fmt::format("{}: {}: holds a NUL byte; a table's file is CSV text", path, name));
    return false;
  }
  s.source.checksum = fnv1a64(text);
  return read_table_csv(text, path, name, x_scale, h_scale, s, problems);
}

// profile.type "table": x and h inline, or a file; their units; the interpolation; a file's checksum.
void parse_table(Reader& r, ProfileSpec& s, const std::filesystem::path& scene_dir) {
  std::array<std::optional<double>, 2> scale;
  for (std::size_t k = 0; k < 2; ++k) {
    const std::string key = k == 0 ? "x_unit" : "h_unit";
    const auto unit = r.string(key, "m", kTableUnitWords);
    if (!unit) continue;
    for (const auto& [word, metres] : kTableUnits)
      if (*unit == word) scale[k] = metres;
    if (!scale[k]) r.problem(r.at(key), fmt::format("\"{}\" is not a unit; use {}", *unit, kTableUnitWords));
    (k == 0 ? s.source.x_unit : s.source.h_unit) = *unit;
  }
  bool interpolation_ok = false;
  if (const auto word = r.string("interpolation", "linear", interpolation_words())) {
    try {
      s.interpolation = interpolation_from_string(*word);
      interpolation_ok = true;
    } catch (const InputError& e) {
      r.problem(r.at("interpolation"), e.what());
    }
  }
  const json* file = r.find("file");
  const json* checksum = r.find("checksum");
  bool points_ok = false;
  const bool inline_points = r.find("x") != nullptr, inline_heights = r.find("h") != nullptr;  // both seen
  if (file && (inline_points || inline_heights)) {
    r.problem(r.at("file"), "given with inline x or h; give the table either inline (x and h) or as a file, not both");
  } else if (file) {
    if (!file->is_string() || file->get<std::string>().empty()) {
      r.problem(r.at("file"), fmt::format("{} is {}; give the path of a CSV file of x, h (relative to the scene's "
                                          "folder)",
                                          describe(*file), file->is_string() ? "empty" : type_name(*file)));
    } else if (scale[0] && scale[1]) {
      const std::filesystem::path given = file->get<std::string>();
      const std::filesystem::path full = given.is_absolute() ? given : scene_dir / given;
      std::error_code ec;
      const std::filesystem::path absolute = std::filesystem::absolute(full, ec).lexically_normal();
      s.source.file = (ec ? full : absolute).string();
      // The resolved scene records the file's full path as JSON text, which is UTF-8 only: a scene in a folder whose
      // name is not would solve and then fail to write it.
      if (holds_nul(given.native()))
        r.problem(r.at("file"), fmt::format("{} {}", describe(*file), kHoldsNul));
      else if (!utf8_text(s.source.file))
        r.problem(r.at("file"),
                  fmt::format("{} is read from {}, which is not UTF-8 text as scene.resolved.json must record it; "
                              "move the scene and its table into a folder whose path is UTF-8",
                              describe(*file), json(s.source.file).dump(-1, ' ', false, json::error_handler_t::replace)));
      else
        points_ok = read_table_file(full, r.at("file"), *scale[0], *scale[1], s, r.problems());
      if (points_ok && checksum) {
        if (!checksum->is_string())
          r.problem(r.at("checksum"), fmt::format("{} is {}; give the file's \"fnv1a64:...\" of a resolved scene",
                                                  describe(*checksum), type_name(*checksum)));
        else if (*checksum != s.source.checksum)
          r.problem(r.at("checksum"),
                    fmt::format("{} is not the file's checksum, {}: the file changed since the scene was resolved; "
                                "restore it, or remove checksum to take the file as it is",
                                describe(*checksum), s.source.checksum));
      }
    }
  } else {
    if (checksum) r.problem(r.at("checksum"), "given without file; a checksum belongs to a table read from a file");
    const auto read_array = [&](const std::string& key, double unit, const Bound& span, std::vector<double>& out) {
      const json* v = r.find(key);
      if (!v) return r.problem(r.at(key), "missing; give an array of at least two numbers, or a file of x, h");
      if (!v->is_array())
        return r.problem(r.at(key), fmt::format("{} is {}; give an array of numbers", describe(*v), type_name(*v)));
      for (std::size_t i = 0; i < v->size(); ++i) {
        const json& e = (*v)[i];
        if (!e.is_number() || !std::isfinite(e.get<double>()))
          return r.problem(fmt::format("{}[{}]", r.at(key), i), fmt::format("{} is not a finite number", describe(e)));
        if (!span.ok(e.get<double>() * unit))
          return r.problem(fmt::format("{}[{}]", r.at(key), i),
                           fmt::format("{} is not allowed; give {}", describe(e), span.allowed));
        out.push_back(e.get<double>() * unit);
      }
    };
    if (scale[0]) read_array("x", *scale[0], position(), s.x);
    if (scale[1]) read_array("h", *scale[1], position("a height"), s.h);
    const json* xv = r.find("x");
    const json* hv = r.find("h");
    if (xv && hv && xv->is_array() && hv->is_array()) {
      const std::size_t before = r.problems().size();
      const auto nx = xv->size(), nh = hv->size();
      if (nx < 2) r.problem(r.at("x"), fmt::format("has {} point(s); a table needs at least two", nx));
      if (nx != nh) r.problem(r.at("h"), fmt::format("has {} values but x has {}; give one h per x", nh, nx));
      for (std::size_t i = 1; i < s.x.size(); ++i)
        if (!(s.x[i] > s.x[i - 1])) {
          r.problem(fmt::format("{}[{}]", r.at("x"), i),
                    fmt::format("{} does not exceed the previous {}; x must increase strictly", s.x[i], s.x[i - 1]));
          break;
        }
      points_ok = r.problems().size() == before && s.x.size() == nx && s.h.size() == nh && scale[0] && scale[1];
    }
  }
  // What the interpolation needs of the points, once both are known to be right.
  if (points_ok && interpolation_ok) {
    if (s.x.size() < min_table_points(s.interpolation))
      r.problem(r.at("interpolation"), fmt::format("\"{}\" needs at least {} points; the table has {}: give more "
                                                   "points or use \"linear\"",
                                                   to_string(s.interpolation), min_table_points(s.interpolation),
                                                   s.x.size()));
    else if (s.interpolation == Interpolation::cubic && !uniformly_spaced(s.x))
      r.problem(r.at("interpolation"), "\"cubic\" (a cardinal cubic B-spline) needs uniformly spaced x; use "
                                       "\"makima\" or \"pchip\" for a table on non-uniform x");
  }
  if (!points_ok || s.x.size() < min_table_points(s.interpolation) ||
      (s.interpolation == Interpolation::cubic && !uniformly_spaced(s.x)))
    s.x = {-1.0, 1.0}, s.h = {0.0, 0.0}, s.interpolation = Interpolation::linear;  // evaluable while reported
}

ProfileSpec parse_profile(const json& j, const std::string& path, std::vector<std::string>& problems, int depth,
                          const std::filesystem::path& scene_dir) {
  ProfileSpec s;
  if (!j.is_object()) {
    problems.push_back(fmt::format("{}: {} is {}; give an object with a \"type\"", path, describe(j), type_name(j)));
    return s;
  }
  Reader r(j, path, problems);
  auto type = r.string("type", std::nullopt, "one of " + profile_type_words());
  if (!type) return s;
  try {
    s.type = profile_type_from_string(*type);
  } catch (const InputError&) {
    r.problem(r.at("type"), fmt::format("\"{}\" is not a profile type; use one of {}", *type, profile_type_words()));
    return s;
  }
  s.offset_x = r.number("offset_x", 0.0, position()).value_or(0.0);
  s.tilt_rad = r.number("tilt_rad", 0.0, {[](double v) { return std::abs(v) < 1.0; }, "a number in (−1, 1) rad"})
                   .value_or(0.0);
  const Bound angle{[](double v) { return v > 0.0 && v < 90.0; }, "an angle in (0, 90) degrees"};
  switch (s.type) {
    case ProfileType::cylinder:
      s.R = r.number("R", std::nullopt, length("a radius")).value_or(1.0);
      break;
    case ProfileType::flat_rounded:
      s.a = r.number("a", std::nullopt, length("a flat half-length")).value_or(1.0);
      s.R = r.number("R", std::nullopt, length("a radius")).value_or(1.0);
      break;
    case ProfileType::flat:
      s.b = r.number("b", std::nullopt, length("a half-width")).value_or(1.0);
      break;
    case ProfileType::wedge:
      s.angle_deg = r.number("angle_deg", std::nullopt, angle).value_or(1.0);
      break;
    case ProfileType::rounded_wedge:
      s.angle_deg = r.number("angle_deg", std::nullopt, angle).value_or(1.0);
      s.R = r.number("R", std::nullopt, length("a radius")).value_or(1.0);
      break;
    case ProfileType::wavy:
      s.amplitude = r.number("amplitude", std::nullopt, length("an amplitude")).value_or(1.0);
      s.wavelength = r.number("wavelength", std::nullopt, length("a wavelength")).value_or(1.0);
      break;
    case ProfileType::table:
      parse_table(r, s, scene_dir);
      break;
    case ProfileType::sum:
    case ProfileType::envelope: {
      const json* v = r.find("terms");
      if (!v) {
        r.problem(r.at("terms"), "missing; give an array of profiles");
      } else if (!v->is_array() || v->empty()) {
        r.problem(r.at("terms"), fmt::format("{} is {}; give a non-empty array of profiles", describe(*v),
                                              v->is_array() ? "empty" : type_name(*v)));
      } else if (depth >= kMaxProfileDepth) {
        r.problem(r.at("terms"), fmt::format("profiles nest deeper than {} levels", kMaxProfileDepth));
      } else {
        for (std::size_t i = 0; i < v->size(); ++i)
          s.terms.push_back(
              parse_profile((*v)[i], fmt::format("{}[{}]", r.at("terms"), i), problems, depth + 1, scene_dir));
      }
      if (s.terms.empty()) {
        ProfileSpec placeholder;  // keeps the tree evaluable while the problem is reported
        placeholder.R = 1.0;
        s.terms.push_back(placeholder);
      }
      break;
    }
  }
  r.finish();
  return s;
}

Material parse_material(const json& j, const std::string& path, std::vector<std::string>& problems) {
  Reader r(j, path, problems);
  Material m;
  m.E = r.number("E", std::nullopt, within(spans::kMinModulus, spans::kMaxModulus, "a Young's modulus", "Pa"))
            .value_or(1.0);
  m.nu = r.number("nu", std::nullopt,
                  {[](double v) { return v > -1.0 && v < 0.5; }, "a Poisson's ratio in (-1, 0.5)"})
             .value_or(0.0);
  r.finish();
  return m;
}

bool valid_name(const std::string& s) {
  return !s.empty() && s.size() <= 128 && s != "." && s != ".." &&
         std::all_of(s.begin(), s.end(), [](char c) {
           return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
         });
}

json profile_to_json(const ProfileSpec& s) {
  json j{{"type", to_string(s.type)}};
  switch (s.type) {
    case ProfileType::cylinder: j["R"] = s.R; break;
    case ProfileType::flat_rounded: j["a"] = s.a; j["R"] = s.R; break;
    case ProfileType::flat: j["b"] = s.b; break;
    case ProfileType::wedge: j["angle_deg"] = s.angle_deg; break;
    case ProfileType::rounded_wedge: j["angle_deg"] = s.angle_deg; j["R"] = s.R; break;
    case ProfileType::wavy: j["amplitude"] = s.amplitude; j["wavelength"] = s.wavelength; break;
    case ProfileType::table:
      if (s.source.file.empty()) {  // inline: in metres, whatever units the scene gave
        j["x"] = s.x, j["h"] = s.h;
      } else {  // the file, its units and its checksum: a changed file is refused when the scene is run again
        j["file"] = s.source.file, j["x_unit"] = s.source.x_unit, j["h_unit"] = s.source.h_unit;
        j["checksum"] = s.source.checksum;
      }
      j["interpolation"] = to_string(s.interpolation);
      break;
    case ProfileType::sum:
    case ProfileType::envelope: {
      j["terms"] = json::array();
      for (const auto& t : s.terms) j["terms"].push_back(profile_to_json(t));
      break;
    }
  }
  j["offset_x"] = s.offset_x;
  j["tilt_rad"] = s.tilt_rad;
  return j;
}

}  // namespace

// The words a user types for an enum: one table each, read both ways.
namespace {

template <typename Enum>
using Words = std::span<const std::pair<Enum, const char*>>;

constexpr std::pair<TangentialRoute, const char*> kRouteWords[] = {
    {TangentialRoute::automatic, "auto"}, {TangentialRoute::analogy, "analogy"},
    {TangentialRoute::incremental, "incremental"}};
constexpr std::pair<LoadControl, const char*> kControlWords[] = {{LoadControl::force, "force"},
                                                                 {LoadControl::displacement, "displacement"}};
constexpr std::pair<WearStepper, const char*> kStepperWords[] = {{WearStepper::implicit, "implicit"},
                                                                 {WearStepper::explicit_capped, "explicit"},
                                                                 {WearStepper::cycle_by_cycle, "cycle_by_cycle"}};
// A position x is given as a number, not a word.
constexpr std::pair<GrowthMode, const char*> kGrowthModeWords[] = {{GrowthMode::mode_I, "I"},
                                                                   {GrowthMode::equivalent, "equivalent"}};
constexpr std::pair<CrackPosition, const char*> kCrackEdgeWords[] = {{CrackPosition::trailing_edge, "trailing_edge"},
                                                                     {CrackPosition::leading_edge, "leading_edge"}};

template <typename Enum>
std::string word_of(Words<Enum> words, Enum e) {
  for (const auto& [value, word] : words)
    if (value == e) return word;
  return "?";
}

// "a", "b" or "c"
template <typename Enum>
std::string words_list(Words<Enum> words) {
  std::string s;
  for (std::size_t k = 0; k < words.size(); ++k)
    s += (k == 0 ? "" : k + 1 == words.size() ? " or " : ", ") + fmt::format("\"{}\"", words[k].second);
  return s;
}

template <typename Enum>
Enum from_word(Words<Enum> words, std::string_view word, const char* what) {
  for (const auto& [value, w] : words)
    if (word == w) return value;
  throw InputError(fmt::format("\"{}\" is not {}; use {}", word, what, words_list(words)));
}

}  // namespace

std::string to_string(TangentialRoute r) { return word_of<TangentialRoute>(kRouteWords, r); }
TangentialRoute route_from_string(std::string_view word) { return from_word<TangentialRoute>(kRouteWords, word, "a route"); }
std::string route_words() { return words_list<TangentialRoute>(kRouteWords); }

std::string to_string(LoadControl c) { return word_of<LoadControl>(kControlWords, c); }
LoadControl control_from_string(std::string_view word) { return from_word<LoadControl>(kControlWords, word, "a load control"); }
std::string control_words() { return words_list<LoadControl>(kControlWords); }

std::string sliding_under_force_control(double Q, double fP) {
  return fmt::format("effects.wear: Q = {:.6g} N/m reaches f P = {:.6g} N/m: the bodies slide, and under force "
                     "control the slip, hence the wear, is not determined; prescribe the displacement instead "
                     "(load.control \"displacement\" with load.delta)",
                     Q, fP);
}

std::string to_string(WearStepper stepper) { return word_of<WearStepper>(kStepperWords, stepper); }
WearStepper stepper_from_string(std::string_view word) {
  return from_word<WearStepper>(kStepperWords, word, "a stepper");
}
std::string stepper_words() { return words_list<WearStepper>(kStepperWords); }

std::string to_string(GrowthMode mode) { return word_of<GrowthMode>(kGrowthModeWords, mode); }
GrowthMode growth_mode_from_string(std::string_view word) {
  return from_word<GrowthMode>(kGrowthModeWords, word, "a growth mode");
}

double LifeEffect::a_initial() const {
  if (growth && growth->a_initial) return *growth->a_initial;
  return initiation ? initiation->critical_distance : 0.0;
}

std::string to_string(CrackPosition at) {
  return at == CrackPosition::x ? "x" : word_of<CrackPosition>(kCrackEdgeWords, at);
}
CrackPosition crack_position_from_string(std::string_view word) {
  return from_word<CrackPosition>(kCrackEdgeWords, word, "a crack position");
}

double Scene::P_max() const {
  double P_max = P;
  for (const auto& pt : history) P_max = std::max(P_max, pt[1]);
  return P_max;
}

double Scene::Q_max() const {
  if (!history.empty()) {
    double Q = 0.0;
    for (const auto& pt : history) Q = std::max(Q, std::abs(pt[2]));
    return Q;
  }
  if (Q_amplitude) return *Q_amplitude;
  if (Q_ratio && friction) return *Q_ratio * *friction * P;
  return 0.0;
}

namespace {

// A problem as printed: the control characters a scene's strings and keys may hold (a NUL, which ends a C string and
// with it every problem after it, an escape sequence) written as JSON writes them, \u0000.
std::vector<std::string> printable(std::vector<std::string> problems) {
  for (std::string& p : problems) {
    std::string out;
    for (const char c : p)
      if ((static_cast<unsigned char>(c) < 0x20 && c != '\n' && c != '\t') || c == 0x7f)
        out += fmt::format("\\u{:04x}", static_cast<unsigned char>(c));
      else
        out += c;
    p = std::move(out);
  }
  return problems;
}

}  // namespace

SceneError::SceneError(std::vector<std::string> problems) : SceneError("the scene is invalid", std::move(problems)) {}

SceneError::SceneError(const std::string& heading, std::vector<std::string> problems)
    : InputError(heading + ":\n  " + join(printable(problems), "\n  ")), problems_(printable(std::move(problems))) {}

namespace {

// What the scene gives, valid or not: an invalid value is reported once, for what it is, and never again as missing
// (or as given where it is not used) by the checks of what the effects need.
struct Given {
  bool materials_ok = false;  // the moduli as given: the coupling checks need them, not an invalid one's placeholder
  bool friction = false, load_read = false, P_ok = false, Q = false, delta = false, history = false;
  bool window = false, reference_depth = false;
  bool effects_unknown = false;  // effects given but not an object: what they need is unknown
  bool loads_unknown = false;    // load.blocks given but its first block's load is unreadable
  bool wear_cycles_ok = true;    // effects.wear.cycles as given (the blocks' total is checked against it)
  bool blocks_cycles_ok = true;  // every load.blocks[k].cycles as given
  std::optional<LoadControl> control = LoadControl::force;  // nullopt: an invalid word
};

// name, plane.
// Returns whether the name was read without a problem (the default output folder, output/<name>, is then known).
bool parse_naming(Reader& top, const std::string& default_name, Scene& s) {
  constexpr std::size_t kMaxName = 128;  // valid_name's limit
  const std::size_t n_problems_before = top.problems().size();
  s.name = top.string("name", default_name, "a name of at most 128 letters, digits, '_', '-' and '.'")
               .value_or("scene");
  if (!valid_name(s.name))
    top.problem("name", s.name.size() > kMaxName
                            ? fmt::format("\"{}\" cannot name a folder: it has {} characters; use at most {}, of "
                                          "letters, digits, '_', '-' and '.'",
                                          s.name, s.name.size(), kMaxName)
                            : fmt::format("\"{}\" cannot name a folder; use letters, digits, '_', '-' and '.'",
                                          s.name));
  const bool name_read = top.problems().size() == n_problems_before;

  if (auto plane = top.string("plane", "strain", "\"strain\" or \"stress\"")) {
    try {
      s.plane = plane_state_from_string(*plane);
    } catch (const InputError&) {
      top.problem("plane", fmt::format("\"{}\" is not a plane state; use \"strain\" or \"stress\"", *plane));
    }
  }
  return name_read;
}

// materials: "both", or "pad" and "specimen".
void parse_materials(Reader& top, Scene& s, std::vector<std::string>& problems) {
  if (const json* m = top.object("materials", true)) {
    Reader r(*m, "materials", problems);
    // Which form is given is read from the keys; a member that is not an object is reported once, as such.
    const bool both = r.find("both"), pad = r.find("pad"), spec = r.find("specimen");
    const auto read = [&](const char* key, Material& into) {
      if (const json* v = r.object(key, false)) into = parse_material(*v, std::string("materials.") + key, problems);
    };
    if (both && (pad || spec)) {
      r.problem("materials", "give either \"both\" or \"pad\" and \"specimen\", not both forms");
    } else if (both) {
      read("both", s.pad);
      s.specimen = s.pad;
    } else if (pad && spec) {
      read("pad", s.pad);
      read("specimen", s.specimen);
      s.similar = false;
    } else if (!pad && !spec) {
      r.problem("materials", "give \"both\" (similar bodies) or \"pad\" and \"specimen\"");
    } else {
      read(pad ? "pad" : "specimen", pad ? s.pad : s.specimen);
      r.problem(pad ? "materials.specimen" : "materials.pad", "missing; give {\"E\": ..., \"nu\": ...}");
    }
    r.finish();
  }
}

// load.history: points [t, P, Q, sigma_bulk] closing a cycle.
void parse_history(const json* hv, Reader& r, std::vector<std::array<double, 4>>& history,
                   const std::string& path = "load.history") {
  const std::string what = "give a list of at least two points [t, P, Q, sigma_bulk] (s, N/m, N/m, Pa)";
  if (!hv->is_array() || hv->size() < 2) {
    r.problem(path, fmt::format("{} is not {}; {}", describe(*hv),
                                          hv->is_array() ? "long enough" : "a list", what));
  } else {
    const std::array<std::pair<const char*, Bound>, 4> point_spans{
        {{"t", time_point()}, {"P", normal_load()}, {"Q", tangential_load()}, {"sigma_bulk", stress()}}};
    for (std::size_t i = 0; i < hv->size(); ++i) {
      const json& pt = (*hv)[i];
      const std::string at = fmt::format("{}[{}]", path, i);
      const bool numbers = pt.is_array() && pt.size() == 4 && std::all_of(pt.begin(), pt.end(), [](const json& v) {
        return v.is_number() && std::isfinite(v.get<double>());
      });
      if (!numbers) {
        r.problem(at, fmt::format("{} is not a point [t, P, Q, sigma_bulk] of four finite numbers", describe(pt)));
        history.clear();
        break;
      }
      const std::array<double, 4> v{pt[0].get<double>(), pt[1].get<double>(), pt[2].get<double>(),
                                    pt[3].get<double>()};
      std::optional<std::string> wrong;
      for (std::size_t k = 0; k < v.size() && !wrong; ++k)
        if (!point_spans[k].second.ok(v[k]))
          wrong = fmt::format("{} = {} is not allowed; give {}", point_spans[k].first, v[k],
                              point_spans[k].second.allowed);
      if (wrong) {
        r.problem(at, *wrong);
        history.clear();
        break;
      }
      if (!history.empty() && !(v[0] > history.back()[0])) {
        r.problem(at, fmt::format("t = {} does not exceed the previous {}; t must increase strictly", v[0],
                                  history.back()[0]));
        history.clear();
        break;
      }
      history.push_back(v);
    }
    if (!history.empty()) {
      const auto& a = history.front();
      const auto& b = history.back();
      if (a[1] != b[1] || a[2] != b[2] || a[3] != b[3]) {
        r.problem(fmt::format("{}[{}]", path, history.size() - 1),
                  fmt::format("ends the cycle at P, Q, sigma_bulk = {}, {}, {}, not where it starts ({}, {}, {}); "
                              "a cycle closes: repeat the first point's P, Q and sigma_bulk at the end",
                              b[1], b[2], b[3], a[1], a[2], a[3]));
        history.clear();
      }
    }
  }
}

// load.blocks: [{"Q": {...} | "delta": d | "history": [...], "cycles": N}, ...]; the first block's load becomes the
// scene's own (the cycle stage's), and `given` says what it gives, as if given at the top of load.
void parse_blocks(const json* bv, Reader& r, Scene& s, Given& given, std::vector<std::string>& problems) {
  if (!bv->is_array() || bv->empty()) {
    given.loads_unknown = true;
    r.problem("load.blocks", fmt::format("{} is not {}; give a list of blocks {{\"Q\": {{...}} or \"delta\": d or "
                                         "\"history\": [...], \"cycles\": N}}",
                                         describe(*bv), bv->is_array() ? "a non-empty list" : "a list"));
    return;
  }
  for (std::size_t i = 0; i < bv->size(); ++i) {
    const std::string at = fmt::format("load.blocks[{}]", i);
    const json& b = (*bv)[i];
    // The first block's load stands for the scene's: unreadable, what the effects need of it is unknown too.
    if (i == 0 && (!b.is_object() || int(b.contains("Q")) + int(b.contains("delta")) + int(b.contains("history")) != 1))
      given.loads_unknown = true;
    if (!b.is_object()) {
      r.problem(at, fmt::format("{} is not an object; give {{\"Q\": {{...}} or \"delta\": d or \"history\": "
                                "[...], \"cycles\": N}}",
                                describe(b)));
      continue;
    }
    Reader rb(b, at, problems);
    LoadBlock block;
    const int loads = int(b.contains("Q")) + int(b.contains("delta")) + int(b.contains("history"));
    if (loads != 1)
      rb.problem(at, fmt::format("gives {} loads; give exactly one of \"Q\" ({{\"amplitude\": N/m}} or "
                                 "{{\"ratio\": Q/(fP)}}), \"delta\" (m, displacement control) or \"history\"",
                                 loads));
    if (const json* q = rb.object("Q", false)) {
      Reader rq(*q, at + ".Q", problems);
      const bool has_amplitude = q->contains("amplitude"), has_ratio = q->contains("ratio");
      if (has_amplitude == has_ratio) {
        rq.problem(at + ".Q", "give exactly one of \"amplitude\" (N/m) or \"ratio\" (Q/(fP))");
        rq.find("amplitude"), rq.find("ratio");
      } else if (has_amplitude) {
        block.Q_amplitude = rq.number("amplitude", std::nullopt, tangential_load(0.0));
      } else {
        block.Q_ratio = rq.number("ratio", std::nullopt, within(0.0, spans::kMaxLoadRatio, "a ratio Q/(fP)", ""));
      }
      rq.finish();
    }
    if (rb.find("delta")) block.delta = rb.number("delta", std::nullopt, displacement_amplitude());
    if (const json* hv = rb.find("history")) parse_history(hv, rb, block.history, at + ".history");
    const auto cycles = rb.number("cycles", std::nullopt,
                                  {[](double v) { return v >= 1.0 && v <= 1e12 && v == std::floor(v); },
                                   "a whole number of cycles from 1 to 1e12"});
    block.cycles = cycles.value_or(1.0);
    if (!cycles) given.blocks_cycles_ok = false;  // the total is then no check of effects.wear.cycles
    rb.finish();
    s.blocks.push_back(std::move(block));
  }
  if (s.blocks.empty()) return;
  const LoadBlock& first = s.blocks.front();
  s.Q_amplitude = first.Q_amplitude, s.Q_ratio = first.Q_ratio, s.delta = first.delta, s.history = first.history;
  s.control = first.delta ? LoadControl::displacement : LoadControl::force;
  given.control = s.control;
  given.Q = (*bv)[0].is_object() && (*bv)[0].contains("Q");
  given.delta = first.delta.has_value();
  given.history = !first.history.empty();
}

// load: P, Q, bulk_stress, control, delta, history, blocks.
void parse_load(Reader& top, Scene& s, Given& given, std::vector<std::string>& problems) {
  const json* l = top.object("load", true);
  if (!l) return;
  Reader r(*l, "load", problems);
  given.load_read = true;
  const auto P = r.number("P", std::nullopt, normal_load());
  given.P_ok = P.has_value();
  s.P = P.value_or(1.0);
  given.Q = r.find("Q") != nullptr;
  if (const json* q = r.object("Q", false)) {
    Reader rq(*q, "load.Q", problems);
    const bool has_amplitude = q->contains("amplitude"), has_ratio = q->contains("ratio");
    if (has_amplitude == has_ratio) {
      rq.problem("load.Q", "give exactly one of \"amplitude\" (N/m) or \"ratio\" (Q/(fP))");
      rq.find("amplitude"), rq.find("ratio");
    } else if (has_amplitude) {
      s.Q_amplitude = rq.number("amplitude", std::nullopt, tangential_load(0.0));
    } else {
      s.Q_ratio = rq.number("ratio", std::nullopt, within(0.0, spans::kMaxLoadRatio, "a ratio Q/(fP)", ""));
    }
    rq.finish();
  }
  if (const json* b = r.object("bulk_stress", false)) {
    Reader rb(*b, "load.bulk_stress", problems);
    s.bulk_stress = rb.number("amplitude", 0.0, stress()).value_or(0.0);
    rb.finish();
  }
  if (const auto word = r.string("control", "force", control_words())) {
    try {
      s.control = control_from_string(*word);
    } catch (const InputError& e) {
      r.problem("load.control", e.what());
      given.control.reset();
    }
  } else {
    given.control.reset();
  }
  if (given.control) given.control = s.control;
  given.delta = r.find("delta") != nullptr;
  if (given.delta)
    s.delta = r.number("delta", std::nullopt, displacement_amplitude());
  if (const json* hv = r.find("history")) {
    given.history = true;
    parse_history(hv, r, s.history);
  }
  if (const json* bv = r.find("blocks")) {
    for (const char* key : {"Q", "delta", "history", "control"})
      if (l->contains(key))
        r.problem(fmt::format("load.{}", key),
                  fmt::format("given with load.blocks, whose blocks give the loads (\"Q\" or \"history\": force "
                              "control, \"delta\": displacement control); move it into the blocks"));
    parse_blocks(bv, r, s, given, problems);
  }
  r.finish();
}

// grid: cells, window, reference_depth.
void parse_grid(Reader& top, Scene& s, Given& given, std::vector<std::string>& problems) {
  given.window = top.find("grid") != nullptr;  // a grid that is not an object: a missing window is not asked for
  if (const json* g = top.object("grid", false)) {
    given.window = g->contains("window");
    Reader r(*g, "grid", problems);
    if (const json* c = r.find("cells")) {
      const bool whole = c->is_number_integer() || (c->is_number_float() && std::isfinite(c->get<double>()) &&
                                                    c->get<double>() == std::floor(c->get<double>()));
      if (!whole) {
        r.problem("grid.cells", fmt::format("{} is not a whole number; give a whole number of cells from {} to {}",
                                            describe(*c), kMinCells, kMaxCells));
      } else if (c->get<double>() < kMinCells || c->get<double>() > kMaxCells) {
        r.problem("grid.cells", fmt::format("{} is out of range; give a whole number of cells from {} to {}",
                                            describe(*c), kMinCells, kMaxCells));
      } else {
        s.cells = int(c->get<double>());
      }
    }
    if (const json* w = r.find("window")) {
      if (!w->is_array() || w->size() != 2 || !(*w)[0].is_number() || !(*w)[1].is_number()) {
        r.problem("grid.window", fmt::format("{} is not [x_min, x_max]; give two numbers (m)", describe(*w)));
      } else if (const double lo = (*w)[0].get<double>(), hi = (*w)[1].get<double>();
                 !(lo < hi) || !std::isfinite(lo) || !std::isfinite(hi)) {
        r.problem("grid.window", fmt::format("{} is empty; give [x_min, x_max] with x_min < x_max (m)", describe(*w)));
      } else if (const Bound end = position(); !end.ok(lo) || !end.ok(hi)) {
        for (std::size_t i : {0u, 1u})
          if (!end.ok((*w)[i].get<double>()))
            r.problem(fmt::format("grid.window[{}]", i),
                      fmt::format("{} is not allowed; give {}", describe((*w)[i]), end.allowed));
      } else if (hi - lo < spans::kMinLength) {
        r.problem("grid.window", fmt::format("{} is narrower than {} m; give [x_min, x_max] with x_max - x_min >= {} m",
                                             describe(*w), short_number(spans::kMinLength),
                                             short_number(spans::kMinLength)));
      } else {
        s.window = std::pair(lo, hi);
      }
    }
    given.reference_depth = r.find("reference_depth") != nullptr;
    if (given.reference_depth)
      s.reference_depth = r.number("reference_depth", std::nullopt,
                                   {length("a depth").ok, "a depth > 0 m below the contact centre, in " +
                                                              interval(spans::kMinLength, spans::kMaxLength, "m")});
    r.finish();
  }
}

// effects.tangential: the route and the increments of a cycle.
void parse_tangential(Reader& r, Scene& s, std::vector<std::string>& problems) {
  if (const json* t = r.object("tangential", false)) {
    Reader rt(*t, "effects.tangential", problems);
    TangentialEffect effect;
    if (auto route = rt.string("route", "auto", route_words())) {
      try {
        effect.route = route_from_string(*route);
      } catch (const InputError& e) {
        rt.problem("effects.tangential.route", e.what());
      }
    }
    effect.increments = int(rt.number("increments", 40.0, {[](double v) { return v >= 4 && v <= 100000 && v == std::floor(v) && std::fmod(v, 4.0) == 0.0; },
                                                         "a whole number of increments from 4 to 100000, a multiple of 4"})
                                .value_or(40.0));
    rt.finish();
    s.tangential = effect;
  } else if (r.find("tangential")) {
    s.tangential = TangentialEffect{};  // asked for, though not readable: the checks of what it needs still apply
  }
}

// effects.wear.record: a count of log-spaced records, or the cycles to record at.
void parse_record(const json* rec, Reader& rw, WearEffect& effect) {
  if (rec->is_number_integer() && rec->get<long long>() >= 1 && rec->get<long long>() <= 1000) {
    effect.record_count = int(rec->get<long long>());
  } else if (rec->is_array() && !rec->empty()) {
    double last = 0.0;
    for (std::size_t i = 0; i < rec->size(); ++i) {
      const json& at = (*rec)[i];
      if (!at.is_number() || !(at.get<double>() > last) || at.get<double>() > effect.cycles) {
        rw.problem(fmt::format("effects.wear.record[{}]", i),
                   fmt::format("{} is not allowed; give increasing cycle counts in (0, cycles]", describe(at)));
        break;
      }
      last = at.get<double>();
      effect.record.push_back(last);
    }
    effect.record_count = 0;
  } else {
    rw.problem("effects.wear.record", fmt::format("{} is neither a count from 1 to 1000 nor a list of cycles",
                                                  describe(*rec)));
  }
}

// effects.wear's coefficient of the law: both bodies together (k or alpha, with pad_fraction), or each body's
// (k_pad and k_specimen, or alpha_pad and alpha_specimen; PHYSICS.md, "per-body wear"): then the wear of both
// together runs at their sum and the pad's share is its own over the sum.
void parse_wear_coefficients(Reader& rw, const json& w, WearEffect& effect) {
  const bool archard = effect.law == wear::Law::archard;
  const std::string key = archard ? "k" : "alpha", other = archard ? "alpha" : "k";
  const std::string pad = key + "_pad", specimen = key + "_specimen";
  bool other_given = false;
  for (const std::string& o : {other, other + "_pad", other + "_specimen"})
    if (w.contains(o)) {
      other_given = true;
      rw.find(o);
      rw.problem("effects.wear." + o,
                 fmt::format("belongs to the other law; the {} law takes \"{}\" (or \"{}\" and \"{}\")",
                             to_string(effect.law), key, pad, specimen));
    }
  const Bound coefficient = within(spans::kMinWearCoefficient, spans::kMaxWearCoefficient, "a wear coefficient",
                                   "1/Pa", true);
  const bool together = w.contains(key), each = w.contains(pad) || w.contains(specimen);
  if (!each) {
    // The other law's coefficient in its place is one mistake, reported above, not also a missing key.
    if (together || !other_given) effect.coefficient = rw.number(key, std::nullopt, coefficient).value_or(1e-15);
    return;
  }
  effect.per_body = true;
  if (together) {
    rw.find(key);
    rw.problem("effects.wear." + key, fmt::format("given with \"{}\"/\"{}\"; give either \"{}\" (both bodies "
                                                  "together, with pad_fraction) or \"{}\" and \"{}\"",
                                                  pad, specimen, key, pad, specimen));
  }
  if (w.contains("pad_fraction")) {
    rw.find("pad_fraction");
    rw.problem("effects.wear.pad_fraction", fmt::format("given with \"{}\" and \"{}\", which set the pad's share "
                                                        "({} / ({} + {})); leave it out",
                                                        pad, specimen, pad, pad, specimen));
  }
  const Bound one_body{[coefficient](double v) { return v == 0.0 || coefficient.ok(v); },
                       "0 (the body does not wear) or " + coefficient.allowed};
  const auto c_pad = rw.number(pad, std::nullopt, one_body), c_specimen = rw.number(specimen, std::nullopt, one_body);
  if (!c_pad || !c_specimen) return;
  effect.coefficient = *c_pad + *c_specimen;
  if (!(effect.coefficient > 0.0)) {
    rw.problem("effects.wear." + pad, fmt::format("{} and {} are both 0: nothing wears; give a positive "
                                                  "coefficient to at least one body, or leave out effects.wear",
                                                  pad, specimen));
    return;
  }
  effect.coefficient_pad = *c_pad, effect.coefficient_specimen = *c_specimen;
  effect.pad_fraction = *c_pad / effect.coefficient;
}

// effects.wear: the law and its coefficient, the share of the pad, the cycles, the stepper, the records.
void parse_wear(Reader& r, Scene& s, Given& given, std::vector<std::string>& problems) {
  if (const json* w = r.object("wear", false)) {
    Reader rw(*w, "effects.wear", problems);
    WearEffect effect;
    const auto word = rw.string("law", "archard", "\"archard\" or \"energy\"");
    std::optional<wear::Law> law;
    if (word) {
      try {
        law = wear::law_from_string(*word);
      } catch (const InputError& e) {
        rw.problem("effects.wear.law", e.what());
      }
    }
    if (!law) {
      // Which coefficients belong is unknown until the law is: not unknown keys.
      for (const char* k : {"k", "alpha", "k_pad", "k_specimen", "alpha_pad", "alpha_specimen"}) rw.find(k);
    } else {
      effect.law = *law;
      parse_wear_coefficients(rw, *w, effect);
    }
    if (!effect.per_body)
      effect.pad_fraction = rw.number("pad_fraction", 0.5, {[](double v) { return v >= 0.0 && v <= 1.0; },
                                                            "a share in [0, 1]"})
                                .value_or(0.5);
    const auto cycles = rw.number("cycles", std::nullopt, {[](double v) { return v >= 1.0 && v <= 1e12 && v == std::floor(v); },
                                                           "a whole number of cycles from 1 to 1e12"});
    effect.cycles = cycles.value_or(1e12);  // records are checked against the cycles only when they are valid
    given.wear_cycles_ok = cycles.has_value();
    if (const auto stepper = rw.string("stepper", "implicit", stepper_words())) {
      try {
        effect.stepper = stepper_from_string(*stepper);
      } catch (const InputError& e) {
        rw.problem("effects.wear.stepper", e.what());
      }
    }
    // Below 1e-5 the implicit stepper's first error estimate stays above the tolerance whatever the step (the
    // contact solves' own tolerance sets a floor under it), and no step is ever accepted.
    effect.tolerance = rw.number("tolerance", 1e-3, {[](double v) { return v >= 1e-5 && v <= 0.1; },
                                                     "a relative tolerance in [1e-5, 0.1]"})
                           .value_or(1e-3);
    if (const json* rec = rw.find("record")) parse_record(rec, rw, effect);
    rw.finish();
    s.wear = effect;
  }
  if (r.find("wear") && !s.tangential) {
    s.tangential = TangentialEffect{};
    s.tangential_implied = true;
  }
}

// effects.stress: the map's points and depth.
void parse_stress(Reader& r, Scene& s, std::vector<std::string>& problems) {
  if (const json* st = r.object("stress", false)) {
    Reader rs(*st, "effects.stress", problems);
    StressEffect effect;
    const Bound points{[](double v) { return v >= 3 && v <= 2001 && v == std::floor(v); }, "a whole number from 3 to 2001"};
    effect.nx = int(rs.number("nx", 161.0, points).value_or(161.0));
    effect.ny = int(rs.number("ny", 81.0, points).value_or(81.0));
    const Bound depth = length("a depth");
    effect.depth = rs.number("depth", 0.0, {[depth](double v) { return v == 0.0 || depth.ok(v); },
                                            "0 (the contact half-width) or " + depth.allowed})
                       .value_or(0.0);
    rs.finish();
    s.stress = effect;
  }
}

// effects.life.initiation: the strain-life constants and the critical distance.
std::optional<LifeInitiation> parse_initiation(Reader& r, std::vector<std::string>& problems) {
  const json* i = r.object("initiation", false);
  if (!i) return std::nullopt;
  Reader ri(*i, "effects.life.initiation", problems);
  LifeInitiation e;
  const auto sigma_f = ri.number("sigma_f", std::nullopt, within(1e6, 1e11, "a fatigue strength coefficient", "Pa"));
  const auto b = ri.number("b", std::nullopt, {[](double v) { return v > -1.0 && v < 0.0; },
                                               "a fatigue strength exponent in (-1, 0)"});
  const auto eps_f = ri.number("eps_f", std::nullopt, {[](double v) { return v > 0.0 && v <= 10.0; },
                                                       "a fatigue ductility coefficient in (0, 10]"});
  const auto c = ri.number("c", std::nullopt, {[](double v) { return v > -2.0 && v < 0.0; },
                                               "a fatigue ductility exponent in (-2, 0)"});
  const Bound distance = length("a critical distance");
  const auto ell = ri.number("critical_distance", 0.0, {[distance](double v) { return v == 0.0 || distance.ok(v); },
                                                        "0 (the point method) or " + distance.allowed});
  ri.finish();
  if (!sigma_f || !b || !eps_f || !c || !ell) return std::nullopt;
  e.sigma_f = *sigma_f, e.b = *b, e.eps_f = *eps_f, e.c = *c, e.critical_distance = *ell;
  return e;
}

// effects.life.growth: Paris' constants, the threshold, the lengths, the short-crack correction and the mode.
std::optional<LifeGrowth> parse_growth(Reader& r, std::vector<std::string>& problems) {
  const json* gj = r.object("growth", false);
  if (!gj) return std::nullopt;
  Reader rg(*gj, "effects.life.growth", problems);
  LifeGrowth g;
  bool ok = true;
  if (const auto law = rg.string("law", "paris", "\"paris\""); law && *law != "paris") {
    rg.problem("effects.life.growth.law", fmt::format("\"{}\" is not a growth law; use \"paris\"", *law));
    ok = false;
  }
  const auto C = rg.number("C", std::nullopt, within(1e-60, 1e-3, "a Paris coefficient", "m/cycle per (Pa m^0.5)^m"));
  const auto m = rg.number("m", std::nullopt, {[](double v) { return v > 0.0 && v <= 20.0; },
                                               "a Paris exponent in (0, 20]"});
  const auto dK_th = rg.number("dK_th", 0.0, within(0.0, 1e9, "a threshold", "Pa m^0.5"));
  const auto a_final = rg.number("a_final", std::nullopt, length("a final crack length"));
  std::optional<double> a_initial;
  if (rg.find("a_initial")) a_initial = rg.number("a_initial", std::nullopt, length("an initial crack length"));
  std::optional<double> K_c;
  if (rg.find("K_c")) K_c = rg.number("K_c", std::nullopt, within(1e3, 1e10, "a fracture toughness", "Pa m^0.5"));
  const auto short_crack = rg.string("short_crack", "none", "\"none\" or \"el_haddad\"");
  if (short_crack && *short_crack != "none" && *short_crack != "el_haddad") {
    rg.problem("effects.life.growth.short_crack",
               fmt::format("\"{}\" is not a short-crack correction; use \"none\" or \"el_haddad\"", *short_crack));
    ok = false;
  }
  g.el_haddad = short_crack && *short_crack == "el_haddad";
  const bool short_crack_known = short_crack && (*short_crack == "none" || g.el_haddad);
  if (!short_crack_known) {
    rg.find("fatigue_limit");  // whether it belongs is unknown until the correction is
  } else if (g.el_haddad) {
    const auto limit = rg.number("fatigue_limit", std::nullopt, within(1e3, 1e11, "a fatigue limit (stress range)", "Pa"));
    if (limit) g.fatigue_limit = *limit;
    ok = ok && limit;
    if (dK_th && *dK_th == 0.0) {
      rg.problem("effects.life.growth.dK_th", "is 0 with short_crack \"el_haddad\", which scales the threshold; give "
                                              "the long-crack threshold (Pa m^0.5)");
      ok = false;
    }
  } else if (rg.find("fatigue_limit")) {
    rg.problem("effects.life.growth.fatigue_limit", "given without short_crack \"el_haddad\", which uses it; add "
                                                    "\"short_crack\": \"el_haddad\" or remove it");
    ok = false;
  }
  if (const auto mode = rg.string("mode", "I", words_list<GrowthMode>(kGrowthModeWords))) {
    try {
      g.mode = growth_mode_from_string(*mode);
    } catch (const InputError& e) {
      rg.problem("effects.life.growth.mode", e.what());
      ok = false;
    }
  }
  rg.finish();
  if (a_initial && a_final && !(*a_final > *a_initial)) {
    rg.problem("effects.life.growth.a_final", fmt::format("{} m is not longer than a_initial = {} m; the crack grows "
                                                          "from a_initial to a_final",
                                                          *a_final, *a_initial));
    ok = false;
  }
  if (!ok || !C || !m || !dK_th || !a_final || (rg.find("a_initial") && !a_initial) || (rg.find("K_c") && !K_c))
    return std::nullopt;
  g.C = *C, g.m = *m, g.dK_th = *dK_th, g.a_final = *a_final, g.a_initial = a_initial, g.K_c = K_c;
  return g;
}

// effects.life: initiation and/or growth, and the cycles past which a life is a runout.
void parse_life(Reader& r, Scene& s, std::vector<std::string>& problems) {
  const json* l = r.object("life", false);
  if (!l) return;
  Reader rl(*l, "effects.life", problems);
  LifeEffect effect;
  const std::size_t before = problems.size();
  effect.initiation = parse_initiation(rl, problems);
  effect.growth = parse_growth(rl, problems);
  effect.cycles_max = rl.number("cycles_max", 1e9, {[](double v) { return v >= 1.0 && v <= 1e15; },
                                                    "a number of cycles from 1 to 1e15"})
                          .value_or(1e9);
  rl.finish();
  if (problems.size() != before) return;
  if (!rl.find("initiation") && !rl.find("growth")) {
    rl.problem("effects.life", "has neither \"initiation\" nor \"growth\"; give one or both");
    return;
  }
  if (effect.growth && !effect.growth->a_initial) {
    const double ell = effect.initiation ? effect.initiation->critical_distance : 0.0;
    if (ell <= 0.0) {
      rl.problem("effects.life.growth.a_initial", "missing, and there is no critical distance to start from; give "
                                                  "the initial crack length (m)");
      return;
    }
    if (!(effect.growth->a_final > ell)) {
      rl.problem("effects.life.growth.a_final", fmt::format("{} m is not longer than the initial length, the "
                                                            "critical distance {} m",
                                                            effect.growth->a_final, ell));
      return;
    }
  }
  s.life = effect;
}

// effects.crack: where, at what angle, how long, the quadrature and the faces' friction.
void parse_crack(Reader& r, Scene& s, std::vector<std::string>& problems) {
  if (const json* c = r.object("crack", false)) {
    Reader rc(*c, "effects.crack", problems);
    CrackEffect effect;
    if (const json* at = rc.find("at")) {
      const Bound x = position("a position x");
      if (at->is_number() && std::isfinite(at->get<double>()) && x.ok(at->get<double>())) {
        effect.at = CrackPosition::x;
        effect.x = at->get<double>();
      } else if (at->is_string() && (*at == "trailing_edge" || *at == "leading_edge")) {
        effect.at = crack_position_from_string(at->get<std::string>());
      } else {
        rc.problem("effects.crack.at", fmt::format("{} is not allowed; give \"trailing_edge\", \"leading_edge\" "
                                                   "or {}", describe(*at), x.allowed));
      }
    }
    // Flatter cracks than CrackSpec::kMinAngle lie close to the surface over their whole length, where the
    // quadrature converges too slowly to trust (contact/crack_solver.hpp).
    constexpr double lo = CrackSpec::kMinAngle, hi = 180.0 - CrackSpec::kMinAngle;
    effect.angle_deg = rc.number("angle_deg", 90.0,
                                 {[](double v) { return v >= lo && v <= hi; },
                                  fmt::format("an angle to the surface in [{}, {}] degrees (90: normal to it)", lo, hi)})
                           .value_or(90.0);
    effect.face_friction = rc.number("face_friction", 0.0,
                                     {[](double v) { return v >= 0.0; }, "a Coulomb coefficient >= 0 (0: frictionless faces)"})
                               .value_or(0.0);
    effect.quadrature = int(rc.number("quadrature", 60.0, {[](double v) { return v >= 2 && v <= 1000 && v == std::floor(v); },
                                                          "a whole number of points from 2 to 1000"})
                                .value_or(60.0));
    const json* lengths = rc.find("lengths");
    if (!lengths) {
      rc.problem("effects.crack.lengths", "missing; give an array of crack lengths (m)");
    } else if (!lengths->is_array() || lengths->empty()) {
      rc.problem("effects.crack.lengths", fmt::format("{} is not a non-empty array of crack lengths (m)", describe(*lengths)));
    } else {
      const Bound crack_length = length("a crack length");
      for (std::size_t k = 0; k < lengths->size(); ++k) {
        const json& l = (*lengths)[k];
        if (!l.is_number() || !std::isfinite(l.get<double>()) || !crack_length.ok(l.get<double>())) {
          rc.problem(fmt::format("effects.crack.lengths[{}]", k),
                     fmt::format("{} is not allowed; give {}", describe(l), crack_length.allowed));
          break;
        }
        effect.lengths.push_back(l.get<double>());
      }
    }
    rc.finish();
    s.crack = effect;
  }
}

// effects: each effect's keys in a function of its own.
void parse_effects(Reader& top, Scene& s, Given& given, std::vector<std::string>& problems) {
  given.effects_unknown = top.find("effects") && !top.find("effects")->is_object();
  const json* e = top.object("effects", false);
  if (!e) return;
  Reader r(*e, "effects", problems);
  parse_tangential(r, s, problems);
  parse_wear(r, s, given, problems);
  parse_stress(r, s, problems);
  parse_crack(r, s, problems);
  parse_life(r, s, problems);
  r.finish();
}

// output: dir (default output/<name>) and plots.
void parse_output(Reader& top, Scene& s, std::vector<std::string>& problems) {
  if (const json* o = top.object("output", false)) {
    Reader r(*o, "output", problems);
    if (r.find("dir"))  // optional: output/<name> below
      if (auto dir = r.string("dir", std::nullopt, "a folder path")) {
        if (dir->empty()) r.problem("output.dir", "is empty; give a folder path");
        if (holds_nul(*dir)) r.problem("output.dir", fmt::format("{} {}", json(*dir).dump(), kHoldsNul));
        // A shell expands these, and fretwear would make a folder named "~" here, whose removal by hand
        // (rm -r ~/...) is the home folder's.
        if (!dir->empty() && (dir->front() == '~' || dir->front() == '$'))
          r.problem("output.dir", fmt::format("{} starts with {}, which a shell expands ({}) and fretwear does not: it "
                                              "would make a folder named {} here; give the path itself",
                                              json(*dir).dump(), dir->front(),
                                              dir->front() == '~' ? "the home folder" : "a variable",
                                              json(dir->substr(0, dir->find('/'))).dump()));
        s.output_dir = *dir;
      }
    s.plots = r.boolean("plots", true).value_or(true);
    r.finish();
  }
  if (s.output_dir.empty()) s.output_dir = std::filesystem::path("output") / s.name;
}

// What the effects need of the load, the friction and the bodies, and what is given that no effect uses.
void check_needs(const Scene& s, const Given& given, std::vector<std::string>& problems) {
  if (s.life && !given.effects_unknown && !s.tangential)
    problems.push_back("effects.life: needs the load cycle, whose stresses start the crack and whose SIFs grow it; "
                       "add \"tangential\": {} to effects, with friction and load.Q (or load.control "
                       "\"displacement\" with load.delta)");
  if (given.effects_unknown) {
    // reported above; what the effects need is checked once they are readable
  } else if (s.tangential) {
    const char* who = s.tangential_implied ? "effects.wear (through the load cycle it needs)" : "effects.tangential";
    if (!given.friction)
      problems.push_back(fmt::format("friction: missing; {} needs a friction coefficient in (0, 10]", who));
    if (!s.blocks.empty()) {
      double total = 0.0;
      for (const LoadBlock& b : s.blocks) total += b.cycles;
      if (!s.wear)
        problems.push_back("load.blocks: given without effects.wear; the cycle effect computes one steady cycle, and "
                           "only the wear stage runs the blocks one after another: add effects.wear, or give the one "
                           "load as load.Q, load.delta or load.history");
      else if (given.wear_cycles_ok && given.blocks_cycles_ok && s.wear->cycles != total)
        problems.push_back(fmt::format("effects.wear.cycles: {} is not the blocks' total, {}; the wear runs "
                                       "load.blocks once, in order: give their sum",
                                       s.wear->cycles, total));
      if (s.stress || s.crack || s.life)
        problems.push_back("load.blocks: given with effects.stress, effects.crack or effects.life, which are "
                           "computed at the top and the bottom of one steady cycle, while the blocks load a cycle "
                           "of their own each (and a life under blocks would need a damage sum over them, which "
                           "fretwear does not model): run the blocks with effects.wear alone, and each block's load "
                           "as a scene of its own for its stresses, cracks and life");
      // A force-controlled block after the first that slides: its wear is not determined, as for the scene's own
      // load (the first block's, checked below as load.Q), whatever the first block's control.
      if (s.wear && s.friction && given.P_ok)
        for (std::size_t i = 1; i < s.blocks.size(); ++i) {
          const LoadBlock& b = s.blocks[i];
          const double fP = *s.friction * s.P;
          const double Q = b.Q_amplitude ? *b.Q_amplitude : b.Q_ratio ? *b.Q_ratio * fP : 0.0;
          const char* why = "the bodies slide, and under force control the slip, hence the block's wear, is not "
                            "determined; give the block \"delta\" (displacement control) instead";
          if ((b.Q_amplitude || b.Q_ratio) && Q >= fP)
            problems.push_back(
                fmt::format("load.blocks[{}].Q: Q = {:.6g} N/m reaches f P = {:.6g} N/m: {}", i, Q, fP, why));
          for (const auto& pt : b.history)
            if (std::abs(pt[2]) >= *s.friction * pt[1]) {
              problems.push_back(fmt::format("load.blocks[{}].history: reaches |Q| = {:.6g} N/m >= f P = {:.6g} N/m "
                                             "at t = {:.6g}: {}",
                                             i, std::abs(pt[2]), *s.friction * pt[1], pt[0], why));
              break;
            }
        }
      if (s.bulk_stress != 0.0)
        for (std::size_t i = 0; i < s.blocks.size(); ++i)
          if (!s.blocks[i].history.empty())
            problems.push_back(fmt::format("load.blocks[{}].history: given with load.bulk_stress, which the "
                                           "history's sigma_bulk replaces; remove load.bulk_stress or give it in "
                                           "every history",
                                           i));
    }
    if (given.history) {
      if (given.Q)
        problems.push_back("load.Q: given with load.history, which gives Q at each point; remove load.Q");
      if (s.bulk_stress != 0.0)
        problems.push_back(
            "load.bulk_stress: given with load.history, which gives sigma_bulk at each point; remove it");
      if (given.control == LoadControl::displacement)
        problems.push_back("load.history: its points [t, P, Q, sigma_bulk] prescribe Q, which is force control, "
                           "while load.control \"displacement\" prescribes the relative displacement instead: use "
                           "load.control \"force\" with the history, or load.delta with a constant P");
      if (s.tangential->route == TangentialRoute::analogy)
        problems.push_back("effects.tangential.route: \"analogy\" cannot run load.history (the analogy needs a "
                           "constant P and Q between fixed limits); use \"auto\" or \"incremental\"");
      // Stress, crack and life take the history's top and bottom (the largest and the smallest Q) from the cycle;
      // where the history slides, force control determines no traction there.
      if ((s.stress || s.crack || s.life) && s.friction)
        for (const auto& pt : s.history)
          if (std::abs(pt[2]) >= *s.friction * pt[1]) {
            problems.push_back(fmt::format(
                "load.history: reaches |Q| = {:.6g} N/m >= f P = {:.6g} N/m at t = {:.6g}, where the bodies slide "
                "and force control leaves the traction undetermined; effects.stress, effects.crack and effects.life "
                "need the traction at the history's top and bottom: keep |Q| < f P at every point",
                std::abs(pt[2]), *s.friction * pt[1], pt[0]));
            break;
          }
    } else if (!given.control || !given.load_read || given.loads_unknown) {
      // the load control is unknown, or so is the whole load: nothing more to ask for
    } else if (given.control == LoadControl::force) {
      if (!given.Q)
        problems.push_back(fmt::format("load.Q: missing; {} needs {{\"amplitude\": Q (N/m)}} or {{\"ratio\": Q/(fP)}}",
                                       who));
      if (given.delta)
        problems.push_back("load.delta: given, but load.control is \"force\"; set load.control to \"displacement\" "
                           "or remove load.delta");
      if (s.wear && s.friction && given.P_ok && s.Q_max() >= *s.friction * s.P)
        problems.push_back(sliding_under_force_control(s.Q_max(), *s.friction * s.P));
    } else {
      if (!given.delta)
        problems.push_back("load.delta: missing; load.control \"displacement\" needs the amplitude of the relative "
                           "tangential displacement of the reference points, " + displacement_amplitude().allowed);
      if (given.Q)
        problems.push_back("load.Q: given with load.control \"displacement\", where Q is the result; remove load.Q");
      if (s.tangential->route == TangentialRoute::analogy)
        problems.push_back("effects.tangential.route: \"analogy\" cannot run load.control \"displacement\" (the "
                           "analogy needs Q between fixed limits); use \"auto\" or \"incremental\"");
    }
    const ElasticPair pair(s.pad.E > 0 ? s.pad : Material{1, 0}, s.specimen.E > 0 ? s.specimen : Material{1, 0}, s.plane);
    // Dissimilar bodies: the incremental route couples the normal and tangential problems under force control.
    if (given.materials_ok && std::abs(pair.beta()) > 1e-12) {
      const std::string dissimilar = fmt::format("materials: dissimilar bodies (Dundurs beta = {:.4g}) couple the "
                                                 "normal and tangential problems",
                                                 pair.beta());
      if (s.tangential->route == TangentialRoute::analogy)
        problems.push_back(dissimilar + "; effects.tangential.route \"analogy\" needs similar bodies (beta = 0): "
                                        "use \"auto\" or \"incremental\"");
      // Stress, crack and life take the coupled pressure at the top and the bottom of the cycle; in gross slip under
      // force control the incremental route solves no cycle, so there is none to take.
      if ((s.stress || s.crack || s.life) && given.control == LoadControl::force && !given.history && s.friction &&
          given.P_ok && given.Q && s.Q_max() >= *s.friction * s.P)
        problems.push_back(dissimilar + fmt::format("; with load.Q = {:.6g} N/m >= f P = {:.6g} N/m the bodies slide "
                                                    "and force control solves no coupled pressure, which "
                                                    "effects.stress, effects.crack and effects.life need: lower "
                                                    "load.Q or use load.control \"displacement\"",
                                                    s.Q_max(), *s.friction * s.P));
    }
  } else {
    if (given.Q)
      problems.push_back("load.Q: given, but no effect uses it; add \"tangential\": {} to effects or remove load.Q");
    if (s.bulk_stress != 0.0)
      problems.push_back("load.bulk_stress: given, but no effect uses it; add \"tangential\": {} to effects");
    if (given.friction)
      problems.push_back("friction: given, but no effect uses it; add \"tangential\": {} to effects");
    if (given.history)
      problems.push_back("load.history: given, but no effect uses it; add \"tangential\": {} to effects");
    if (given.control != LoadControl::force || given.delta)
      problems.push_back("load.control, load.delta: given, but no effect uses them; add \"tangential\": {} to "
                         "effects");
    if (given.reference_depth)
      problems.push_back("grid.reference_depth: given, but no effect uses it (the displacement datum serves the load "
                         "cycle); add \"tangential\": {} to effects");
  }
}

// The profile against the window: the lowest point inside a given window; a window for a lone waviness.
void check_window(const Scene& s, const Given& given, std::vector<std::string>& problems) {
  // Whole-scene checks, once the parts are readable.
  const bool profile_ok = std::none_of(problems.begin(), problems.end(),
                                       [](const std::string& p) { return p.rfind("profile", 0) == 0; });
  if (profile_ok) {
    try {
      Profile profile(s.profile);
      if (s.window) {
        // The lowest point, or one as low (1e-15 m: round-off) of another asperity: of equal asperities any one.
        const double x = profile.lowest_point();
        const auto inside = [&](double p) { return p >= s.window->first && p <= s.window->second; };
        bool holds = inside(x);
        for (double a : asperity_lowest_points(profile))
          holds = holds || (inside(a) && profile.gap(a) <= profile.gap(x) + 1e-15);
        if (!holds)
          problems.push_back(fmt::format("grid.window: [{}, {}] does not contain the profile's lowest point x = {} m",
                                         s.window->first, s.window->second, x));
      } else if (profile.periodic() && !given.window) {
        problems.push_back("grid.window: missing; a profile whose lowest point repeats (a lone waviness) needs "
                           "[x_min, x_max] (m)");
      }
    } catch (const InputError& e) {
      problems.push_back(e.what());
    }
  }
}

}  // namespace

Scene parse_scene(const json& j, const std::string& default_name, const std::filesystem::path& scene_dir) {
  std::vector<std::string> problems;
  Scene s;
  if (!j.is_object()) throw SceneError({fmt::format("(top): the scene is {}; give a JSON object", type_name(j))});
  Reader top(j, "", problems);
  Given given;
  bool folder_read = parse_naming(top, default_name, s);  // the output folder is known: name, output read well
  const std::size_t n_problems_before_materials = problems.size();
  parse_materials(top, s, problems);
  given.materials_ok = problems.size() == n_problems_before_materials;
  if (const json* p = top.find("profile")) {
    s.profile = parse_profile(*p, "profile", problems, 0, scene_dir);
  } else {
    top.problem("profile", "missing; give an object with a \"type\" (" + profile_type_words() + ")");
  }

  given.friction = top.find("friction") != nullptr;
  if (given.friction)
    s.friction = top.number("friction", std::nullopt,
                            {[](double v) { return v > 0.0 && v <= 10.0; }, "a friction coefficient in (0, 10]"});
  parse_load(top, s, given, problems);
  parse_grid(top, s, given, problems);
  parse_effects(top, s, given, problems);
  const std::size_t n_problems_before_output = problems.size();
  parse_output(top, s, problems);
  folder_read = folder_read && problems.size() == n_problems_before_output;
  top.finish();
  check_needs(s, given, problems);
  check_window(s, given, problems);
  if (!problems.empty()) {
    SceneError e(std::move(problems));
    if (folder_read) e.output_dir = s.output_dir;
    throw e;
  }
  return s;
}

namespace {

// An iterator over a scene's text that counts the characters the JSON parser has read, so that the SAX events, which
// carry no position, can name their line.
class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* at, std::size_t* n_read) : at_(at), n_read_(n_read) {}
  reference operator*() const { return *at_; }
  CountingIterator& operator++() {
    ++at_;
    ++*n_read_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const CountingIterator& other) const { return at_ == other.at_; }

 private:
  const char* at_;
  std::size_t* n_read_;
};

// Builds the document from nlohmann's SAX events, as its json_sax_dom_parser does, and keeps what a document
// forgets: the JSON path of each value and the line of each key. A key given twice in an object, a number that
// overflows a double and nesting deeper than kMaxSceneDepth become problems naming the path and the line; a syntax
// error becomes one naming the source, with nlohmann's line and column. The work stays linear in the text: a path
// is kept as its parts and written out only for a problem.
class SceneText {
 public:
  SceneText(std::string_view text, std::string source, json& root)
      : text_(text), source_(std::move(source)), root_(root) {}

  CountingIterator begin() { return {text_.data(), &n_read_}; }
  CountingIterator end() { return {text_.data() + text_.size(), &n_read_}; }

  // The problems of the text: the keys given more than once (in the order of their second line), then what stopped
  // the parser, if anything did.
  std::vector<std::string> problems() {
    std::stable_sort(duplicates_.begin(), duplicates_.end(),
                     [](const Duplicate& a, const Duplicate& b) { return a.lines[1] < b.lines[1]; });
    std::vector<std::string> out;
    for (const auto& d : duplicates_) {
      std::string lines;
      for (std::size_t i = 0; i < d.lines.size(); ++i)
        lines += (i == 0 ? "" : i + 1 == d.lines.size() ? " and " : ", ") + std::to_string(d.lines[i]);
      const std::string times = d.lines.size() == 2 ? "twice" : fmt::format("{} times", d.lines.size());
      out.push_back(fmt::format("{}: given {} (lines {}); give each key once", d.path, times, lines));
    }
    if (n_duplicates_ > duplicates_.size())
      out.push_back(fmt::format("(top): {} more keys are given more than once; give each key once",
                                n_duplicates_ - duplicates_.size()));
    if (stop_) out.push_back(*stop_);
    return out;
  }

  // The SAX events (nlohmann/detail/input/json_sax.hpp).
  bool null() { return value(nullptr); }
  bool boolean(bool v) { return value(v); }
  bool number_integer(json::number_integer_t v) { return value(v); }
  bool number_unsigned(json::number_unsigned_t v) { return value(v); }
  bool number_float(json::number_float_t v, const json::string_t&) { return value(v); }
  bool string(json::string_t& v) { return value(std::move(v)); }
  bool binary(json::binary_t& v) { return value(std::move(v)); }
  bool start_object(std::size_t) { return open(json::value_t::object); }
  bool start_array(std::size_t) { return open(json::value_t::array); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }

  bool key(json::string_t& k) {
    Frame& f = frames_.back();
    f.lines[k].push_back(line_at(n_read_));  // the parser has just read the key's closing quote
    f.key = k;
    element_ = &(*f.value)[k];  // a key given again replaces the value; the duplicate is a problem
    return true;
  }

  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) {
    if (e.id == 406) {  // out_of_range.406: the number overflows a double
      stop_ = fmt::format("{}: {} on line {} overflows a double; give a number between -1.8e308 and 1.8e308 (and "
                          "within the key's range)",
                          path(frames_.size(), next_part()), shortened(token), line_at(position));
    } else {
      // NaN and Infinity, which some writers emit for floats, are no JSON numbers: say so, and what to give.
      const std::size_t colon = token.find_last_of(":[,");  // the value's own text, after its key or comma
      std::string value = token.substr(colon == std::string::npos ? 0 : colon + 1);
      value.erase(0, value.find_first_not_of(" \t\r\n-"));
      const bool not_number = !value.empty() && std::string("NnIi").find(value.front()) != std::string::npos;
      stop_ = fmt::format("{}: not valid JSON (UTF-8) at {}: {}{}", source_, path(frames_.size(), next_part()), e.what(),
                          not_number ? "; NaN and Infinity are not JSON numbers: give a finite number within the key's "
                                       "range (\"Ranges\" in docs/SCENES.md)"
                                     : "");
    }
    close_all();
    return false;
  }

 private:
  struct Frame {
    json* value;                                            // the object or array being filled
    std::string part;                                       // its part of the path: "key", ".key" or "[i]"
    std::string key;                                        // an object's latest key
    std::map<std::string, std::vector<std::size_t>> lines;  // an object's keys, each with the lines it is on
  };
  struct Duplicate {
    std::string path;
    std::vector<std::size_t> lines;
  };
  static constexpr std::size_t kMaxDuplicatesNamed = 100;

  static std::string shortened(const std::string& s) { return s.size() > 40 ? s.substr(0, 37) + "..." : s; }

  // The part of the path that names the value the parser reads next.
  std::string next_part() const {
    if (frames_.empty()) return "";
    const Frame& f = frames_.back();
    if (f.value->is_array()) return fmt::format("[{}]", f.value->size());
    return (frames_.size() == 1 ? "" : ".") + shortened(f.key);
  }

  // The JSON path of the first n open frames followed by last; "(top)" when empty.
  std::string path(std::size_t n, const std::string& last) const {
    std::string p;
    for (std::size_t i = 0; i < n; ++i) p += frames_[i].part;
    p += last;
    return p.empty() ? "(top)" : p;
  }

  // The line (from 1) of the character before offset.
  std::size_t line_at(std::size_t offset) {
    offset = std::min(offset, text_.size());
    if (offset >= counted_to_)
      n_newlines_ += std::size_t(std::count(text_.begin() + counted_to_, text_.begin() + offset, '\n'));
    else
      n_newlines_ -= std::size_t(std::count(text_.begin() + offset, text_.begin() + counted_to_, '\n'));
    counted_to_ = offset;
    return n_newlines_ + 1;
  }

  template <typename Value>
  json* place(Value&& v) {
    if (frames_.empty()) {
      root_ = json(std::forward<Value>(v));
      return &root_;
    }
    json& container = *frames_.back().value;
    if (container.is_array()) {
      container.push_back(json(std::forward<Value>(v)));
      return &container.back();
    }
    *element_ = json(std::forward<Value>(v));
    return element_;
  }

  template <typename Value>
  bool value(Value&& v) {
    place(std::forward<Value>(v));
    return true;
  }

  bool open(json::value_t type) {
    std::string part = next_part();
    if (frames_.size() >= kMaxSceneDepth) {
      stop_ = fmt::format("{}: {}: nests deeper than {} objects and arrays (line {}); a scene needs far fewer levels",
                          source_, shortened(path(frames_.size(), part)), kMaxSceneDepth, line_at(n_read_));
      close_all();
      return false;
    }
    json* v = place(type);
    frames_.push_back({v, std::move(part), {}, {}});
    return true;
  }

  bool close() {
    const Frame& f = frames_.back();
    for (const auto& [k, lines] : f.lines) {
      if (lines.size() < 2) continue;
      if (++n_duplicates_ <= kMaxDuplicatesNamed)
        duplicates_.push_back({path(frames_.size(), (frames_.size() == 1 ? "" : ".") + shortened(k)), lines});
    }
    frames_.pop_back();
    return true;
  }

  // Reports the duplicates of the objects still open when the parser stops.
  void close_all() {
    while (!frames_.empty()) close();
  }

  std::string_view text_;
  std::string source_;
  json& root_;
  std::size_t n_read_ = 0;                       // characters the parser has read
  std::size_t counted_to_ = 0, n_newlines_ = 0;  // newlines in text_[0, counted_to_)
  std::vector<Frame> frames_;                    // the open objects and arrays, outermost first
  json* element_ = nullptr;                      // where an object's next value goes
  std::vector<Duplicate> duplicates_;            // the first kMaxDuplicatesNamed
  std::size_t n_duplicates_ = 0;
  std::optional<std::string> stop_;              // what stopped the parser
};

}  // namespace

Scene parse_scene_text(std::string_view text, const std::string& default_name, const std::string& source,
                       const std::filesystem::path& scene_dir) {
  json j;
  SceneText reader(text, source, j);
  const bool complete = json::sax_parse(reader.begin(), reader.end(), &reader);
  std::vector<std::string> problems = reader.problems();
  if (!complete) throw SceneError(std::move(problems));
  // Outside a string the JSON reader takes a NUL byte for the end of the text, and would ignore what follows it.
  if (const auto nul = text.find('\0'); nul != std::string_view::npos)
    throw SceneError({fmt::format("{}: holds a NUL byte on line {}; a scene is UTF-8 text", source,
                                  1 + std::count(text.begin(), text.begin() + std::ptrdiff_t(nul), '\n'))});
  std::optional<std::filesystem::path> output_dir;
  try {
    Scene s = parse_scene(j, default_name, scene_dir);
    if (problems.empty()) return s;
  } catch (const SceneError& e) {
    if (problems.empty()) output_dir = e.output_dir;  // a key given twice may be the folder's
    problems.insert(problems.end(), e.problems().begin(), e.problems().end());
  }
  SceneError e(std::move(problems));
  e.output_dir = output_dir;
  throw e;
}

Scene load_scene(const std::filesystem::path& path) {
  namespace fs = std::filesystem;
  if (path == kStdinScene) {  // read once, to its end: a pipe cannot be read again, so it is taken whole or refused
    std::string text(kMaxSceneBytes + 1, '\0');
    std::cin.read(text.data(), std::streamsize(text.size()));
    if (std::cin.bad()) throw SceneError({"standard input: cannot be read"});
    text.resize(std::size_t(std::cin.gcount()));
    if (text.size() > kMaxSceneBytes)
      throw SceneError({fmt::format("standard input: holds more than {} bytes, the most a scene may be",
                                    kMaxSceneBytes)});
    if (text.empty())  // closed, or nothing piped into it
      throw SceneError({"standard input: is empty; give the scene on it (fretwear run - < scene.json), or its path"});
    return parse_scene_text(text, "stdin", "standard input", fs::path());
  }
  std::error_code ec;
  const auto status = fs::status(path, ec);
  if (ec || !fs::exists(status)) throw SceneError({path.string() + ": no such file"});
  if (fs::is_directory(status)) throw SceneError({path.string() + ": is a directory; give a scene file (.json)"});
  if (!fs::is_regular_file(status))  // a pipe or a device: its size is unknown and its reading may never end
    throw SceneError({path.string() + ": is not a regular file (a pipe or a device); give a scene file, or - to read "
                                      "the scene from standard input"});
  const auto size = fs::file_size(path, ec);
  if (ec) throw SceneError({path.string() + ": cannot be read (" + ec.message() + ")"});
  if (size > kMaxSceneBytes)
    throw SceneError({fmt::format("{}: is {} bytes; a scene is at most {} bytes", path.string(), size, kMaxSceneBytes)});
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError({path.string() + ": cannot be opened for reading"});
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_scene_text(buf.str(), path.stem().string(), path.string(), path.parent_path());
}

json Scene::to_json() const {
  json j;
  j["name"] = name;
  j["plane"] = to_string(plane);
  auto mat = [](const Material& m) { return json{{"E", m.E}, {"nu", m.nu}}; };
  if (similar)
    j["materials"] = {{"both", mat(pad)}};
  else
    j["materials"] = {{"pad", mat(pad)}, {"specimen", mat(specimen)}};
  j["profile"] = profile_to_json(profile);
  j["load"] = {{"P", P}};
  if (Q_amplitude) j["load"]["Q"] = {{"amplitude", *Q_amplitude}};
  if (Q_ratio) j["load"]["Q"] = {{"ratio", *Q_ratio}};
  if (tangential) j["load"]["bulk_stress"] = {{"amplitude", bulk_stress}};
  if (tangential) j["load"]["control"] = to_string(control);
  if (delta) j["load"]["delta"] = *delta;
  if (!history.empty()) j["load"]["history"] = history;
  if (!blocks.empty()) {  // the first block's load stands for the scene's own: only the blocks are written
    for (const char* key : {"Q", "delta", "history", "control"}) j["load"].erase(key);
    json b = json::array();
    for (const LoadBlock& block : blocks) {
      json one = {{"cycles", block.cycles}};
      if (block.Q_amplitude) one["Q"] = {{"amplitude", *block.Q_amplitude}};
      if (block.Q_ratio) one["Q"] = {{"ratio", *block.Q_ratio}};
      if (block.delta) one["delta"] = *block.delta;
      if (!block.history.empty()) one["history"] = block.history;
      b.push_back(std::move(one));
    }
    j["load"]["blocks"] = std::move(b);
  }
  if (friction) j["friction"] = *friction;
  j["grid"] = {{"cells", cells}};
  if (window) j["grid"]["window"] = {window->first, window->second};
  if (reference_depth) j["grid"]["reference_depth"] = *reference_depth;
  j["effects"] = json::object();
  if (tangential)
    j["effects"]["tangential"] = {{"route", to_string(tangential->route)}, {"increments", tangential->increments}};
  if (stress) j["effects"]["stress"] = {{"nx", stress->nx}, {"ny", stress->ny}, {"depth", stress->depth}};
  if (life) {
    json l = {{"cycles_max", life->cycles_max}};
    if (life->initiation) {
      const LifeInitiation& i = *life->initiation;
      l["initiation"] = {{"sigma_f", i.sigma_f}, {"b", i.b}, {"eps_f", i.eps_f}, {"c", i.c},
                         {"critical_distance", i.critical_distance}};
    }
    if (life->growth) {
      const LifeGrowth& g = *life->growth;
      json gj = {{"law", "paris"}, {"C", g.C}, {"m", g.m}, {"dK_th", g.dK_th}, {"a_initial", life->a_initial()},
                 {"a_final", g.a_final}, {"short_crack", g.el_haddad ? "el_haddad" : "none"}, {"mode", to_string(g.mode)}};
      if (g.K_c) gj["K_c"] = *g.K_c;
      if (g.el_haddad) gj["fatigue_limit"] = g.fatigue_limit;
      l["growth"] = gj;
    }
    j["effects"]["life"] = l;
  }
  if (crack) {
    j["effects"]["crack"] = {{"angle_deg", crack->angle_deg}, {"lengths", crack->lengths},
                             {"quadrature", crack->quadrature}, {"face_friction", crack->face_friction}};
    if (crack->at == CrackPosition::x)
      j["effects"]["crack"]["at"] = crack->x;
    else
      j["effects"]["crack"]["at"] = to_string(crack->at);
  }
  if (wear) {
    const std::string key = wear->law == wear::Law::archard ? "k" : "alpha";
    json w = {{"law", to_string(wear->law)}, {"cycles", wear->cycles}};
    if (wear->per_body) {
      w[key + "_pad"] = wear->coefficient_pad;
      w[key + "_specimen"] = wear->coefficient_specimen;
    } else {
      w[key] = wear->coefficient;
      w["pad_fraction"] = wear->pad_fraction;
    }
    w.update(json{{"stepper", to_string(wear->stepper)}, {"tolerance", wear->tolerance}});
    if (wear->record_count > 0)
      w["record"] = wear->record_count;
    else
      w["record"] = wear->record;
    j["effects"]["wear"] = w;
  }
  j["output"] = {{"dir", output_dir.generic_string()}, {"plots", plots}};
  return j;
}

std::vector<std::string> default_effect_words() { return {"normal", "tangential", "wear", "stress", "crack", "life"}; }

json default_scene_json(const std::string& effect) {
  const auto words = default_effect_words();
  if (!effect.empty() && std::find(words.begin(), words.end(), effect) == words.end())
    throw InputError(fmt::format("--effect: \"{}\" is not an effect; use {}", effect, join(words)));
  json j = {{"name", effect.empty() ? "hertz_all" : "hertz_" + effect},
            {"plane", "strain"},
            {"materials", {{"both", {{"E", 200e9}, {"nu", 0.3}}}}},
            {"profile", {{"type", "cylinder"}, {"R", 0.01}}},
            {"load", {{"P", 1.0e5}}},
            {"grid", {{"cells", 1024}}}};
  if (effect == "normal") return parse_scene(j).to_json();
  // Every effect (or the one asked for) with its required keys at PHYSICS.md's Hertz case and the rest defaulted,
  // and the load cycle the effects after the normal one need.
  j["friction"] = 0.5;
  j["load"]["Q"] = {{"ratio", 0.5}};
  j["load"]["bulk_stress"] = {{"amplitude", 0.0}};
  const json all = {
      {"tangential", json::object()},
      {"wear", {{"law", "archard"}, {"k", 1e-15}, {"cycles", 1e6}}},
      {"stress", json::object()},
      {"crack", {{"at", "trailing_edge"}, {"lengths", {1e-5, 2e-5, 5e-5, 1e-4}}}},
      {"life", {{"initiation", {{"sigma_f", 1.817e9}, {"b", -0.08}, {"eps_f", 0.35}, {"c", -0.52},
                                {"critical_distance", 2e-5}}},
                {"growth", {{"law", "paris"}, {"C", 5e-30}, {"m", 3.0}, {"a_final", 1e-3}}}}}};
  j["effects"] = json::object();
  for (const auto& [name, value] : all.items())
    if (effect.empty() || name == effect || name == "tangential") j["effects"][name] = value;
  return parse_scene(j).to_json();
}

bool utf8_text(const std::string& text) {
  try {
    (void)json(text).dump();
    return true;
  } catch (const json::type_error&) {
    return false;
  }
}

bool holds_nul(std::string_view path) { return path.find('\0') != std::string_view::npos; }

std::string fnv1a64(std::string_view bytes) {
  std::uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return fmt::format("fnv1a64:{:016x}", hash);
}

}  // namespace fretwear
