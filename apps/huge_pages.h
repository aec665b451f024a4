// The heap on transparent huge pages: the solves and the optimizer stream
// arrays of hundreds of megabytes and gather from vectors of tens, and with
// 4 KB pages most of those gathers miss the TLB (docs/benchmarks.md, "Huge
// pages").
#pragma once

namespace pdd::cli {

// Asks glibc's malloc (2.35 and later, as built) to back its heap with
// transparent huge pages, through GLIBC_TUNABLES, which glibc reads only when
// a process starts: returns true when it set the variable and the process must start over for
// it to act. False when the kernel would not use them (transparent huge pages
// "never", or "always", where every heap has them already), when glibc is
// older, and when GLIBC_TUNABLES already says what to do (the user's choice:
// glibc.malloc.hugetlb=0 keeps 4 KB pages).
bool ask_for_huge_pages();

}  // namespace pdd::cli
