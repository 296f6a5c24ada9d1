#include "config/units.hpp"

#include <fmt/format.h>
#include <udunits2.h>

#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
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
    DimensionRow{Dimension::Energy, "energy", "J", "J", "1 mJ"},
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

// The unit text may be a product of units and their small integer powers, nothing else: UDUNITS
// also reads numbers as scale factors ("mm 2", "m -2"), offsets ("mm @ 5", "s since 2000-01-01")
// and logarithms ("lg(re 1 mW)"), and an exponent too large for an int wraps around.
constexpr int kMaxExponent = 4;

bool is_unit_char(unsigned char ch) {
  return std::isalpha(ch) != 0 || ch == '_' || ch == '%' || ch == '\'' || ch == '"' || ch >= 0x80;
}

// The UTF-8 superscript digit or minus at s[i] (its value, 10 for the minus, and its length).
std::optional<std::pair<int, std::size_t>> superscript(std::string_view s, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
  if (i + 1 < s.size() && byte(i) == 0xC2) {
    if (byte(i + 1) == 0xB9) return std::pair{1, std::size_t{2}};
    if (byte(i + 1) == 0xB2) return std::pair{2, std::size_t{2}};
    if (byte(i + 1) == 0xB3) return std::pair{3, std::size_t{2}};
  }
  if (i + 2 < s.size() && byte(i) == 0xE2 && byte(i + 1) == 0x81) {
    const unsigned char last = byte(i + 2);
    if (last == 0xB0 || (last >= 0xB4 && last <= 0xB9)) {
      return std::pair{last == 0xB0 ? 0 : last - 0xB0, std::size_t{3}};
    }
    if (last == 0xBB) return std::pair{10, std::size_t{3}};
  }
  return std::nullopt;
}

void check_exponent(std::string_view unit, std::string_view digits, bool negative) {
  const bool small = !digits.empty() && digits.size() <= 2 &&
                     std::stoi(std::string(digits)) <= kMaxExponent &&
                     std::stoi(std::string(digits)) > 0;
  if (!small) {
    throw UnitError(fmt::format(
        "the unit '{}' has the power {}{}; a unit's powers are whole numbers from -{} to {}",
        text::excerpt(unit), negative ? "-" : "", digits, kMaxExponent, kMaxExponent));
  }
}

// Reads the power at s[i] after a unit name or ')': "^2", "**-1", "2", "-3" or superscripts.
std::size_t skip_power(std::string_view unit, std::size_t i) {
  const auto& s = unit;
  std::size_t k = i;
  const bool marked = s.substr(k, 1) == "^" || s.substr(k, 2) == "**";
  if (marked) k += s[k] == '^' ? 1 : 2;
  if (auto sup = superscript(s, k); !marked && sup) {
    std::string digits;
    bool negative = false;
    for (; sup; sup = superscript(s, k)) {
      if (sup->first == 10) {
        negative = true;
      } else {
        digits += static_cast<char>('0' + sup->first);
      }
      k += sup->second;
    }
    check_exponent(unit, digits, negative);
    return k;
  }
  const std::size_t sign = k;
  if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
  const std::size_t first = k;
  while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])) != 0) ++k;
  if (k == first) {
    if (marked) throw UnitError(fmt::format("cannot read the unit '{}'", text::excerpt(unit)));
    return i;  // no power: a '-' here is a product ("kg-m")
  }
  check_exponent(unit, s.substr(first, k - first), sign < first && s[sign] == '-');
  return k;
}

[[maybe_unused]] void check_plain_product(std::string_view unit) {
  const auto refuse = [&](std::string_view what) {
    throw UnitError(fmt::format(
        "the unit '{}' {}; write a product of units and their powers (e.g. \"kg/m^3\", \"Pa^-1 "
        "s^-2\")",
        text::excerpt(unit), what));
  };
  std::size_t i = 0;
  while (i < unit.size()) {
    const auto ch = static_cast<unsigned char>(unit[i]);
    if (is_unit_char(ch) && !superscript(unit, i)) {
      const std::size_t first = i;
      while (i < unit.size() && is_unit_char(static_cast<unsigned char>(unit[i])) &&
             !superscript(unit, i)) {
        ++i;
      }
      const auto name = text::lower(unit.substr(first, i - first));
      if (name == "after" || name == "from" || name == "since" || name == "ref") {
        refuse(fmt::format("shifts its origin with '{}'",
                           text::excerpt(unit.substr(first, i - first))));
      }
      const auto next = unit.find_first_not_of(' ', i);
      const bool call = next != std::string_view::npos && unit[next] == '(';
      if (call && (name == "log" || name == "lg" || name == "ln" || name == "lb")) {
        refuse("is a logarithm");
      }
      i = skip_power(unit, i);
    } else if (ch == ')') {
      i = skip_power(unit, i + 1);
    } else if (ch == '@') {
      refuse("shifts its origin with '@'");
    } else if (std::isdigit(ch) != 0) {
      // A factor: only the 1 of "1/s" is taken.
      const auto after = unit.find_first_not_of(' ', i + 1);
      if (ch != '1' || after == std::string_view::npos || unit[after] != '/') {
        refuse("holds a number; the number goes before the unit");
      }
      ++i;
    } else if (std::string_view(" */.()-").find(static_cast<char>(ch)) != std::string_view::npos) {
      ++i;
    } else {
      refuse(fmt::format("holds '{}'", text::excerpt(std::string(1, static_cast<char>(ch)))));
    }
  }
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
        throw UnitError(fmt::format("cannot read the unit '{}'", text::excerpt(text)));
      }
      throw UnitError(fmt::format("unknown unit '{}'", text::excerpt(text)));
    }
    return u;
  }

  // The factor that takes a value in `given` to `target` when the two are the same dimension: a
  // plain scale. UDUNITS also converts a unit to its reciprocal (m^-1 to m as 1/x), which is not
  // the same quantity; nullopt then, and for units of other dimensions.
  static std::optional<double> scale(const ut_unit* given, const ut_unit* target) {
    if (ut_are_convertible(given, target) == 0) return std::nullopt;
    ConverterPtr conv(ut_get_converter(const_cast<ut_unit*>(given), const_cast<ut_unit*>(target)));
    if (!conv) return std::nullopt;
    const double zero = cv_convert_double(conv.get(), 0.0);
    const double one = cv_convert_double(conv.get(), 1.0);
    const double two = cv_convert_double(conv.get(), 2.0);
    const bool linear = zero == 0.0 && std::isfinite(one) && one != 0.0 &&
                        std::abs(two - 2.0 * one) <= 1e-12 * std::abs(one);
    if (!linear) return std::nullopt;
    return one;
  }

  // "a length", "the reciprocal of a length", "an energy", for messages.
  std::string describe(const ut_unit* u) const {
    const auto kind = [&](std::string_view si) {
      const auto ref = parse_unit(si);
      if (scale(u, ref.get())) return 1;
      return ut_are_convertible(u, ref.get()) != 0 ? -1 : 0;
    };
    for (const auto& r : kDimensions) {
      if (r.dimension == Dimension::Dimensionless) continue;
      if (const int k = kind(r.si); k != 0) {
        return k > 0 ? with_article(r.name) : "the reciprocal of " + with_article(r.name);
      }
    }
    for (const auto& [name, si] : kOtherDimensions) {
      if (const int k = kind(si); k != 0) {
        return k > 0 ? with_article(name) : "the reciprocal of " + with_article(name);
      }
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
        throw UnitError(
            fmt::format("takes a plain number without unit, not '{}'", text::excerpt(unit_str)));
      }
      return value;
    }
    if (unit_str.empty()) return value;  // SI already
    check_plain_product(unit_str);
    const auto given = parse_unit(unit_str);
    const auto target = parse_unit(r.si);
    const auto factor = scale(given.get(), target.get());
    // The database counts angles as dimensionless (rad^2 and 1/rad convert to rad): an angle's
    // unit is one name alone ("deg", "rad").
    const bool one_name = expected != Dimension::Angle ||
                          unit_str.find_first_of(" */.()-^0123456789") == std::string_view::npos;
    if (!factor || !one_name) {
      const auto what = factor ? std::string("not an angle's unit") : describe(given.get());
      throw UnitError(fmt::format("'{}' is {}, but {} is needed (in {} or a multiple, e.g. \"{}\")",
                                  text::excerpt(unit_str), what, with_article(r.name), r.shown,
                                  r.example));
    }
    return value * *factor;
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
    throw UnitError(fmt::format("'{}' is out of range", text::excerpt(s)));
  }
  if (n.ec != std::errc() || n.rest.size() == s.size()) {
    throw UnitError(fmt::format("'{}' does not start with a number (e.g. \"{}\")", text::excerpt(s),
                                row(expected).example));
  }
  if (!std::isfinite(n.value))
    throw UnitError(fmt::format("'{}' is not a finite number", text::excerpt(s)));
  const double si = impl_->to_si(n.value, n.rest, expected);
  if (!std::isfinite(si))
    throw UnitError(fmt::format("'{}' is not a finite number", text::excerpt(s)));
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
