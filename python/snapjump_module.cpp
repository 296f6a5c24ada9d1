// The compiled part of the Python package `snapjump` (python/snapjump/__init__.py): the command
// line run in-process, so that Python gets the same results and the same error messages, with
// a run's progress lines handed to a Python callable and Ctrl-C (or any pending Python signal)
// stopping a run as --pause-at does; and the theory over many designs at once, one loop in C++
// with the case checked as a case file's is.
#include <fmt/format.h>
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <cstddef>
#include <map>
#include <optional>
#include <sstream>
#include <streambuf>
#include <string>
#include <tuple>
#include <vector>

#include "app/cli.hpp"
#include "config/case.hpp"
#include "config/units.hpp"
#include "io/prediction_report.hpp"
#include "theory/prefactors.hpp"
#include "theory/scaling.hpp"

#ifndef SNAPJUMP_VERSION
#error "SNAPJUMP_VERSION (the project's version) is set by CMakeLists.txt"
#endif

namespace py = pybind11;

namespace {

// A stream buffer that keeps what is written and hands each complete line to a callback.
class LineBuffer : public std::streambuf {
 public:
  explicit LineBuffer(std::function<void(const std::string&)> on_line)
      : on_line_(std::move(on_line)) {}
  [[nodiscard]] const std::string& text() const { return text_; }
  void finish() {
    if (!line_.empty()) emit();
  }

 protected:
  int_type overflow(int_type ch) override {
    if (ch == traits_type::eof()) return traits_type::not_eof(ch);
    const char c = traits_type::to_char_type(ch);
    text_.push_back(c);
    if (c == '\n') {
      emit();
    } else {
      line_.push_back(c);
    }
    return ch;
  }

 private:
  void emit() {
    if (on_line_) on_line_(line_);
    line_.clear();
  }
  std::function<void(const std::string&)> on_line_;
  std::string text_, line_;
};

// Runs `snapjump ARGS...`; returns (exit status, standard output, standard error). progress, when
// given, receives each line of either (a run's progress and results) as it is written.
std::tuple<int, std::string, std::string> cli(const std::vector<std::string>& args,
                                              const py::object& progress) {
  std::vector<std::string> words{"snapjump"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<const char*> argv;
  for (const auto& w : words) argv.push_back(w.c_str());

  bool interrupted = false;
  std::optional<py::error_already_set> callback_error;
  const auto hand_on = [&](const std::string& line) {
    if (progress.is_none() || callback_error) return;
    py::gil_scoped_acquire gil;
    try {
      progress(line);
    } catch (py::error_already_set& e) {
      callback_error = std::move(e);  // raised again once the run has stopped
    }
  };
  LineBuffer out_buf(hand_on), err_buf(hand_on);
  std::ostream out(&out_buf), err(&err_buf);
  snapjump::app::CliHooks hooks;
  hooks.stop_requested = [&] {
    py::gil_scoped_acquire gil;
    if (!callback_error && PyErr_CheckSignals() != 0) {
      if (PyErr_ExceptionMatches(PyExc_KeyboardInterrupt)) {
        PyErr_Clear();
        interrupted = true;  // raised again, with what the run wrote, once it has stopped
      } else {
        callback_error = py::error_already_set();  // what a signal handler raised, as it is
      }
    }
    return interrupted || callback_error.has_value();
  };
  int code = 0;
  {
    py::gil_scoped_release release;
    code = snapjump::app::run_cli(static_cast<int>(argv.size()), argv.data(), out, err, hooks);
  }
  out_buf.finish();
  err_buf.finish();
  if (callback_error) throw std::move(*callback_error);
  if (interrupted) {
    PyErr_SetString(PyExc_KeyboardInterrupt,
                    ("snapjump stopped; what it wrote stays:\n" + out_buf.text()).c_str());
    throw py::error_already_set();
  }
  return {code, out_buf.text(), err_buf.text()};
}

// The position of element `flat` of an array of `shape`, as numpy writes it: "[2, 3]".
std::string position(std::size_t flat, const std::vector<std::size_t>& shape) {
  std::vector<std::size_t> index(shape.size());
  for (std::size_t d = shape.size(); d-- > 0;) {
    index[d] = shape[d] == 0 ? 0 : flat % shape[d];
    flat = shape[d] == 0 ? 0 : flat / shape[d];
  }
  return fmt::format("[{}]", fmt::join(index, ", "));
}

// A value the closed forms cannot evaluate (inf, or NaN inside the theory's range), as the
// command line's predict refuses it.
void check_evaluated(const std::vector<snapjump::io::ReportRow>& rows,
                     const snapjump::theory::Prediction& p) {
  const auto failed = [&](double v) {
    return std::isinf(v) || (std::isnan(v) && p.beyond_range.empty());
  };
  for (const auto& row : rows) {
    if (failed(row.lo) || failed(row.hi)) {
      throw snapjump::config::CaseError(fmt::format(
          "the design gives a non-finite {} ({} .. {}): outside what the closed forms can "
          "evaluate",
          row.key, row.lo, row.hi));
    }
  }
}

// What predict_many collects, element by element, before it becomes numpy arrays.
struct Columns {
  std::vector<std::string> quantity_keys, quantity_units, case_keys;
  std::vector<std::vector<double>> lower, upper, case_values;
  std::vector<std::string> outcome, beyond_range;
  std::string constants_source;

  void add(const nlohmann::json& case_json, const std::vector<snapjump::io::ReportRow>& rows,
           const snapjump::theory::Prediction& p) {
    if (quantity_keys.empty()) {
      for (const auto& r : rows) {
        quantity_keys.push_back(r.key);
        quantity_units.push_back(r.si_unit);
      }
      lower.resize(rows.size());
      upper.resize(rows.size());
      for (const auto& [k, v] : case_json.items()) {
        if (v.is_number() || (v.is_null() && k != "mesh")) case_keys.push_back(k);
      }
      case_values.resize(case_keys.size());
      constants_source = p.constants_source;
    }
    for (std::size_t q = 0; q < rows.size(); ++q) {
      lower[q].push_back(rows[q].lo);
      upper[q].push_back(rows[q].hi);
    }
    for (std::size_t k = 0; k < case_keys.size(); ++k) {
      const auto& v = case_json[case_keys[k]];
      case_values[k].push_back(v.is_number() ? v.get<double>() : std::nan(""));
    }
    outcome.push_back(p.outcome_text());
    beyond_range.push_back(p.beyond_range);
  }
};

py::array_t<double> to_array(const std::vector<double>& v) {
  py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict to_dict(const Columns& c) {
  py::dict quantities, case_values;
  for (std::size_t q = 0; q < c.quantity_keys.size(); ++q) {
    py::dict row;
    row["lower"] = to_array(c.lower[q]);
    row["upper"] = to_array(c.upper[q]);
    row["unit"] = c.quantity_units[q];
    quantities[py::str(c.quantity_keys[q])] = row;
  }
  for (std::size_t k = 0; k < c.case_keys.size(); ++k) {
    case_values[py::str(c.case_keys[k])] = to_array(c.case_values[k]);
  }
  py::dict out;
  out["case"] = case_values;
  out["quantities"] = quantities;
  out["outcome"] = c.outcome;
  out["beyond_range"] = c.beyond_range;
  out["constants_source"] = c.constants_source;
  return out;
}

// A value given for the whole grid: its case key, its text ("30 mm") and its name in messages.
using Fixed = std::tuple<std::string, std::string, std::string>;

// The theory for each design of a grid: the case (TOML text, or the built-in default when none)
// with the fixed values and, for element i, values[k][i] (SI) of keys[k]. Each design is read
// and checked as a case file with those values is; an error names the value, the element and
// the key, and is raised as ValueError. Returns flat arrays of the quantities' bounds, the case
// values, the outcome texts.
py::dict predict_many(
    const std::optional<std::string>& case_text, const std::string& source,
    const std::vector<Fixed>& fixed, const std::vector<std::string>& keys,
    const std::vector<std::string>& names,
    const std::vector<py::array_t<double, py::array::c_style | py::array::forcecast>>& values,
    const std::vector<std::size_t>& shape, bool allow_implausible) {
  namespace config = snapjump::config;
  if (keys.size() != values.size() || keys.size() != names.size()) {
    throw py::value_error("predict_many: keys, names and values differ in length");
  }
  std::size_t n = 1;
  for (const auto s : shape) n *= s;
  std::vector<const double*> data;
  for (const auto& v : values) {
    if (static_cast<std::size_t>(v.size()) != n) {
      throw py::value_error("predict_many: a value array does not hold one value a design");
    }
    data.push_back(v.data());
  }
  const std::string text(case_text ? *case_text : config::default_case_text());
  Columns columns;
  std::string error;
  {
    py::gil_scoped_release release;
    try {
      const snapjump::units::UnitParser parser;
      const auto& constants = snapjump::theory::contact_constants();
      std::vector<config::Override> overrides;
      for (const auto& [key, value, origin] : fixed) overrides.push_back({key, value, origin});
      const auto n_fixed = overrides.size();
      for (std::size_t i = 0; i < n; ++i) {
        overrides.resize(n_fixed);
        const auto at = position(i, shape);
        for (std::size_t k = 0; k < keys.size(); ++k) {
          overrides.push_back({keys[k], fmt::format("{:.17g}", data[k][i]), names[k] + at});
        }
        try {
          const auto c = config::parse_case(text, source, overrides, &parser);
          if (!c.implausible.empty() && !allow_implausible) {
            throw config::CaseError(fmt::format(
                "{}; allow_implausible=True takes it as it is (README.md, \"Plausible values\")",
                c.implausible.front()));
          }
          const auto p = snapjump::theory::predict(c, constants);
          const auto rows = snapjump::io::prediction_rows(p);
          check_evaluated(rows, p);
          columns.add(snapjump::io::case_to_json(c), rows, p);
        } catch (const snapjump::InputError& e) {
          throw snapjump::InputError(keys.empty() ? std::string(e.what())
                                                  : fmt::format("design {}: {}", at, e.what()));
        }
      }
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  if (!error.empty()) throw py::value_error(error);
  return to_dict(columns);
}

}  // namespace

PYBIND11_MODULE(_snapjump, m) {
  m.doc() = "snapjump's command line, in-process (use the package snapjump, not this module)";
  m.def("cli", &cli, py::arg("args"), py::arg("progress") = py::none(),
        "Runs `snapjump ARGS...` in this process; returns (status, stdout, stderr).");
  m.def("predict_many", &predict_many, py::arg("case_text"), py::arg("source"), py::arg("fixed"),
        py::arg("keys"), py::arg("names"), py::arg("values"), py::arg("shape"),
        py::arg("allow_implausible") = false,
        "The theory for a grid of designs: flat arrays of the bounds, case values and outcomes.");
  py::list keys;
  for (const auto& k : snapjump::config::quantity_keys()) {
    py::dict d;
    d["key"] = fmt::format("{}.{}", k.table, k.name);
    d["flag"] = std::string(k.flag);
    d["dimension"] = std::string(snapjump::units::dimension_name(k.dimension));
    d["unit"] = std::string(snapjump::units::si_unit(k.dimension));
    d["required"] = k.required;
    d["default"] = std::string(k.default_text);
    d["example"] = std::string(k.example);
    d["help"] = std::string(k.help);
    keys.append(d);
  }
  m.attr("case_keys") = keys;
  m.attr("__version__") = SNAPJUMP_VERSION;
}
