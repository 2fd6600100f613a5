// The text layer shared by the OBJ and MTL readers (obj_mesh.h, mtl_file.h):
// lines with their numbers (\n, \r\n or \r; a trailing '\' continues a line;
// '#' at the start or after a blank starts a comment), blank-separated
// tokens and locale-independent numbers.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace duskmap {

class ObjTextLines {
 public:
  explicit ObjTextLines(std::string_view text) : text_(text) {}

  // The next line with content (comment removed, blanks trimmed); false at
  // the end. `line_number` is where the line starts (1-based).
  bool Next(std::string_view* line, int* line_number);

 private:
  std::string_view NextRawLine();  // trimmed, without its line break

  std::string_view text_;
  size_t position_ = 0;
  int line_number_ = 0;
  std::string joined_;  // storage for a line continued with '\'
};

// Splits off the first blank-separated token of *rest (leading blanks
// skipped); empty when none is left.
std::string_view NextObjToken(std::string_view* rest);

// `text` without leading and trailing blanks.
std::string_view TrimObjBlanks(std::string_view text);

// A finite decimal number (an optional leading '+' allowed), or nullopt.
std::optional<double> ParseObjNumber(std::string_view token);

// A decimal integer, or nullopt.
std::optional<long long> ParseObjInteger(std::string_view token);

}  // namespace duskmap
