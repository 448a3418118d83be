#include "uampc/mpc/uncertainty_surrogate.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "angles.hpp"

namespace uampc::mpc {

namespace {
using detail::kTwoPi;
}  // namespace

UncertaintySurrogate::UncertaintySurrogate(double theta_start, double step,
                                           std::vector<double> samples)
    : theta_start_(theta_start), step_(step), samples_(std::move(samples)) {
  if (samples_.empty()) throw std::invalid_argument("UncertaintySurrogate: no samples");
  if (!std::isfinite(theta_start_)) {
    throw std::invalid_argument("UncertaintySurrogate: theta_start is not finite");
  }
  if (!(std::abs(step_ * samples_.size() - kTwoPi) < 1e-9)) {
    throw std::invalid_argument("UncertaintySurrogate: " + std::to_string(samples_.size()) +
                                " samples every " + std::to_string(step_) +
                                " rad do not make one turn; use turnStep(count)");
  }
  for (double u : samples_) {
    if (!std::isfinite(u)) throw std::invalid_argument("UncertaintySurrogate: non-finite sample");
  }
}

int UncertaintySurrogate::samplesPerTurn(double step) {
  if (!(step > 0.0) || step > kTwoPi) {
    throw std::invalid_argument("UncertaintySurrogate: sample step must be in (0, 2 pi]");
  }
  return static_cast<int>(std::lround(kTwoPi / step));
}

double UncertaintySurrogate::turnStep(int count) { return kTwoPi / count; }

void UncertaintySurrogate::evaluate(double theta, double* value, double* slope) const {
  const long long n = static_cast<long long>(samples_.size());
  const double t = (theta - theta_start_) / step_;
  if (!std::isfinite(t)) {  // a NaN angle stays visible instead of indexing at random
    if (value != nullptr) *value = std::numeric_limits<double>::quiet_NaN();
    if (slope != nullptr) *slope = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  const double whole = std::floor(t);
  const double fraction = t - whole;  // in [0, 1)
  long long s = static_cast<long long>(whole) % n;
  if (s < 0) s += n;
  const double u0 = samples_[s];
  const double u1 = samples_[(s + 1) % n];  // the 2 pi wrap: U_N = U_0
  if (value != nullptr) *value = u0 + fraction * (u1 - u0);  // Eq. 9
  if (slope != nullptr) *slope = (u1 - u0) / step_;           // Eq. 10
}

double UncertaintySurrogate::value(double theta) const {
  double v = 0.0;
  evaluate(theta, &v, nullptr);
  return v;
}

double UncertaintySurrogate::slope(double theta) const {
  double s = 0.0;
  evaluate(theta, nullptr, &s);
  return s;
}

}  // namespace uampc::mpc
