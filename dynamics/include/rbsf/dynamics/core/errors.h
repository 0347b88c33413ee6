#pragma once
/// \file
/// \brief The exception every loader and parser throws for bad input.

#include <stdexcept>
#include <string>

namespace rbsf {

/// \brief Bad input (cell file, command-line value, state): the message names the
///        offending key, argument or value. Tools map it to exit status 2.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rbsf
