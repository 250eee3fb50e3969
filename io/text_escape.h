// Text written into structured files, escaped so that any bytes give a valid file:
//   json_string  a JSON string literal (RFC 8259): quotes and backslashes escaped,
//                control characters as \u00XX, invalid UTF-8 replaced by U+FFFD
//   csv_field    one CSV field (RFC 4180): quoted, with quotes doubled, when it
//                holds a comma, a quote, CR or LF; otherwise as it is
//   valid_utf8   the text with every invalid UTF-8 sequence replaced by U+FFFD
//   shell_quote  a POSIX shell word: '...' with ' written as '\'' (any bytes)
//   json_number  a JSON number at 17 digits (round-trips), null when not finite, no -0
//   xml_text     text for an XML 1.0 attribute value or element: & < > " ' as
//                entities, characters XML 1.0 forbids (controls but tab, LF,
//                CR) as U+FFFD, invalid UTF-8 as U+FFFD
#pragma once

#include <string>

namespace evas {

std::string valid_utf8(const std::string& s);
std::string json_string(const std::string& s);
std::string csv_field(const std::string& s);
std::string shell_quote(const std::string& s);
std::string json_number(double x);
std::string xml_text(const std::string& s);

}  // namespace evas
