#include "app/option_values.hpp"

#include <fmt/format.h>

#include <cmath>

#include "config/case.hpp"

namespace snapjump::app {

double quantity_option(const units::UnitParser& parser, const std::string& text, units::Dimension d,
                       const char* flag) {
  double v = 0.0;
  try {
    v = parser.parse(text, d);
  } catch (const units::UnitError& e) {
    throw config::CaseError(fmt::format("{}: {}", flag, e.what()));
  }
  if (!std::isfinite(v)) throw config::CaseError(fmt::format("{} {}: not finite", flag, text));
  return v;
}

double positive_option(const units::UnitParser& parser, const std::string& text, units::Dimension d,
                       const char* flag) {
  const double v = quantity_option(parser, text, d, flag);
  if (!(v > 0.0)) throw config::CaseError(fmt::format("{} {}: must be positive", flag, text));
  return v;
}

std::pair<std::string, std::string> name_value(const std::string& text, const char* flag) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
    throw config::CaseError(fmt::format(
        "{} {}: write NAME=VALUE, e.g. --column t=\"Time (s)\" or --unit F=mN", flag, text));
  }
  return {text.substr(0, eq), text.substr(eq + 1)};
}

}  // namespace snapjump::app
