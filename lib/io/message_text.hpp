#pragma once
// How a message quotes what it was given (a name from a file, a value from
// the command line): bounded, so that one long input cannot make a message
// of megabytes (a 100 KB --material-variant was echoed whole, a file's
// 200,000 variant names listed in 3.4 MB; issue 32).
#include <string>
#include <string_view>
#include <vector>

namespace headlight {

// 'text', cut to its first 80 bytes: "'xxxx...' (100000 bytes)".
std::string quotedName(std::string_view text);
// "'a', 'b', ... and 199980 more": at most 20 items, each quotedName.
std::string quotedList(const std::vector<std::string>& items);

}  // namespace headlight
