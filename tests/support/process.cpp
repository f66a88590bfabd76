#include "support/process.hpp"

#include <sys/wait.h>
#include <array>
#include <cstdio>
#include <stdexcept>

namespace headlight::test {

std::string shellQuote(const std::string& text) {
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

ProcessResult runCommand(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) throw std::runtime_error("runCommand: popen failed for: " + command);
  ProcessResult result;
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

ProcessResult runHeadlight(const std::string& args) { return runCommand(shellQuote(HEADLIGHT_EXE) + " " + args); }

}  // namespace headlight::test
