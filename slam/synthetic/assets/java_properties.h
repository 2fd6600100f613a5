// Java .properties text as java.util.Properties.load reads it: logical lines
// joined across a trailing backslash (the continuation's leading blanks
// dropped), '#' and '!' comment lines, a key ended by the first unescaped
// '=', ':' or blank, and the escapes \t \n \r \f \uXXXX and \<char> = <char>.
// Text that is valid UTF-8 is read as UTF-8, anything else as ISO-8859-1 (as
// Java 9+ resource bundles do); keys and values are returned in UTF-8.
#pragma once

#include <map>
#include <string>

namespace duskmap {

// The key -> value pairs of `text`; a key given twice keeps its last value.
// Throws InputError "<source>:<line>: malformed \uXXXX escape" for a \u not
// followed by four hexadecimal digits.
std::map<std::string, std::string> ParseJavaProperties(const std::string& text, const std::string& source);

}  // namespace duskmap
