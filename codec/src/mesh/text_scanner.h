// Text scanning shared by the ASCII readers (PLY ascii, OBJ, OFF): lines with
// their numbers, whitespace-separated tokens and strict number parsing. All
// of it works on views of the input and never allocates.
#ifndef MESHWAVE_MESH_TEXT_SCANNER_H_
#define MESHWAVE_MESH_TEXT_SCANNER_H_

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <system_error>

#include "core/quoted.h"  // Quoted, for the readers' messages

namespace meshwave {

inline bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' ||
         c == '\f';
}

// Splits text into lines ('\n' or "\r\n"), numbering them from `first_line`.
class LineSplitter {
 public:
  explicit LineSplitter(std::string_view text, size_t first_line = 1)
      : text_(text), next_number_(first_line) {}

  // The next line without its terminator; false at the end of the text.
  bool Next(std::string_view* line) {
    if (position_ >= text_.size()) return false;
    size_t end = text_.find('\n', position_);
    size_t next = end == std::string_view::npos ? text_.size() : end + 1;
    if (end == std::string_view::npos) end = text_.size();
    std::string_view found = text_.substr(position_, end - position_);
    if (!found.empty() && found.back() == '\r') found.remove_suffix(1);
    *line = found;
    position_ = next;
    number_ = next_number_++;
    return true;
  }

  // 1-based number of the line last returned by Next().
  size_t number() const { return number_; }
  // Offset of the first byte after the line last returned.
  size_t position() const { return position_; }
  size_t remaining() const { return text_.size() - position_; }

 private:
  std::string_view text_;
  size_t position_ = 0;
  size_t number_ = 0;
  size_t next_number_;
};

// Splits one line into whitespace-separated tokens.
class TokenSplitter {
 public:
  explicit TokenSplitter(std::string_view line) : line_(line) {}

  bool Next(std::string_view* token) {
    while (position_ < line_.size() && IsSpace(line_[position_])) ++position_;
    if (position_ >= line_.size()) return false;
    size_t start = position_;
    while (position_ < line_.size() && !IsSpace(line_[position_])) ++position_;
    *token = line_.substr(start, position_ - start);
    return true;
  }

  // Whatever follows the last token returned, leading spaces removed.
  std::string_view Rest() {
    while (position_ < line_.size() && IsSpace(line_[position_])) ++position_;
    return line_.substr(position_);
  }

 private:
  std::string_view line_;
  size_t position_ = 0;
};

// The next line of an OBJ or MTL file with its comment (from '#') cut;
// false at the end of the text.
inline bool NextStatementLine(LineSplitter& lines, std::string_view* line) {
  if (!lines.Next(line)) return false;
  const size_t hash = line->find('#');
  if (hash != std::string_view::npos) *line = line->substr(0, hash);
  return true;
}

// Tokens across line breaks, remembering the line each token starts on
// (ASCII PLY records may in principle wrap).
class TokenCursor {
 public:
  TokenCursor(std::string_view text, size_t first_line)
      : text_(text), line_(first_line) {}

  bool Next(std::string_view* token) {
    while (position_ < text_.size() && IsSpace(text_[position_])) {
      if (text_[position_] == '\n') ++line_;
      ++position_;
    }
    if (position_ >= text_.size()) return false;
    size_t start = position_;
    while (position_ < text_.size() && !IsSpace(text_[position_])) ++position_;
    *token = text_.substr(start, position_ - start);
    return true;
  }

  // Line of the token last returned (or of the end, after a failed Next).
  size_t line() const { return line_; }
  size_t remaining() const { return text_.size() - position_; }

 private:
  std::string_view text_;
  size_t position_ = 0;
  size_t line_;
};

// Parses a whole token as a double (a leading '+' is allowed). Accepts "inf"
// and "nan" spellings; callers reject non-finite values with their own
// message.
inline bool ParseDouble(std::string_view token, double* out) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

// Parses a whole token as a decimal integer (a leading '+' is allowed).
inline bool ParseInt64(std::string_view token, int64_t* out) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

inline bool ParseUint64(std::string_view token, uint64_t* out) {
  if (token.size() > 1 && token[0] == '+') token.remove_prefix(1);
  const char* end = token.data() + token.size();
  auto [ptr, ec] = std::from_chars(token.data(), end, *out);
  return ec == std::errc() && ptr == end;
}

}  // namespace meshwave

#endif  // MESHWAVE_MESH_TEXT_SCANNER_H_
