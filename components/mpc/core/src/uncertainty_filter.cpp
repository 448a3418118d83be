#include "uampc/mpc/uncertainty_filter.hpp"

#include <cmath>
#include <stdexcept>

namespace uampc::mpc {

namespace {
// The bin of the turn nearest to theta: bins are at whole multiples of step.
std::size_t binOf(double theta, double step, std::size_t bins) {
  const long long k = std::llround(theta / step) % static_cast<long long>(bins);
  return static_cast<std::size_t>(k < 0 ? k + static_cast<long long>(bins) : k);
}
}  // namespace

UncertaintyFilter::UncertaintyFilter(double weight) : weight_(weight) {
  if (!(weight > 0.0) || weight > 1.0) {
    throw std::invalid_argument("U filter weight must be in (0, 1], got " + std::to_string(weight));
  }
}

std::vector<double> UncertaintyFilter::apply(double theta_start, double step, std::vector<double> samples) {
  if (weight_ >= 1.0 || samples.empty()) return samples;
  const bool first = averages_.size() != samples.size();
  if (first) averages_.assign(samples.size(), 0.0);
  for (std::size_t s = 0; s < samples.size(); ++s) {
    double& average = averages_[binOf(theta_start + static_cast<double>(s) * step, step, samples.size())];
    average = first ? samples[s] : (1.0 - weight_) * average + weight_ * samples[s];
    samples[s] = average;
  }
  return samples;
}

}  // namespace uampc::mpc
