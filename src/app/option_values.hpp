// The values of command-line options that the subcommands share: a quantity with its unit, and
// NAME=VALUE pairs (--column, --unit). Errors are config::CaseError naming the option.
#pragma once

#include <string>
#include <utility>

#include "config/units.hpp"

namespace snapjump::app {

// `text` as a quantity of dimension `d` in SI; `flag` names the option in the error. Not finite
// is an error too.
double quantity_option(const units::UnitParser& parser, const std::string& text, units::Dimension d,
                       const char* flag);
// The same, and it must be positive.
double positive_option(const units::UnitParser& parser, const std::string& text, units::Dimension d,
                       const char* flag);
// "NAME=TEXT" -> {NAME, TEXT}.
std::pair<std::string, std::string> name_value(const std::string& text, const char* flag);

}  // namespace snapjump::app
