// Figures through gnuplot: a figure is a self-contained gnuplot script (FIGURE.gp, its data in
// datablocks) kept beside the image it draws (FIGURE.png or FIGURE.svg), so that a user can edit
// the script and run `gnuplot FIGURE.gp` in that folder to redraw it.
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "config/input_error.hpp"

namespace snapjump::plot {

// Bad input for a figure: a missing file or column, an empty table. what() names the file and
// the column. The command line exits with status 2.
class PlotInputError : public InputError {
 public:
  using InputError::InputError;
};

// gnuplot is missing or failed. what() names the script and quotes gnuplot's message. The
// command line exits with status 1.
class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Format { Png, Svg };
std::string_view extension(Format f);  // "png", "svg"
// "png" / "svg" (case-insensitive); nothing otherwise.
std::optional<Format> parse_format(std::string_view text);

// Where and how to draw one figure.
struct FigureOptions {
  Format format = Format::Png;
  std::filesystem::path output;     // the image; empty: the figure's default place
  std::string gnuplot = "gnuplot";  // the program to run
};

// What a figure command produced.
struct FigureResult {
  std::filesystem::path figure;    // the image
  std::filesystem::path script;    // the gnuplot script beside it
  std::vector<std::string> notes;  // what a user should know (data left out, fallbacks)
};

// The options for an image named `image` (.png or .svg, from its extension; gnuplot from the
// environment's SNAPJUMP_GNUPLOT when set). Throws PlotInputError naming `flag` for another
// extension.
FigureOptions options_for_image(const std::filesystem::path& image, std::string_view flag);

// The image and script paths for a figure: options.output if given (the script takes its stem
// and the extension .gp), else `default_path` with the format's extension.
FigureResult figure_paths(const FigureOptions& options, const std::filesystem::path& default_path);

// --- Script text ---

// Text with every control character (below 0x20, and 0x7f) replaced by a space. gnuplot reads
// a script line by line, so a newline or carriage return inside a string a user wrote (a case
// title, a folder or file name) would end the string's line and make the rest a command, such
// as system("..."). Every user-written string that reaches a script goes through this, by way of
// quote() or datablock().
std::string printable(std::string_view text);

// A gnuplot single-quoted string of printable(text), quotes doubled: 'it''s'. gnuplot expands
// neither backquotes nor macros inside single quotes, so the result is inert data.
std::string quote(std::string_view text);

// The terminal lines for a figure of width x height pixels (pngcairo or svg, enhanced text,
// UTF-8, white background) and `set output` with the image's file name (relative to the script's
// folder, where render() runs gnuplot).
std::string terminal(Format format, int width, int height, const std::filesystem::path& image,
                     int font_size = 14);

// A datablock `$name << EOD ... EOD` with one line per row, values in full precision; `columns`
// becomes a comment line naming them (printable(), so that it cannot end the datablock). Rows with
// a non-finite value are written as a blank line (gnuplot breaks lines there).
std::string datablock(std::string_view name, std::string_view columns,
                      const std::vector<std::vector<double>>& rows);

// A number for a script, in full precision.
std::string number(double v);

// Writes the script and runs gnuplot on it in the script's folder. Throws PlotError naming the
// script and quoting gnuplot's output when gnuplot is missing, fails or leaves no image.
void render(const FigureResult& paths, const std::string& script, const std::string& gnuplot);

}  // namespace snapjump::plot
