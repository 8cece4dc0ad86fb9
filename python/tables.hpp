// A run's fields as numpy arrays: one Table per CSV file the command line writes, one column per CSV column, in the
// same rows and the same order, in the CSV's units (SI; angles in degrees where the CSV gives degrees). The column's
// name is the CSV header's without its unit suffix ("p_Pa" is `p`); a value the CSV leaves empty is NaN. The arrays
// are read-only: each is handed out to every caller (table.x is table["x"]), and `.copy()` gives one to write into.
#pragma once

#include <map>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "engine/scene.hpp"
#include "engine/simulation.hpp"

namespace fretwear::python {

struct Column {
  std::string name;     // the CSV header's, without the unit: "p"
  std::string unit;     // "Pa", "m", "1" for a pure number, "" for a label
  std::string meaning;  // one line
  pybind11::object values;  // a 1-D numpy array, read-only (its WRITEABLE flag cannot be set)
};

class Table {
 public:
  Table() = default;  // no file and no columns: what Table.__new__ makes, for __setstate__ to fill
  Table(std::string file, std::string meaning) : file_(std::move(file)), meaning_(std::move(meaning)) {}
  void add(std::string name, std::string unit, std::string meaning, const std::vector<double>& values);
  void add_labels(std::string name, std::string meaning, const std::vector<std::string>& values);
  void add_integers(std::string name, std::string meaning, const std::vector<long>& values);

  const std::string& file() const { return file_; }
  const std::vector<Column>& columns() const { return columns_; }
  std::size_t rows() const { return rows_; }
  const Column& column(const std::string& name) const;  // throws pybind11::key_error naming the columns
  std::string describe() const;  // the file, its meaning, and each column with its unit and meaning

  // Pickling: (file, meaning, [(name, unit, meaning, values), ...]), and the table again from that, each array
  // read-only again (an unpickled array is writeable). from_state throws std::runtime_error for a state of another
  // shape, and std::logic_error for columns of different lengths.
  pybind11::tuple state() const;
  static Table from_state(const pybind11::tuple& state);

 private:
  void check_rows(std::size_t n);
  std::string file_, meaning_;
  std::vector<Column> columns_;
  std::size_t rows_ = 0;
};

// A column name as a message quotes it: "name", its control characters escaped (\x00), since Python's exception
// messages end at a NUL.
std::string quoted_name(const std::string& name);

// The tables of a run, by the CSV's stem ("contact", "cycle", "wear_history", ...): those the command line writes for
// it, and no others.
std::map<std::string, Table> result_tables(const Scene& scene, const RunResult& result);

// The stems result_tables() may hold, in the order the stages run, each with a line for the Result's docstring.
const std::vector<std::pair<std::string, std::string>>& table_names();

}  // namespace fretwear::python
