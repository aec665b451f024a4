// What every fuzz target checks on the bytes it is given, read as a file
// named `name` (its extension picks the reader):
//  - reading fails only with pdd::InputError (one message naming the file);
//  - what reads as a point set or as a mesh is written in the same format and
//    read back to the same values, bit for bit (the writers are exact).
// Anything else (another exception, a sanitizer report, a mismatch) aborts,
// which libFuzzer reports with the input that did it.
#pragma once

#include <cstddef>
#include <cstdint>

namespace pdd::fuzz {

int read_write_read(const char* name, const std::uint8_t* data, std::size_t size);

}  // namespace pdd::fuzz
