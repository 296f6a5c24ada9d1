#include "config/units.hpp"

#include <fmt/format.h>
#include <udunits2.h>

#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>

#include "config/text.hpp"

namespace snapjump::units {
namespace {

struct DimensionRow {
  Dimension dimension;
  std::string_view name;
  std::string_view si;  // as udunits parses it
  std::string_view shown;
  std::string_view example;
};

constexpr std::array kDimensions{
    DimensionRow{Dimension::Length, "length", "m", "m", "30 mm"},
    DimensionRow{Dimension::Angle, "angle", "rad", "rad", "80 deg"},
    DimensionRow{Dimension::Pressure, "pressure", "Pa", "Pa", "1.2 MPa"},
    DimensionRow{Dimension::Force, "force", "N", "N", "0.48 N"},
    DimensionRow{Dimension::Mass, "mass", "kg", "kg", "49 g"},
    DimensionRow{Dimension::Density, "density", "kg/m^3", "kg/m^3", "1160 kg/m^3"},
    DimensionRow{Dimension::Volume, "volume", "m^3", "m^3", "200 mL"},
    DimensionRow{Dimension::Time, "time", "s", "s", "10 ms"},
    DimensionRow{Dimension::Dimensionless, "dimensionless number", "1", "1", "0.3"},
    DimensionRow{Dimension::ValveAcceleration, "inverse pressure per time squared", "Pa^-1 s^-2",
                 "Pa^-1 s^-2", "1.0e-3 Pa^-1 s^-2"},
    DimensionRow{Dimension::ValveRate, "inverse pressure per time", "Pa^-1 s^-1", "Pa^-1 s^-1",
                 "5.0e-5 Pa^-1 s^-1"},
    DimensionRow{Dimension::Stiffness, "stiffness", "N/m", "N/m", "3 kN/m"},
};

const DimensionRow& row(Dimension d) {
  for (const auto& r : kDimensions) {
    if (r.dimension == d) return r;
  }
  throw std::logic_error("unknown dimension");
}

// Extra dimensions that only serve to name what a user wrote by mistake.
constexpr std::array<std::pair<std::string_view, std::string_view>, 6> kOtherDimensions{{
    {"area", "m^2"},
    {"energy", "J"},
    {"velocity", "m/s"},
    {"acceleration", "m/s^2"},
    {"temperature", "K"},
    {"frequency", "Hz"},
}};

// "a length", "an angle", "an energy".
std::string with_article(std::string_view noun) {
  const bool vowel =
      !noun.empty() && std::string_view("aeiou").find(noun.front()) != std::string_view::npos;
  return fmt::format("{} {}", vowel ? "an" : "a", noun);
}

using text::trim;

// The number at the start of s (a leading '+' allowed, which from_chars does not take) and the
// text after it; ec as from_chars gives it, rest all of s when no number was read.
struct LeadingNumber {
  double value = 0.0;
  std::string_view rest;
  std::errc ec{};
};

LeadingNumber leading_number(std::string_view s) {
  LeadingNumber n;
  const char* begin = s.data();
  const char* end = s.data() + s.size();
  if (begin != end && *begin == '+') ++begin;
  const auto [ptr, ec] = std::from_chars(begin, end, n.value);
  n.ec = ec;
  const char* after = ec == std::errc() && ptr != begin ? ptr : s.data();
  n.rest = std::string_view(after, static_cast<size_t>(end - after));
  return n;
}

struct UnitDeleter {
  void operator()(ut_unit* u) const { ut_free(u); }
};
using UnitPtr = std::unique_ptr<ut_unit, UnitDeleter>;

struct ConverterDeleter {
  void operator()(cv_converter* c) const { cv_free(c); }
};
using ConverterPtr = std::unique_ptr<cv_converter, ConverterDeleter>;

}  // namespace

std::string_view dimension_name(Dimension d) { return row(d).name; }
std::string_view si_unit(Dimension d) { return row(d).shown; }
std::string_view example(Dimension d) { return row(d).example; }

struct UnitParser::Impl {
  ut_system* system = nullptr;

  ~Impl() {
    if (system != nullptr) ut_free_system(system);
  }

  UnitPtr parse_unit(std::string_view text) const {
    const std::string s(text);
    UnitPtr u(ut_parse(system, s.c_str(), UT_UTF8));
    if (!u) {
      const auto status = ut_get_status();
      if (status == UT_SYNTAX) {
        throw UnitError(fmt::format("cannot read the unit '{}'", text));
      }
      throw UnitError(fmt::format("unknown unit '{}'", text));
    }
    return u;
  }

  std::string describe(const ut_unit* u) const {
    for (const auto& r : kDimensions) {
      if (r.dimension == Dimension::Dimensionless) continue;
      const auto ref = parse_unit(r.si);
      if (ut_are_convertible(u, ref.get()) != 0) {
        return with_article(r.name);
      }
    }
    for (const auto& [name, si] : kOtherDimensions) {
      const auto ref = parse_unit(si);
      if (ut_are_convertible(u, ref.get()) != 0) return with_article(name);
    }
    char buf[256];
    if (ut_format(u, buf, sizeof buf, UT_ASCII | UT_DEFINITION) > 0) {
      return fmt::format("a quantity in {}", buf);
    }
    return "a quantity of another dimension";
  }

  double to_si(double value, std::string_view unit_text, Dimension expected) const {
    const auto unit_str = trim(unit_text);
    const auto& r = row(expected);
    if (expected == Dimension::Dimensionless) {
      if (!unit_str.empty()) {
        throw UnitError(fmt::format("takes a plain number without unit, not '{}'", unit_str));
      }
      return value;
    }
    if (unit_str.empty()) return value;  // SI already
    const auto given = parse_unit(unit_str);
    const auto target = parse_unit(r.si);
    const bool convertible = ut_are_convertible(given.get(), target.get()) != 0;
    if (!convertible) {
      throw UnitError(fmt::format("'{}' is {}, but {} is needed (e.g. \"{}\")", unit_str,
                                  describe(given.get()), with_article(r.name), r.example));
    }
    ConverterPtr conv(ut_get_converter(given.get(), target.get()));
    if (!conv) throw UnitError(fmt::format("cannot convert '{}' to {}", unit_str, r.shown));
    return cv_convert_double(conv.get(), value);
  }
};

UnitParser::UnitParser() : impl_(std::make_unique<Impl>()) {
  // The library reports through a process-wide handler; we report errors ourselves.
  ut_set_error_message_handler(ut_ignore);
  impl_->system = ut_read_xml(nullptr);
  if (impl_->system == nullptr) {
    throw std::runtime_error(
        "cannot load the UDUNITS-2 unit database (is Debian's libudunits2-data installed, or "
        "UDUNITS2_XML_PATH set?)");
  }
  // "deg" is the usual short name for the arc degree; the database spells it "degree"/"arcdeg".
  ut_unit* degree = ut_get_unit_by_name(impl_->system, "degree");
  if (degree != nullptr) {
    ut_map_symbol_to_unit("deg", UT_ASCII, degree);
    ut_free(degree);
  }
}

UnitParser::~UnitParser() = default;
UnitParser::UnitParser(UnitParser&&) noexcept = default;
UnitParser& UnitParser::operator=(UnitParser&&) noexcept = default;

double UnitParser::parse(std::string_view text, Dimension expected) const {
  const auto s = trim(text);
  if (s.empty()) {
    throw UnitError(fmt::format("the value is empty; write a number with a unit (e.g. \"{}\")",
                                row(expected).example));
  }
  const auto n = leading_number(s);
  if (n.ec == std::errc::result_out_of_range) {
    throw UnitError(fmt::format("'{}' is out of range", s));
  }
  if (n.ec != std::errc() || n.rest.size() == s.size()) {
    throw UnitError(
        fmt::format("'{}' does not start with a number (e.g. \"{}\")", s, row(expected).example));
  }
  if (!std::isfinite(n.value)) throw UnitError(fmt::format("'{}' is not a finite number", s));
  const double si = impl_->to_si(n.value, n.rest, expected);
  if (!std::isfinite(si)) throw UnitError(fmt::format("'{}' is not a finite number", s));
  return si;
}

bool is_bare_number(std::string_view text) {
  const auto s = trim(text);
  const auto n = leading_number(s);
  return !s.empty() && n.ec == std::errc() && n.rest.size() < s.size() && trim(n.rest).empty();
}

bool UnitParser::is_unit(std::string_view text) const {
  const auto s = trim(text);
  if (s.empty()) return false;
  try {
    (void)impl_->parse_unit(s);
    return true;
  } catch (const UnitError&) {
    return false;
  }
}

double UnitParser::to_si(double value, std::string_view unit, Dimension expected) const {
  return impl_->to_si(value, unit, expected);
}

double UnitParser::from_si(double value_si, std::string_view unit, Dimension d) const {
  return value_si / impl_->to_si(1.0, unit, d);
}

}  // namespace snapjump::units
