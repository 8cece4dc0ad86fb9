#include "python/tables.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <pybind11/numpy.h>

#include "contact/subsurface_stress.hpp"

namespace py = pybind11;

namespace fretwear::python {

namespace {

// A column's array as the table hands it out: read-only for good, over an immutable bytes object (numpy refuses to
// set its WRITEABLE flag again), so that table.x, table["x"] and to_dict() can hand out the one array without one
// caller changing another's data; array.copy() gives a writeable array of the caller's own.
py::object frozen(const py::array& values) {
  return py::module_::import("numpy").attr("frombuffer")(values.attr("tobytes")(),
                                                          py::arg("dtype") = values.attr("dtype"));
}

}  // namespace

void Table::check_rows(std::size_t n) {
  if (columns_.empty()) rows_ = n;
  if (n != rows_) throw std::logic_error(fmt::format("{}: a column of {} rows in a table of {}", file_, n, rows_));
}

void Table::add(std::string name, std::string unit, std::string meaning, const std::vector<double>& values) {
  check_rows(values.size());
  columns_.push_back({std::move(name), std::move(unit), std::move(meaning),
                      frozen(py::array_t<double>(py::ssize_t(values.size()), values.data()))});
}

void Table::add_labels(std::string name, std::string meaning, const std::vector<std::string>& values) {
  check_rows(values.size());
  py::list list;
  for (const auto& v : values) list.append(py::str(v));
  columns_.push_back({std::move(name), "", std::move(meaning),
                      frozen(py::module_::import("numpy").attr("array")(list, py::arg("dtype") = "str"))});
}

void Table::add_integers(std::string name, std::string meaning, const std::vector<long>& values) {
  check_rows(values.size());
  columns_.push_back({std::move(name), "1", std::move(meaning),
                      frozen(py::array_t<long>(py::ssize_t(values.size()), values.data()))});
}

std::string quoted_name(const std::string& name) {
  std::string quoted = "\"";
  for (const char c : name)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      quoted += fmt::format("\\x{:02x}", static_cast<unsigned char>(c));
    else
      quoted += c;
  return quoted + "\"";
}

const Column& Table::column(const std::string& name) const {
  for (const Column& c : columns_)
    if (c.name == name) return c;
  std::string names;
  for (const Column& c : columns_) names += (names.empty() ? "" : ", ") + c.name;
  throw py::key_error(fmt::format("{} has no column {}; its columns: {}", file_, quoted_name(name), names));
}

pybind11::tuple Table::state() const {
  py::list columns;
  for (const Column& c : columns_) columns.append(py::make_tuple(c.name, c.unit, c.meaning, c.values));
  return py::make_tuple(file_, meaning_, columns);
}

Table Table::from_state(const pybind11::tuple& state) {
  if (state.size() != 3) throw std::runtime_error("a pickled fretwear.Table holds 3 items");
  Table t(state[0].cast<std::string>(), state[1].cast<std::string>());
  for (const auto& item : state[2].cast<py::list>()) {
    const auto c = item.cast<py::tuple>();
    if (c.size() != 4) throw std::runtime_error("a pickled fretwear.Table's column holds 4 items");
    const auto values = py::array::ensure(c[3]);
    if (!values || values.ndim() != 1) throw std::runtime_error("a pickled fretwear.Table's column is a 1-D array");
    t.check_rows(std::size_t(values.size()));
    t.columns_.push_back(
        {c[0].cast<std::string>(), c[1].cast<std::string>(), c[2].cast<std::string>(), frozen(values)});
  }
  return t;
}

std::string Table::describe() const {
  if (file_.empty() && columns_.empty()) return "an empty fretwear.Table: no file, no columns";
  std::string s = fmt::format("{}: {}; {} rows\n", file_, meaning_, rows_);
  for (const Column& c : columns_)
    s += fmt::format("  {:<16} {:<8} {}\n", c.name, c.unit.empty() ? "label" : c.unit, c.meaning);
  return s;
}

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();  // what the CSV leaves empty

template <typename Item, typename Get>
std::vector<double> of(const std::vector<Item>& items, Get get) {
  std::vector<double> v;
  v.reserve(items.size());
  for (const Item& item : items) v.push_back(get(item));
  return v;
}

std::vector<double> cell_centres(const Grid& grid) {
  std::vector<double> x(std::size_t(grid.n));
  for (int i = 0; i < grid.n; ++i) x[std::size_t(i)] = grid.x(i);
  return x;
}

Table contact_table(const NormalResult& n) {
  Table t("contact.csv", "the contact under the normal load P alone, per cell");
  t.add("x", "m", "cell centre", cell_centres(n.grid));
  t.add("gap0", "m", "initial gap (inf off the pad)", n.g0);
  t.add("p", "Pa", "contact pressure", n.state.p);
  t.add("gap", "m", "gap under load", n.state.gap);
  if (n.reference) t.add("p_closed_form", "Pa", "the closed form's cell-average pressure", n.reference->p_cell);
  return t;
}

Table cycle_table(const NormalResult& n, const CycleStage& st) {
  const CycleResult& c = st.result;
  Table t("cycle.csv", "the steady load cycle, per cell");
  t.add("x", "m", "cell centre", cell_centres(n.grid));
  t.add("p", "Pa", "contact pressure under P alone", n.state.p);
  t.add("q_top", "Pa", "shear traction at the top of the cycle", c.q_top);
  t.add("q_unloaded", "Pa", "shear traction unloaded (Q = 0 after the top)", c.q_unloaded);
  t.add("q_bottom", "Pa", "shear traction at the bottom of the cycle", c.q_bottom);
  t.add("q_reloaded", "Pa", "shear traction reloaded (Q = 0 after the bottom)", c.q_reloaded);
  t.add("slip_range", "m", "peak-to-peak relative tangential displacement", c.slip_range);
  t.add("slip_per_cycle", "m", "distance slipped per cycle", c.slip_travelled);
  t.add("energy_density", "J/m^2", "frictional energy per cycle per unit area", c.energy_density);
  if (st.plan.dissimilar()) {
    t.add("p_top", "Pa", "coupled pressure at the top of the cycle", st.p_top);
    t.add("p_bottom", "Pa", "coupled pressure at the bottom of the cycle", st.p_bottom);
  }
  return t;
}

Table loop_table(const CycleResult& c) {
  Table t("loop.csv", "the fretting loop: the first loading, then the steady cycle top to top");
  std::vector<std::string> phase;
  std::vector<LoopPoint> points;
  for (const LoopPoint& l : c.first_loading) phase.push_back("first_loading"), points.push_back(l);
  for (const LoopPoint& l : c.loop) phase.push_back("cycle"), points.push_back(l);
  t.add_labels("phase", "\"first_loading\" or \"cycle\"", phase);
  t.add("P", "N/m", "normal load", of(points, [](const LoopPoint& l) { return l.P; }));
  t.add("Q", "N/m", "tangential load", of(points, [](const LoopPoint& l) { return l.Q; }));
  t.add("delta", "m", "displacement of the pad relative to the specimen at the reference points",
        of(points, [](const LoopPoint& l) { return l.delta; }));
  return t;
}

Table wear_history_table(const WearStage& w) {
  Table t("wear_history.csv", "one row per wear record");
  const auto& r = w.records;
  const bool asymptote = w.asymptote.unavailable.empty();
  t.add("cycles", "1", "cycles at the record", of(r, [](const WearRecord& x) { return x.cycles; }));
  t.add("worn_area", "m^2", "worn area", of(r, [](const WearRecord& x) { return x.worn_area; }));
  t.add("max_depth", "m", "largest worn depth", of(r, [](const WearRecord& x) { return x.max_depth; }));
  t.add("fraction_of_asymptote", "1", "worn area over the asymptote's (NaN without one)",
        of(r, [asymptote](const WearRecord& x) { return asymptote ? x.fraction : kNaN; }));
  t.add("stick_left", "m", "left end of the stick zone (NaN where all slips)",
        of(r, [](const WearRecord& x) { return x.stick_zone ? x.stick_zone->first : kNaN; }));
  t.add("stick_right", "m", "right end of the stick zone (NaN where all slips)",
        of(r, [](const WearRecord& x) { return x.stick_zone ? x.stick_zone->second : kNaN; }));
  t.add("contact_left", "m", "left end of the loaded contact", of(r, [](const WearRecord& x) { return x.contact.first; }));
  t.add("contact_right", "m", "right end of the loaded contact",
        of(r, [](const WearRecord& x) { return x.contact.second; }));
  t.add("p_max", "Pa", "peak pressure", of(r, [](const WearRecord& x) { return x.p_max; }));
  if (!r.empty() && r.front().block >= 0) {
    std::vector<long> block;
    for (const WearRecord& x : r) block.push_back(x.block);
    t.add_integers("block", "the block of load.blocks the record is under (from 0)", block);
  }
  return t;
}

// wear_stick_zones.csv: zone by zone, one row per record holding that zone (written with several stick zones).
Table wear_stick_zones_table(const WearStage& w) {
  Table t("wear_stick_zones.csv", "one row per stick zone and record, zone by zone (zones from 0, left to right)");
  std::size_t most = 0;
  for (const WearRecord& r : w.records) most = std::max(most, r.stick_zones.size());
  std::vector<double> cycles, left, right;
  std::vector<long> zone;
  for (std::size_t k = 0; k < most; ++k)
    for (const WearRecord& r : w.records)
      if (k < r.stick_zones.size()) {
        cycles.push_back(r.cycles);
        zone.push_back(long(k));
        left.push_back(r.stick_zones[k].first);
        right.push_back(r.stick_zones[k].second);
      }
  t.add("cycles", "1", "cycles at the record", cycles);
  t.add_integers("zone", "the stick zone, from 0, left to right in its record", zone);
  t.add("stick_left", "m", "left end of the stick zone", left);
  t.add("stick_right", "m", "right end of the stick zone", right);
  return t;
}

Table profiles_table(const Scene& scene, const NormalResult& n, const WearStage& w) {
  Table t("profiles.csv",
          "the worn profile per record and cell (record k: rows k*cells ... k*cells + cells - 1), then the asymptote "
          "with cycles = inf");
  const double pad = scene.wear->pad_fraction;
  const std::size_t cells = std::size_t(n.grid.n);
  const WearAsymptote& a = w.asymptote;
  const bool asymptote = a.w.size() == cells && a.p.size() == cells;
  std::vector<double> cycles, x, g0, wear, wear_pad, wear_specimen, p, slip;
  // Each body's own wear where the run tracked the frames (WearRecord::w_pad), else the split of w by pad_fraction.
  auto row = [&](double c, std::size_t i, double wi, double wp, double ws, double pi, double si) {
    cycles.push_back(c);
    x.push_back(n.grid.x(int(i)));
    g0.push_back(n.g0[i]);
    wear.push_back(wi);
    wear_pad.push_back(wp);
    wear_specimen.push_back(ws);
    p.push_back(pi);
    slip.push_back(si);
  };
  for (const WearRecord& r : w.records)
    for (std::size_t i = 0; i < cells; ++i)
      row(r.cycles, i, r.w[i], r.w_pad.empty() ? pad * r.w[i] : r.w_pad[i],
          r.w_specimen.empty() ? (1.0 - pad) * r.w[i] : r.w_specimen[i], r.p[i], r.s[i]);
  if (asymptote)
    for (std::size_t i = 0; i < cells; ++i)
      row(std::numeric_limits<double>::infinity(), i, a.w[i], pad * a.w[i], (1.0 - pad) * a.w[i], a.p[i], kNaN);
  t.add("cycles", "1", "cycles at the record (inf: the asymptote)", cycles);
  t.add("x", "m", "cell centre", x);
  t.add("gap0", "m", "initial gap", g0);
  t.add("wear", "m", "worn depth, both bodies", wear);
  t.add("wear_pad", "m", "worn depth of the pad", wear_pad);
  t.add("wear_specimen", "m", "worn depth of the specimen", wear_specimen);
  t.add("p", "Pa", "contact pressure", p);
  t.add("slip_per_cycle", "m", "distance slipped per cycle (NaN for the asymptote)", slip);
  return t;
}

Table stress_table(const Scene& scene, const std::vector<StressMap>& maps) {
  Table t("stress.csv", "stresses under the surface of the last state, per phase and map point (y outer, x inner)");
  std::vector<std::string> phase;
  std::vector<double> x, y, sxx, syy, sxy, vm, s1, s2;
  for (const StressMap& m : maps)
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const Stress& s = m.sigma[j * m.x.size() + i];
        const Principal pr = principal(s);
        phase.push_back(m.phase);
        x.push_back(m.x[i]);
        y.push_back(m.y[j]);
        sxx.push_back(s.xx);
        syy.push_back(s.yy);
        sxy.push_back(s.xy);
        vm.push_back(von_mises(s, scene.specimen.nu));
        s1.push_back(pr.s1);
        s2.push_back(pr.s2);
      }
  t.add_labels("phase", "\"top\" or \"bottom\" of the cycle (\"loaded\" without one)", phase);
  t.add("x", "m", "map point across", x);
  t.add("y", "m", "map point's depth", y);
  t.add("sxx", "Pa", "σxx", sxx);
  t.add("syy", "Pa", "σyy", syy);
  t.add("sxy", "Pa", "σxy", sxy);
  t.add("von_mises", "Pa", "von Mises (plane strain with the specimen's ν)", vm);
  t.add("s1", "Pa", "larger in-plane principal stress", s1);
  t.add("s2", "Pa", "smaller in-plane principal stress", s2);
  return t;
}

Table surface_stress_table(const std::vector<StressMap>& maps) {
  Table t("surface_stress.csv", "σxx along the surface of the last state, per phase");
  std::vector<std::string> phase;
  std::vector<double> x, sxx;
  for (const StressMap& m : maps)
    for (std::size_t i = 0; i < m.x.size(); ++i) {
      phase.push_back(m.phase);
      x.push_back(m.x[i]);
      sxx.push_back(m.surface_sxx[i]);
    }
  t.add_labels("phase", "\"top\" or \"bottom\" of the cycle", phase);
  t.add("x", "m", "map point", x);
  t.add("sxx", "Pa", "σxx at the surface", sxx);
  return t;
}

Table sif_table(const std::vector<SifSet>& sifs) {
  Table t("sif.csv", "the crack's stress intensity factors per state, phase and length");
  std::vector<std::string> phase;
  std::vector<double> cycles, l, K_I, K_I_open, K_II;
  std::vector<long> closed;
  for (const SifSet& set : sifs)
    for (const CrackSif& k : set.result.sifs) {
      cycles.push_back(set.cycles);
      phase.push_back(set.phase);
      l.push_back(k.l);
      K_I.push_back(k.K_I);
      K_I_open.push_back(k.K_I_open);
      K_II.push_back(k.K_II);
      closed.push_back(k.closed ? 1 : 0);
    }
  t.add("cycles", "1", "the wear record (0: the unworn contact)", cycles);
  t.add_labels("phase", "\"top\" or \"bottom\" of the cycle", phase);
  t.add("length", "m", "crack length from the mouth to the tip", l);
  t.add("K_I", "Pa*m^0.5", "mode I, with the crack faces in contact (0 where they touch at the tip)", K_I);
  t.add("K_I_open", "Pa*m^0.5", "mode I of the open crack (negative where its faces would overlap)", K_I_open);
  t.add("K_II", "Pa*m^0.5", "mode II", K_II);
  t.add_integers("closed", "1 where the faces touch at the tip", closed);
  return t;
}

Table fatigue_table(const FatigueStage& f) {
  Table t("fatigue.csv", "Smith–Watson–Topper on the critical plane per state and map point (y outer, x inner)");
  std::vector<double> cycles, x, y, swt, theta, sn, de;
  for (const FatigueRecord& rec : f.records) {
    const SwtMap& m = rec.swt;
    for (std::size_t j = 0; j < m.y.size(); ++j)
      for (std::size_t i = 0; i < m.x.size(); ++i) {
        const SwtResult& r = m.points[j * m.x.size() + i];
        cycles.push_back(rec.cycles);
        x.push_back(m.x[i]);
        y.push_back(m.y[j]);
        swt.push_back(r.swt);
        theta.push_back(r.theta * 180.0 / std::numbers::pi);
        sn.push_back(r.sigma_n_max);
        de.push_back(r.delta_eps_n);
      }
  }
  t.add("cycles", "1", "the wear record (0: the unworn contact)", cycles);
  t.add("x", "m", "map point across", x);
  t.add("y", "m", "map point's depth", y);
  t.add("swt", "Pa", "SWT on the critical plane (J/m^3)", swt);
  t.add("theta_crit", "deg", "the critical plane's normal, from +x toward +y", theta);
  t.add("sigma_n_max", "Pa", "largest normal stress on it over the cycle", sn);
  t.add("delta_eps_n", "1", "its normal strain range over the cycle", de);
  return t;
}

Table ruiz_table(const FatigueStage& f) {
  Table t("ruiz.csv", "Ruiz's parameters along the surface per state");
  std::vector<double> cycles, x, st, tau, delta, F1, F2;
  for (const FatigueRecord& rec : f.records) {
    if (!rec.ruiz) continue;
    const RuizProfile& r = *rec.ruiz;
    for (std::size_t i = 0; i < r.x.size(); ++i) {
      cycles.push_back(rec.cycles);
      x.push_back(r.x[i]);
      st.push_back(r.sigma_t[i]);
      tau.push_back(r.tau[i]);
      delta.push_back(r.delta[i]);
      F1.push_back(r.F1[i]);
      F2.push_back(r.F2[i]);
    }
  }
  t.add("cycles", "1", "the wear record (0: the unworn contact)", cycles);
  t.add("x", "m", "surface point", x);
  t.add("sxx_top", "Pa", "σxx at the surface, top of the cycle", st);
  t.add("tau_top", "Pa", "|q| at the top of the cycle", tau);
  t.add("slip_amplitude", "m", "slip amplitude", delta);
  t.add("F1", "Pa*m", "τ δ (J/m^2)", F1);
  t.add("F2", "Pa^2*m", "max(σxx, 0) τ δ", F2);
  return t;
}

Table crack_growth_table(const GrowthResult& g) {
  Table t("crack_growth.csv", "the crack's growth by Paris' law, one row per accepted step");
  const auto& p = g.path;
  t.add("cycles", "1", "cycles from the start of growth", of(p, [](const GrowthPoint& x) { return x.N; }));
  t.add("a", "m", "crack length", of(p, [](const GrowthPoint& x) { return x.a; }));
  t.add("dK_I", "Pa*m^0.5", "mode I range", of(p, [](const GrowthPoint& x) { return x.dK_I; }));
  t.add("dK_II", "Pa*m^0.5", "mode II range", of(p, [](const GrowthPoint& x) { return x.dK_II; }));
  t.add("da_dN", "m", "growth per cycle", of(p, [](const GrowthPoint& x) { return x.da_dN; }));
  return t;
}

Table damage_table(const LifeInitiationResult& in) {
  Table t("damage.csv", "Miner's damage at the initiation (per cycle if never) per map point (y outer, x inner)");
  std::vector<double> x, y, d;
  for (std::size_t j = 0; j < in.map_y.size(); ++j)
    for (std::size_t k = 0; k < in.map_x.size(); ++k) {
      x.push_back(in.map_x[k]);
      y.push_back(in.map_y[j]);
      d.push_back(in.damage[j * in.map_x.size() + k]);
    }
  t.add("x", "m", "map point across", x);
  t.add("y", "m", "depth below the surface of that state", y);
  t.add("damage", "1", "Miner's damage", d);
  return t;
}

}  // namespace

std::map<std::string, Table> result_tables(const Scene& scene, const RunResult& r) {
  std::map<std::string, Table> tables;
  tables.emplace("contact", contact_table(r.normal));
  // The same conditions as the writers' (write_cycle, write_wear, ...): a table the folder would not hold is absent.
  if (r.cycle && !r.cycle->result.slip_range.empty()) {
    tables.emplace("cycle", cycle_table(r.normal, *r.cycle));
    if (!r.cycle->result.loop.empty()) tables.emplace("loop", loop_table(r.cycle->result));
  }
  if (r.wear) {
    tables.emplace("wear_history", wear_history_table(*r.wear));
    tables.emplace("profiles", profiles_table(scene, r.normal, *r.wear));
    std::size_t most = 0;
    for (const WearRecord& x : r.wear->records) most = std::max(most, x.stick_zones.size());
    if (most > 1) tables.emplace("wear_stick_zones", wear_stick_zones_table(*r.wear));
  }
  if (!r.stress_maps.empty()) {
    const std::vector<StressMap> last = last_record(r.stress_maps);
    tables.emplace("stress", stress_table(scene, last));
    tables.emplace("surface_stress", surface_stress_table(last));
  }
  if (r.fatigue) {
    tables.emplace("fatigue", fatigue_table(*r.fatigue));
    if (r.fatigue->last().ruiz) tables.emplace("ruiz", ruiz_table(*r.fatigue));
  }
  if (!r.sifs.empty()) tables.emplace("sif", sif_table(r.sifs));
  if (r.life) {
    if (r.life->propagation) tables.emplace("crack_growth", crack_growth_table(*r.life->propagation));
    if (r.life->initiation) tables.emplace("damage", damage_table(*r.life->initiation));
  }
  return tables;
}

const std::vector<std::pair<std::string, std::string>>& table_names() {
  static const std::vector<std::pair<std::string, std::string>> names = {
      {"contact", "contact.csv: the contact under P alone per cell (x m, gap0 m, p Pa, gap m, p_closed_form Pa)"},
      {"cycle", "cycle.csv: the steady cycle per cell (tractions Pa, slip m, energy density J/m^2)"},
      {"loop", "loop.csv: the fretting loop (P, Q N/m, delta m)"},
      {"wear_history", "wear_history.csv: one row per wear record (cycles, worn_area m^2, max_depth m, ...)"},
      {"profiles", "profiles.csv: the worn profile per record and cell (wear m, p Pa, slip m)"},
      {"wear_stick_zones", "wear_stick_zones.csv: each stick zone's ends per record, with several zones (m)"},
      {"stress", "stress.csv: stresses of the last state per phase and map point (Pa)"},
      {"surface_stress", "surface_stress.csv: σxx along the surface per phase (Pa)"},
      {"fatigue", "fatigue.csv: SWT per state and map point (Pa), its critical plane (deg)"},
      {"ruiz", "ruiz.csv: Ruiz's F1 (Pa*m) and F2 (Pa^2*m) along the surface per state"},
      {"sif", "sif.csv: the crack's K_I, K_II (Pa*m^0.5) per state, phase and length (m)"},
      {"crack_growth", "crack_growth.csv: the crack's growth (cycles, a m, ranges Pa*m^0.5, da_dN m)"},
      {"damage", "damage.csv: Miner's damage per map point (x, y m)"},
  };
  return names;
}

}  // namespace fretwear::python
