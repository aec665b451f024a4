// Equal-width histograms of quality measures.
#include <pdd/quality.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace pdd {

Histogram histogram(const std::vector<double>& values, double lower, double upper, int bins) {
  if (bins < 1 || !(upper > lower))
    throw std::invalid_argument("histogram: needs bins >= 1 and upper > lower");
  Histogram h;
  h.lower = lower;
  h.bin_width = (upper - lower) / bins;
  h.counts.assign(bins, 0);
  for (const double v : values) {
    if (std::isnan(v)) continue;
    const double bin = std::floor((v - lower) / h.bin_width);
    ++h.counts[static_cast<std::size_t>(std::clamp(bin, 0.0, bins - 1.0))];
  }
  return h;
}

}  // namespace pdd
