// libFuzzer's entry for the XYZ reader; see round_trip.h.
#include "round_trip.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return pdd::fuzz::read_write_read("input.xyz", data, size);
}
