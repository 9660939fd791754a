// Quoting text taken from an input file inside an error message, safely for a terminal.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace glint {

// text with every byte outside printable ASCII (control characters, DEL, and all bytes of
// 0x80 and above, so also UTF-8) written as \xNN, so that a binary or hostile file cannot
// send escape sequences to the terminal that prints the message. Longer text is cut to
// its first maxLength bytes followed by "... (N bytes)" with its whole length (a binary
// "header line" can be megabytes long); std::string::npos keeps all of it, for escaping a
// whole message.
std::string printableText(std::string_view text, size_t maxLength = 80);

}  // namespace glint
