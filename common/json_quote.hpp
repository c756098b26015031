// A JSON string literal (RFC 8259): the text in double quotes, with the quote, the backslash and
// every control character escaped. One function for every JSON file mppm writes (run_info.json,
// summary.json).
#pragma once
#include <string>

namespace mppm {

std::string json_quote(const std::string& text);

}  // namespace mppm
