#pragma once
// What the validation of a parameter struct names when it refuses it: InputError::where() (the
// field or flag at fault), or "(accepted)". Tests of every validate(P) read the refusal this way.
#include <string>

#include "util/input_error.h"

namespace kinray::test {

template <class Params>
std::string rejected_where(const Params& params) {
  try {
    validate(params);  // found by argument-dependent lookup, beside Params
  } catch (const InputError& e) {
    return e.where();
  }
  return "(accepted)";
}

}  // namespace kinray::test
