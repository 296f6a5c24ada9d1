// The one base of every error that bad input causes (a case value, a unit, a time series, a
// mesh, a sweep file, a figure's input): the command line maps it to exit status 2, and a
// program embedding the library can catch it once. what() names the file, key or flag.
#pragma once

#include <stdexcept>

namespace snapjump {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace snapjump
