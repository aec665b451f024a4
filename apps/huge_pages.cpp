#include "huge_pages.h"

#include <cstdlib>
#include <fstream>
#include <string>

namespace pdd::cli {

bool ask_for_huge_pages() {
#if defined(__GLIBC__) && __GLIBC_PREREQ(2, 35)
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  const std::string current = tunables ? tunables : "";
  if (current.find("glibc.malloc.hugetlb") != std::string::npos) return false;
  // The kernel's policy, its choice in brackets: "always [madvise] never".
  std::ifstream policy("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  if (!std::getline(policy, line) || line.find("[madvise]") == std::string::npos) return false;
  const std::string asked = (current.empty() ? "" : current + ":") + "glibc.malloc.hugetlb=1";
  return ::setenv("GLIBC_TUNABLES", asked.c_str(), 1) == 0;
#else
  return false;
#endif
}

}  // namespace pdd::cli
