// Private to src/: the points a statistic of the whole input is taken over.
// A quantile or a mean over the points is as good from 65536 of them, evenly
// strided through the input, as from all (its error is under 1 % there), and
// at a million points the per-point fits behind it took seconds.
#pragma once

#include <cstddef>

namespace pdd::detail {

constexpr std::size_t kStatisticsSample = std::size_t(1) << 16;

// Every stride-th point (0, stride, 2 stride, ...) of n: all of them up to kStatisticsSample.
inline std::size_t statistics_stride(std::size_t n) {
  return n <= kStatisticsSample ? 1 : (n + kStatisticsSample - 1) / kStatisticsSample;
}

}  // namespace pdd::detail
