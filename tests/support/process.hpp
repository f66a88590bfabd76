#pragma once
// Running a program the way a user's shell does, output captured.
#include <filesystem>
#include <string>

namespace headlight::test {

struct ProcessResult {
  int exitCode = -1;   // -1 when the process did not exit normally (a signal)
  std::string output;  // stdout and stderr together, in the order written
  double seconds = 0;  // wall time from start to exit
  long peakRssKb = 0;  // the peak resident memory of the shell and what it ran (wait4's rusage)
};

// `text` in single quotes for /bin/sh (a quote inside is escaped).
std::string shellQuote(const std::string& text);
// shellQuote of a path (or of any text: a std::string converts unchanged):
// the CLI tests build their command lines with it.
inline std::string quote(const std::filesystem::path& path) { return shellQuote(path.string()); }

// Runs `command` with /bin/sh, stderr joined to stdout. Throws
// std::runtime_error when the shell cannot be started.
ProcessResult runCommand(const std::string& command);

// Runs the headlight binary of this build (HEADLIGHT_EXE) with `args`,
// which the caller quotes as the shell needs.
ProcessResult runHeadlight(const std::string& args);

}  // namespace headlight::test
