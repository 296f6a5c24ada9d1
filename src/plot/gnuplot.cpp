#include "plot/gnuplot.hpp"

#include <fmt/format.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <system_error>

#include "config/text.hpp"

namespace snapjump::plot {
namespace {

namespace fs = std::filesystem;

// A word for /bin/sh: 'it'\''s'.
std::string shell_quote(std::string_view text) {
  std::string s = "'";
  for (const char c : text) {
    if (c == '\'') {
      s += "'\\''";
    } else {
      s += c;
    }
  }
  s += '\'';
  return s;
}

std::string trim(std::string s) {
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

// The last `limit` characters of gnuplot's output, enough to show the error and its line.
std::string tail(const std::string& text, std::size_t limit = 2000) {
  auto t = trim(text);
  if (t.size() > limit) t = "..." + t.substr(t.size() - limit);
  return t;
}

}  // namespace

std::string_view extension(Format f) { return f == Format::Svg ? "svg" : "png"; }

std::optional<Format> parse_format(std::string_view text) {
  const auto lower = text::lower(text);
  if (lower == "png") return Format::Png;
  if (lower == "svg") return Format::Svg;
  return std::nullopt;
}

FigureOptions options_for_image(const std::filesystem::path& image, std::string_view flag) {
  FigureOptions o;
  o.output = image;
  const auto ext = image.extension().string();
  const auto f = parse_format(ext.empty() ? "" : ext.substr(1));
  if (!f) {
    throw PlotInputError(fmt::format("{} {}: name the file .png or .svg", flag, image.string()));
  }
  o.format = *f;
  if (const char* g = std::getenv("SNAPJUMP_GNUPLOT"); g != nullptr && *g != '\0') o.gnuplot = g;
  return o;
}

FigureResult figure_paths(const FigureOptions& options, const fs::path& default_path) {
  FigureResult r;
  if (options.output.empty()) {
    // Appended, not replaced: a default named after "b-nu0.45.csv" is "b-nu0.45", whose ".45"
    // is not an extension.
    r.figure = default_path;
    r.figure += fmt::format(".{}", extension(options.format));
  } else {
    r.figure = options.output;
  }
  // The image's name is written into the script (`set output`): a control character there would
  // change the name gnuplot writes to, so such a name is refused rather than altered.
  const auto name = r.figure.filename().string();
  if (printable(name) != name) {
    throw PlotInputError(fmt::format(
        "the figure's file name {} holds a control character (a newline, a tab, ...); choose "
        "another with --output",
        quote(name)));
  }
  r.script = r.figure;
  r.script.replace_extension("gp");
  if (r.script == r.figure) r.script += ".gp";  // an image named FIGURE.gp
  return r;
}

std::string printable(std::string_view text) {
  std::string s;
  s.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    s += (u < 0x20 || u == 0x7f) ? ' ' : c;
  }
  return s;
}

std::string quote(std::string_view text) {
  std::string s = "'";
  for (const char c : printable(text)) {
    if (c == '\'') s += '\'';
    s += c;
  }
  s += '\'';
  return s;
}

std::string terminal(Format format, int width, int height, const fs::path& image, int font_size) {
  std::string s;
  if (format == Format::Svg) {
    s = fmt::format(
        "set terminal svg size {},{} dynamic enhanced font 'DejaVu Sans,{}' linewidth 1.5 "
        "background rgb 'white'\n",
        width, height, font_size);
  } else {
    s = fmt::format(
        "set terminal pngcairo size {},{} enhanced font 'DejaVu Sans,{}' linewidth 1.5 "
        "background rgb 'white'\n",
        width, height, font_size);
  }
  s += "set encoding utf8\n";
  s += fmt::format("set output {}\n", quote(image.filename().string()));
  return s;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "NaN";
  return fmt::format("{:.10g}", v);
}

std::string datablock(std::string_view name, std::string_view columns,
                      const std::vector<std::vector<double>>& rows) {
  std::string s = fmt::format("${} << EOD\n# {}\n", printable(name), printable(columns));
  for (const auto& row : rows) {
    const bool finite =
        std::all_of(row.begin(), row.end(), [](double v) { return std::isfinite(v); });
    if (finite) {
      for (std::size_t i = 0; i < row.size(); ++i) {
        if (i > 0) s += ' ';
        s += number(row[i]);
      }
    }
    s += '\n';
  }
  s += "EOD\n";
  return s;
}

void render(const FigureResult& paths, const std::string& script, const std::string& gnuplot) {
  const fs::path dir =
      paths.script.parent_path().empty() ? fs::path(".") : paths.script.parent_path();
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) {
    throw PlotError(fmt::format("cannot create the folder {}: {}", dir.string(), ec.message()));
  }
  {
    std::ofstream out(paths.script);
    if (!out) throw PlotError(fmt::format("cannot write the script {}", paths.script.string()));
    out << script;
    if (!out) throw PlotError(fmt::format("writing the script {} failed", paths.script.string()));
  }
  fs::remove(paths.figure, ec);  // a stale image must not pass for a new one

  const auto command =
      fmt::format("cd {} && {} {} 2>&1", shell_quote(dir.string()), shell_quote(gnuplot),
                  shell_quote(paths.script.filename().string()));
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) {
    throw PlotError(
        fmt::format("cannot start gnuplot ('{}') for {}", gnuplot, paths.script.string()));
  }
  std::string output;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    output.append(buffer.data(), n);
  const int status = ::pclose(pipe);
  const int code = (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
  if (code == 127 || code == 126) {
    throw PlotError(fmt::format(
        "cannot run gnuplot ('{}'): {}; install it (Debian: apt-get install gnuplot-nox) or name "
        "it with SNAPJUMP_GNUPLOT; the script is kept at {}",
        gnuplot, tail(output).empty() ? "not found" : tail(output), paths.script.string()));
  }
  if (code != 0) {
    fs::remove(paths.figure, ec);
    throw PlotError(fmt::format("gnuplot failed (exit status {}) on {}:\n{}", code,
                                paths.script.string(), tail(output)));
  }
  // The script writes the image into its own folder (figure_paths keeps them together).
  if (!fs::is_regular_file(paths.figure, ec) || fs::file_size(paths.figure, ec) == 0) {
    throw PlotError(fmt::format("gnuplot ran {} but wrote no image {}{}{}", paths.script.string(),
                                paths.figure.string(), output.empty() ? "" : ":\n", tail(output)));
  }
}

}  // namespace snapjump::plot
