#include "plot/snapshots.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <iterator>
#include <optional>
#include <string_view>

#include "config/files.hpp"
#include "config/text.hpp"
#include "plot/gnuplot.hpp"

namespace snapjump::plot {
namespace {

namespace fs = std::filesystem;

// The value of attribute `name` in the text of one XML tag, if present.
std::optional<std::string> attribute(std::string_view tag, std::string_view name) {
  std::size_t pos = 0;
  while (true) {
    pos = tag.find(name, pos);
    if (pos == std::string_view::npos) return std::nullopt;
    const bool starts = pos > 0 && (tag[pos - 1] == ' ' || tag[pos - 1] == '\t' ||
                                    tag[pos - 1] == '\n' || tag[pos - 1] == '\r');
    auto after = pos + name.size();
    while (after < tag.size() && tag[after] == ' ') ++after;
    if (starts && after < tag.size() && tag[after] == '=') {
      ++after;
      while (after < tag.size() && tag[after] == ' ') ++after;
      if (after < tag.size() && (tag[after] == '"' || tag[after] == '\'')) {
        const char q = tag[after];
        const auto end = tag.find(q, after + 1);
        if (end == std::string_view::npos) return std::nullopt;
        return std::string(tag.substr(after + 1, end - after - 1));
      }
    }
    pos += name.size();
  }
}

std::optional<double> to_number(std::string_view s) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace

std::vector<Frame> read_pvd(const fs::path& path) {
  const auto text =
      text::read_file<PlotInputError>(path, "the snapshot collection that `snapjump run` writes");
  std::vector<Frame> frames;
  std::size_t pos = 0;
  while ((pos = text.find("<DataSet", pos)) != std::string::npos) {
    const auto end = text.find('>', pos);
    if (end == std::string::npos) break;
    const std::string_view tag(text.data() + pos, end - pos);
    const auto t = attribute(tag, "timestep");
    const auto file = attribute(tag, "file");
    if (!t || !file) {
      throw PlotInputError(
          fmt::format("{}: a <DataSet> without timestep or file attribute", path.string()));
    }
    const auto time = to_number(*t);
    if (!time) {
      throw PlotInputError(
          fmt::format("{}: timestep \"{}\" is not a number", path.string(), text::excerpt(*t)));
    }
    // The file is named in messages about the frame.
    if (file->empty() || text::has_control_characters(*file)) {
      throw PlotInputError(
          fmt::format("{}: a <DataSet> file \"{}\" that is empty or holds control "
                      "characters",
                      path.string(), text::excerpt(*file)));
    }
    frames.push_back({*time, fs::path(*file)});
    pos = end;
  }
  if (frames.empty()) throw PlotInputError(fmt::format("{}: lists no snapshot", path.string()));
  return frames;
}

const Frame& nearest_frame(const std::vector<Frame>& frames, double t) {
  const Frame* best = &frames.front();
  for (const auto& f : frames) {
    if (std::abs(f.time - t) < std::abs(best->time - t)) best = &f;
  }
  return *best;
}

std::vector<std::array<double, 3>> read_vtu_points(const fs::path& path) {
  const auto text = text::read_file<PlotInputError>(path, "a snapshot listed in run.pvd");
  const auto fail = [&](std::string_view why) {
    return PlotInputError(
        fmt::format("{}: {} (expected an ASCII VTK unstructured grid as "
                    "`snapjump run` writes)",
                    path.string(), why));
  };
  const auto piece = text.find("<Piece");
  if (piece == std::string::npos) throw fail("no <Piece>");
  const auto piece_end = text.find('>', piece);
  if (piece_end == std::string::npos) throw fail("an unterminated <Piece>");
  const auto count_text =
      attribute(std::string_view(text.data() + piece, piece_end - piece), "NumberOfPoints");
  const auto count = count_text ? to_number(*count_text) : std::nullopt;
  // Each coordinate takes at least two characters: a count beyond that is not this file's.
  if (!count || !(*count >= 0) || *count != std::floor(*count) ||
      *count > static_cast<double>(text.size())) {
    throw fail("no usable NumberOfPoints");
  }
  const auto n = static_cast<std::size_t>(*count);
  const auto points = text.find("<Points>", piece);
  if (points == std::string::npos) throw fail("no <Points>");
  const auto array = text.find("<DataArray", points);
  if (array == std::string::npos) throw fail("no <DataArray> in <Points>");
  const auto array_end = text.find('>', array);
  if (array_end == std::string::npos) throw fail("an unterminated <DataArray>");
  const std::string_view tag(text.data() + array, array_end - array);
  if (const auto format = attribute(tag, "format"); format && *format != "ascii") {
    throw fail(fmt::format("the points are in format \"{}\"", text::excerpt(*format)));
  }
  if (const auto comps = attribute(tag, "NumberOfComponents"); comps && *comps != "3") {
    throw fail("the points do not have 3 components");
  }
  const auto close = text.find("</DataArray>", array_end);
  if (close == std::string::npos) throw fail("an unterminated <DataArray>");
  if (3 * n > close - array_end) throw fail("fewer coordinates than NumberOfPoints says");
  std::vector<std::array<double, 3>> out(n);
  const char* p = text.data() + array_end + 1;
  const char* const stop = text.data() + close;
  for (std::size_t i = 0; i < 3 * n; ++i) {
    while (p < stop && (*p == ' ' || *p == '\n' || *p == '\t' || *p == '\r')) ++p;
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(p, stop, v);
    if (ec != std::errc() || p == stop) {
      throw fail(fmt::format("point coordinate {} of {} is missing or not a number", i + 1, 3 * n));
    }
    out[i / 3][i % 3] = v;
    p = ptr;
  }
  return out;
}

}  // namespace snapjump::plot
