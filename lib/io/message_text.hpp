#pragma once
// How a message quotes what it was given (a name from a file, a value from
// the command line): bounded, so that one long input cannot make a message
// of megabytes (a 100 KB --material-variant was echoed whole, a file's
// 200,000 variant names listed in 3.4 MB; issue 32).
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace headlight {

// 'text', cut to its first 80 bytes: "'xxxx...' (100000 bytes)".
std::string quotedName(std::string_view text);
// How many items a list in a message shows.
inline constexpr std::size_t kListShown = 20;
// `shown` (at most kListShown items, as the caller words them) joined with
// ", ", then " ... and N more" for the rest of `total`.
std::string joinedList(const std::vector<std::string>& shown, std::size_t total);
// "'a', 'b', ... and 199980 more": the first kListShown items, each quotedName.
std::string quotedList(const std::vector<std::string>& items);
// A message of several lines (OpenImageIO's are newline-separated) as one:
// trailing newlines and spaces dropped, the others "; ".
std::string oneLine(std::string text);

}  // namespace headlight
