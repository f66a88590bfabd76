#include "tooling/large_pages.hpp"

#include <unistd.h>

#include <cstdlib>
#include <fstream>

namespace headlight {
namespace {

constexpr const char* kTunables = "GLIBC_TUNABLES";
constexpr const char* kLargePages = "glibc.malloc.hugetlb=1";

// The kernel's policy, the bracketed word of
// /sys/kernel/mm/transparent_hugepage/enabled ("always [madvise] never");
// empty where the file is missing (no THP in this kernel, or no /sys).
std::string hugePagePolicy() {
  std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  std::getline(file, line);
  const std::size_t open = line.find('['), close = line.find(']');
  return open != std::string::npos && close != std::string::npos && close > open
             ? line.substr(open + 1, close - open - 1)
             : std::string();
}

}  // namespace

void restartWithLargePages(char** argv) {
  if (std::getenv(kTunables) != nullptr || hugePagePolicy() != "madvise") return;
  if (setenv(kTunables, kLargePages, 1) != 0) return;
  execv("/proc/self/exe", argv);
  unsetenv(kTunables);  // no restart (no /proc?): go on as started
}

std::string largePagesNote() {
  const std::string policy = hugePagePolicy();
  const char* tunables = std::getenv(kTunables);
  std::string note = "memory: transparent huge pages ";
  if (policy.empty()) return note + "not offered by this kernel";
  if (policy == "always") return note + "always on (kernel policy)";
  if (policy == "never") return note + "off (kernel policy 'never')";
  if (tunables == nullptr) return note + "off (policy '" + policy + "', GLIBC_TUNABLES not set)";
  return note + (std::string(tunables).find(kLargePages) != std::string::npos ? "on" : "off") + " (policy '" + policy +
         "', GLIBC_TUNABLES=" + tunables + ")";
}

}  // namespace headlight
