#include "slam/synthetic/assets/java_properties.h"

#include <cstdint>
#include <vector>

#include "slam/core/check.h"

namespace duskmap {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\f'; }

bool IsValidUtf8(const std::string& text) {
  size_t i = 0;
  while (i < text.size()) {
    const auto c = static_cast<unsigned char>(text[i]);
    int follow = 0;
    if (c < 0x80) {
      follow = 0;
    } else if (c >= 0xC2 && c <= 0xDF) {
      follow = 1;
    } else if (c >= 0xE0 && c <= 0xEF) {
      follow = 2;
    } else if (c >= 0xF0 && c <= 0xF4) {
      follow = 3;
    } else {
      return false;
    }
    if (i + follow >= text.size()) return false;  // cut short
    for (int k = 1; k <= follow; ++k) {
      if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return false;
    }
    i += follow + 1;
  }
  return true;
}

std::string Latin1ToUtf8(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c < 0x80) {
      out += ch;
    } else {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }
  return out;
}

void AppendUtf8(uint32_t code, std::string* out) {
  if (code < 0x80) {
    *out += static_cast<char>(code);
  } else if (code < 0x800) {
    *out += static_cast<char>(0xC0 | (code >> 6));
    *out += static_cast<char>(0x80 | (code & 0x3F));
  } else if (code < 0x10000) {
    *out += static_cast<char>(0xE0 | (code >> 12));
    *out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (code & 0x3F));
  } else {
    *out += static_cast<char>(0xF0 | (code >> 18));
    *out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    *out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    *out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

struct LogicalLine {
  std::string text;  // continuations joined, escapes still in place
  int line = 0;      // natural line (1-based) it starts on
};

// Splits into natural lines (\n, \r or \r\n), drops blank and comment lines
// and joins continuations.
std::vector<LogicalLine> LogicalLines(const std::string& text) {
  std::vector<std::string> natural;
  size_t begin = 0;
  while (begin < text.size()) {
    size_t end = begin;
    while (end < text.size() && text[end] != '\n' && text[end] != '\r') ++end;
    natural.push_back(text.substr(begin, end - begin));
    if (end < text.size() && text[end] == '\r' && end + 1 < text.size() && text[end + 1] == '\n') ++end;
    begin = end + 1;
  }
  std::vector<LogicalLine> lines;
  bool continuing = false;
  for (size_t n = 0; n < natural.size(); ++n) {
    const std::string& raw = natural[n];
    size_t start = 0;
    while (start < raw.size() && IsBlank(raw[start])) ++start;
    std::string part = raw.substr(start);
    if (!continuing) {
      if (part.empty() || part[0] == '#' || part[0] == '!') continue;
      lines.push_back({"", static_cast<int>(n) + 1});
    }
    size_t backslashes = 0;
    while (backslashes < part.size() && part[part.size() - 1 - backslashes] == '\\') ++backslashes;
    continuing = backslashes % 2 == 1;
    if (continuing) part.pop_back();
    lines.back().text += part;
  }
  return lines;
}

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// Resolves the escapes of text[begin, end).
std::string Unescape(const std::string& text, size_t begin, size_t end, const std::string& source, int line) {
  std::string out;
  uint32_t high_surrogate = 0;
  for (size_t i = begin; i < end; ++i) {
    if (text[i] != '\\' || i + 1 >= end) {
      out += text[i];
      continue;
    }
    const char c = text[++i];
    if (c != 'u') {
      out += c == 't' ? '\t' : c == 'n' ? '\n' : c == 'r' ? '\r' : c == 'f' ? '\f' : c;
      continue;
    }
    uint32_t code = 0;
    for (int k = 1; k <= 4; ++k) {
      const int digit = i + k < end ? HexValue(text[i + k]) : -1;
      SLAM_THROW_IF_NOT(InputError, digit >= 0) << source << ":" << line << ": malformed \\uXXXX escape";
      code = code * 16 + static_cast<uint32_t>(digit);
    }
    i += 4;
    if (code >= 0xD800 && code <= 0xDBFF) {
      high_surrogate = code;
      continue;
    }
    if (code >= 0xDC00 && code <= 0xDFFF && high_surrogate != 0) {
      code = 0x10000 + ((high_surrogate - 0xD800) << 10) + (code - 0xDC00);
    } else if (code >= 0xD800 && code <= 0xDFFF) {
      code = 0xFFFD;  // a lone low surrogate
    }
    high_surrogate = 0;
    AppendUtf8(code, &out);
  }
  return out;
}

}  // namespace

std::map<std::string, std::string> ParseJavaProperties(const std::string& text, const std::string& source) {
  const std::string utf8 = IsValidUtf8(text) ? text : Latin1ToUtf8(text);
  std::map<std::string, std::string> properties;
  for (const LogicalLine& logical : LogicalLines(utf8)) {
    const std::string& line = logical.text;
    size_t key_end = 0;
    bool escaped = false;
    while (key_end < line.size()) {
      const char c = line[key_end];
      if (!escaped && (c == '=' || c == ':' || IsBlank(c))) break;
      escaped = !escaped && c == '\\';
      ++key_end;
    }
    size_t value_begin = key_end;
    while (value_begin < line.size() && IsBlank(line[value_begin])) ++value_begin;
    if (value_begin < line.size() && (line[value_begin] == '=' || line[value_begin] == ':')) {
      ++value_begin;
      while (value_begin < line.size() && IsBlank(line[value_begin])) ++value_begin;
    }
    properties[Unescape(line, 0, key_end, source, logical.line)] =
        Unescape(line, value_begin, line.size(), source, logical.line);
  }
  return properties;
}

}  // namespace duskmap
