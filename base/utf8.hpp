// Text that is valid UTF-8 whatever bytes it quotes: file names, BDDL tokens
// and paths reach messages, JSON and CSV as the user wrote them, and
// nlohmann::json (type_error.316), Python's str and terminals refuse or mangle
// invalid bytes.
#pragma once

#include <string>
#include <string_view>

namespace chore {

// `text` with each byte that is not part of a well-formed UTF-8 sequence
// (RFC 3629: no overlongs, no surrogates, nothing past U+10FFFF) written as
// the four characters \xNN; valid text comes back unchanged.
std::string valid_utf8(std::string_view text);

}  // namespace chore
