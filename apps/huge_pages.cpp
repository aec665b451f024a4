#include "huge_pages.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#if defined(__GLIBC__)
#include <gnu/libc-version.h>
#endif

namespace pdd::cli {
namespace {

// The kernel's policy: "always", "madvise" or "never" (empty when unknown).
std::string transparent_huge_pages() {
  std::ifstream in("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(in, line)) return {};
  const auto open = line.find('['), close = line.find(']');
  if (open == std::string::npos || close == std::string::npos || close < open) return {};
  return line.substr(open + 1, close - open - 1);
}

bool glibc_has_hugetlb_tunable() {
#if defined(__GLIBC__)
  int major = 0, minor = 0;
  if (std::sscanf(gnu_get_libc_version(), "%d.%d", &major, &minor) != 2) return false;
  return major > 2 || (major == 2 && minor >= 35);
#else
  return false;
#endif
}

}  // namespace

bool ask_for_huge_pages() {
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string current = tunables ? tunables : "";
  if (current.find("glibc.malloc.hugetlb") != std::string::npos) return false;
  if (!glibc_has_hugetlb_tunable() || transparent_huge_pages() != "madvise") return false;
  const std::string asked =
      (current.empty() ? "" : current + ":") + "glibc.malloc.hugetlb=1";
  return ::setenv("GLIBC_TUNABLES", asked.c_str(), 1) == 0;
}

}  // namespace pdd::cli
