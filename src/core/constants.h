// conformesh — mathematical constants, each defined once for the library and its tests.
#pragma once

namespace conformesh {

//! π to double precision (M_PI is not standard C++).
constexpr double kPi = 3.14159265358979323846;

}  // namespace conformesh
