// Comma-separated lists: option values (--times 20us,40us), CSV rows of the run files.
#pragma once
#include <string>
#include <vector>

namespace mppm {

// The items in order, untrimmed: "a,,b," gives {"a", "", "b", ""} (empty items are kept, the
// trailing one too, so a caller can refuse them); "" gives {}.
std::vector<std::string> split_commas(const std::string& text);

// `text` without leading and trailing blanks (spaces, tabs, carriage returns).
std::string trim_blanks(const std::string& text);

}  // namespace mppm
