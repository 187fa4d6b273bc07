// Words and numbers of the text formats (PLY header, ASCII PLY, OBJ, ASCII STL), parsed in place:
// std::from_chars is locale-free and far faster than streams. A leading '+' is accepted.
#ifndef atpTextParsing_h
#define atpTextParsing_h

#include <charconv>
#include <cstdint>
#include <string_view>
#include <system_error>

namespace atp
{

/// The byte-order mark some editors put before a text's first word: not content.
constexpr std::string_view ByteOrderMark = "\xEF\xBB\xBF";

/// `text` without a byte-order mark at its start.
inline std::string_view WithoutByteOrderMark(std::string_view text)
{
  return text.substr(0, ByteOrderMark.size()) == ByteOrderMark ? text.substr(ByteOrderMark.size()) : text;
}

/// Removes and returns the first word of `text` (words are separated by spaces, tabs and
/// carriage returns); empty when there is none left.
inline std::string_view NextWord(std::string_view& text)
{
  auto isBlank = [](char c) { return c == ' ' || c == '\t' || c == '\r'; };
  std::size_t start = 0;
  while (start < text.size() && isBlank(text[start]))
  {
    ++start;
  }
  std::size_t end = start;
  while (end < text.size() && !isBlank(text[end]))
  {
    ++end;
  }
  std::string_view word = text.substr(start, end - start);
  text.remove_prefix(end);
  return word;
}

/// The whole token must be a number; "nan" and "inf" parse (callers reject non-finite values
/// where it matters, with a better message).
inline bool ParseReal(std::string_view token, double& value)
{
  if (!token.empty() && token[0] == '+')
  {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end && !token.empty();
}

/// Parses the integer at the start of `token`; returns the length parsed, 0 when none.
inline std::size_t ParseIntegerPrefix(std::string_view token, std::int64_t& value)
{
  std::size_t skip = !token.empty() && token[0] == '+' ? 1 : 0;
  const char* begin = token.data() + skip;
  auto result = std::from_chars(begin, token.data() + token.size(), value);
  return result.ec == std::errc() && result.ptr != begin
    ? static_cast<std::size_t>(result.ptr - token.data())
    : 0;
}

/// The whole token must be an integer.
inline bool ParseInteger(std::string_view token, std::int64_t& value)
{
  return !token.empty() && ParseIntegerPrefix(token, value) == token.size();
}

} // namespace atp

#endif
