// The token an operator command from the page must carry: drawn at start from OpenSSL's
// generator, printed once on the monitor's terminal, compared in constant time so that a
// guesser learns nothing from how long a refusal takes.
#pragma once

#include <string>
#include <string_view>

namespace rpsd::monitor {

// 32 hexadecimal digits (128 random bits). Throws std::runtime_error if the generator fails.
std::string draw_access_token();
// True only for the same non-empty text.
bool token_matches(std::string_view expected, std::string_view given);

}  // namespace rpsd::monitor
