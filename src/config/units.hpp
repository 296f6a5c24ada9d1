// Physical quantities written with units ("30 mm", "1.2 MPa", "80 deg") turned into SI numbers.
//
// The unit database is that of UDUNITS-2 (Debian's libudunits2), so any unit it knows works, with
// SI prefixes, as products and powers from -4 to 4 ("kg/m^3", "Pa^-1 s^-2", "mL"); a quantity is
// taken only in its own dimension (never through its reciprocal), and UDUNITS' offsets ('@',
// "since"), logarithms and factors inside the unit are refused. A bare number is taken to be in
// SI already. The parser owns its unit system; there is no global state.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "config/input_error.hpp"

namespace snapjump::units {

// What kind of quantity a value must be. Each has an SI unit that the parser converts to.
enum class Dimension {
  Length,             // m
  Angle,              // rad
  Pressure,           // Pa
  Force,              // N
  Mass,               // kg
  Density,            // kg/m^3
  Volume,             // m^3
  Time,               // s
  Dimensionless,      // plain number, no unit allowed
  ValveAcceleration,  // Pa^-1 s^-2 (the gas law's alpha_n)
  ValveRate,          // Pa^-1 s^-1 (the gas law's beta_n)
  Stiffness,          // N/m (a spring: the counterweight's wire)
  Energy,             // J (a design's stored energy)
};

// "length", "pressure", ...
std::string_view dimension_name(Dimension d);
// The SI unit a Dimension is converted to, as written in messages ("m", "Pa", "kg/m^3").
std::string_view si_unit(Dimension d);
// A sample value with a unit, for error messages ("30 mm").
std::string_view example(Dimension d);

// True when text is a number alone, without a unit ("40", " 4e-2 "): parse() reads it in SI.
bool is_bare_number(std::string_view text);

// A value that could not be understood. The message does not name the key: the caller adds it.
class UnitError : public InputError {
 public:
  using InputError::InputError;
};

class UnitParser {
 public:
  // Loads the unit database; throws std::runtime_error if it cannot be found.
  UnitParser();
  ~UnitParser();
  UnitParser(const UnitParser&) = delete;
  UnitParser& operator=(const UnitParser&) = delete;
  UnitParser(UnitParser&&) noexcept;
  UnitParser& operator=(UnitParser&&) noexcept;

  // "30 mm" -> 0.03 for Dimension::Length. A number without unit is SI. Throws UnitError on an
  // unknown unit, a wrong dimension, a missing number or a non-finite value.
  [[nodiscard]] double parse(std::string_view text, Dimension expected) const;

  // value expressed in `unit` -> SI value of `expected`. Throws UnitError as parse().
  [[nodiscard]] double to_si(double value, std::string_view unit, Dimension expected) const;

  // SI value -> value in `unit` (for printing in convenient units). Throws UnitError.
  [[nodiscard]] double from_si(double value_si, std::string_view unit, Dimension d) const;

  // Whether the database knows `text` as a unit, of any dimension ("mm", "kPa", "kg/m^3").
  [[nodiscard]] bool is_unit(std::string_view text) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace snapjump::units
