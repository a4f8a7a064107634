// Text from outside (OpenStreetMap names and addresses, URL parameters, file names) made safe for
// the places it goes: valid UTF-8 for JSON and CSV files, and a form for the screen that cannot
// hide, fake or reorder the text around it.
//
// Contract: every function takes any bytes and never fails; valid UTF-8 without the characters
// named below comes back unchanged. Invalid UTF-8 (stray continuation bytes, truncated or overlong
// sequences, surrogates, code points above U+10FFFF) is replaced by U+FFFD, one per maximal
// invalid subpart as Unicode §3.9 recommends.
#pragma once

#include <string>
#include <string_view>

namespace qv {

/// True when `text` is well-formed UTF-8.
bool isValidUtf8(std::string_view text);

/// `text` with each invalid UTF-8 sequence replaced by U+FFFD (unchanged when it is valid).
std::string toValidUtf8(std::string_view text);

/// True when displaySafe(text) would change `text`.
bool needsDisplayCleaning(std::string_view text);

/// `text` as a panel or list shows it, on one line, with nothing that can reorder or hide the
/// surrounding text:
///   - line breaks and tabs (CR, LF, TAB, VT, FF, NEL, U+2028, U+2029) become a space;
///   - other control characters (C0, DEL, C1) become U+FFFD, so that they stay visible;
///   - bidirectional controls (U+202A–U+202E embeddings and overrides, U+2066–U+2069 isolates,
///     U+200E/U+200F/U+061C marks) are removed: a name cannot turn the rest of a line around;
///   - invalid UTF-8 becomes U+FFFD.
std::string displaySafe(std::string_view text);

}  // namespace qv
