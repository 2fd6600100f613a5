#include "slam/synthetic/assets/obj_text.h"

#include <charconv>
#include <cmath>

namespace duskmap {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }

// Cuts the comment: a '#' at the start of the line or after a blank.
std::string_view WithoutComment(std::string_view line) {
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '#' && (i == 0 || IsBlank(line[i - 1]))) return line.substr(0, i);
  }
  return line;
}

}  // namespace

bool ObjTextLines::Next(std::string_view* line, int* line_number) {
  while (position_ < text_.size()) {
    const int first = line_number_ + 1;
    std::string_view raw = NextRawLine();
    std::string_view whole = raw;
    if (!raw.empty() && raw.back() == '\\') {  // continued: join into joined_
      joined_.clear();
      while (!raw.empty() && raw.back() == '\\') {
        raw.remove_suffix(1);
        joined_.append(raw.data(), raw.size());
        joined_ += ' ';
        if (position_ >= text_.size()) break;
        raw = NextRawLine();
        if (raw.empty() || raw.back() != '\\') joined_.append(raw.data(), raw.size());
      }
      whole = joined_;
    }
    const std::string_view content = TrimObjBlanks(WithoutComment(whole));
    if (content.empty()) continue;
    *line = content;
    *line_number = first;
    return true;
  }
  return false;
}

std::string_view ObjTextLines::NextRawLine() {
  size_t end = position_;
  while (end < text_.size() && text_[end] != '\n' && text_[end] != '\r') ++end;
  const std::string_view raw = text_.substr(position_, end - position_);
  if (end < text_.size() && text_[end] == '\r' && end + 1 < text_.size() && text_[end + 1] == '\n') ++end;
  position_ = end + 1;
  ++line_number_;
  return TrimObjBlanks(raw);
}

std::string_view TrimObjBlanks(std::string_view text) {
  while (!text.empty() && IsBlank(text.front())) text.remove_prefix(1);
  while (!text.empty() && IsBlank(text.back())) text.remove_suffix(1);
  return text;
}

std::string_view NextObjToken(std::string_view* rest) {
  size_t begin = 0;
  while (begin < rest->size() && IsBlank((*rest)[begin])) ++begin;
  size_t end = begin;
  while (end < rest->size() && !IsBlank((*rest)[end])) ++end;
  const std::string_view token = rest->substr(begin, end - begin);
  rest->remove_prefix(end);
  return token;
}

std::optional<double> ParseObjNumber(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;  // from_chars refuses a second sign
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> ParseObjInteger(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  if (token.empty()) return std::nullopt;
  long long value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) return std::nullopt;
  return value;
}

}  // namespace duskmap
