// knit/error.hpp — the one exception type for bad user input (files, meshes, options).
//
// Errors are raised at the boundary (parsers, option validation), never from inside numeric
// loops: stages validate their inputs first, then run without throwing for data problems.
#pragma once
#include <stdexcept>
#include <string>

namespace knit {

class Error : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

}  // namespace knit
