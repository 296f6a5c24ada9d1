// The compiled part of the Python package `snapjump` (python/snapjump/__init__.py): the command
// line run in-process, so that Python gets the same results and the same error messages, with
// a run's progress lines handed to a Python callable and Ctrl-C (or any pending Python signal)
// stopping a run as --pause-at does.
#include <pybind11/functional.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <optional>
#include <sstream>
#include <streambuf>
#include <string>
#include <tuple>
#include <vector>

#include "app/cli.hpp"

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

}  // namespace

PYBIND11_MODULE(_snapjump, m) {
  m.doc() = "snapjump's command line, in-process (use the package snapjump, not this module)";
  m.def("cli", &cli, py::arg("args"), py::arg("progress") = py::none(),
        "Runs `snapjump ARGS...` in this process; returns (status, stdout, stderr).");
}
