#pragma once
// `headlight diff A B [options]`: compares two images, or two render folders
// target by target, with the library's headlight/diff.hpp. The exit code is
// the (worst) DiffStatus: 0 pass, 1 warn, 2 fail, 3 structural mismatch,
// 4 file error; 5 is a usage error. docs/DIFF.md describes it all.
#include <iosfwd>
#include <string>
#include <vector>

namespace headlight::cli {

// Runs the command on the arguments after "diff", printing to std::cout and
// std::cerr; returns the exit code. Never throws.
int runDiffCommand(const std::vector<std::string>& args);

// The same, printing to `out` (results, JSON) and `err` (usage and write errors).
int runDiffCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err);

// `headlight diff --help`, including the default threshold table.
std::string diffHelp();

}  // namespace headlight::cli
