// The circle constants of the mpc core's sources, defined once.
#pragma once

namespace uampc::mpc::detail {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;

}  // namespace uampc::mpc::detail
