// Cheap pre-scans of raw text that bound its nesting depth before a recursive parser sees it
// (internal to the readers). tinyxml, tinyxml2 (inside urdfdom) and nlohmann::json's dump()
// recurse once per nesting level, so a file with 100 000 nested elements or arrays would
// exhaust the stack; these scans walk the text once, without recursion, and report the first
// place where the nesting passes a limit.
//
// The scans never count fewer levels than the parsers: comments, CDATA sections and quoted
// attribute values (XML) and strings (JSON) are skipped as the parsers skip them, a
// declaration or DOCTYPE ends at its first '>' (as in tinyxml), and every other opening tag or
// bracket counts. Malformed text is left to the parser to report.
#pragma once

#include <cstddef>
#include <string>

namespace dss {
namespace input_scan {

/// Where the nesting first went past the limit; `exceeded` false when it never did.
struct NestingExcess {
  bool exceeded = false;
  std::size_t line = 0;    ///< 1-based
  std::size_t column = 0;  ///< 1-based, in bytes
};

namespace detail {

// Position bookkeeping shared by the scans.
struct Cursor {
  const std::string& text;
  std::size_t pos = 0;
  std::size_t line = 1;
  std::size_t line_start = 0;

  bool done() const { return pos >= text.size(); }
  bool startsWith(const char* s) const {
    return text.compare(pos, std::char_traits<char>::length(s), s) == 0;
  }
  void advance() {
    if (text[pos] == '\n') {
      ++line;
      line_start = pos + 1;
    }
    ++pos;
  }
  // Moves past the next occurrence of `end` (or to the end of the text).
  void skipPast(const char* end) {
    const std::size_t n = std::char_traits<char>::length(end);
    while (!done() && !startsWith(end)) advance();
    for (std::size_t i = 0; i < n && !done(); ++i) advance();
  }
  NestingExcess here() const { return {true, line, pos - line_start + 1}; }
};

}  // namespace detail

/// Element nesting of an XML document: the root element is at depth 1, its children (empty
/// or not) at depth 2, and so on.
inline NestingExcess xmlNesting(const std::string& text, std::size_t max_depth) {
  detail::Cursor c{text};
  std::size_t depth = 0;
  while (!c.done()) {
    if (text[c.pos] != '<') {
      c.advance();
      continue;
    }
    if (c.startsWith("<!--")) {
      c.skipPast("-->");
    } else if (c.startsWith("<![CDATA[")) {
      c.skipPast("]]>");
    } else if (c.startsWith("<?") || c.startsWith("<!")) {
      // A declaration, processing instruction or DOCTYPE: tinyxml ends it at the first '>'
      // (tinyxml2 reads a declaration to "?>"; stopping earlier only counts more).
      c.skipPast(">");
    } else if (c.startsWith("</")) {
      if (depth > 0) --depth;
      c.skipPast(">");
    } else {
      // A start tag: to its '>' outside quoted attribute values; "/>" closes it at once.
      const detail::Cursor open = c;
      char quote = 0;
      char last = 0;
      c.advance();
      while (!c.done()) {
        const char ch = text[c.pos];
        if (quote) {
          if (ch == quote) quote = 0;
        } else if (ch == '"' || ch == '\'') {
          quote = ch;
        } else if (ch == '>') {
          break;
        }
        if (ch != ' ' && ch != '\t' && ch != '\r' && ch != '\n') last = ch;
        c.advance();
      }
      if (!c.done()) c.advance();
      // An empty element sits one level below its parent too, but opens nothing.
      if (depth + 1 > max_depth) return open.here();
      if (last != '/') ++depth;
    }
  }
  return {};
}

/// Array and object nesting of JSON text (a top-level array or object is depth 1).
inline NestingExcess jsonNesting(const std::string& text, std::size_t max_depth) {
  detail::Cursor c{text};
  std::size_t depth = 0;
  bool in_string = false;
  while (!c.done()) {
    const char ch = text[c.pos];
    if (in_string) {
      if (ch == '\\')
        c.advance();  // the escaped character cannot end the string
      else if (ch == '"')
        in_string = false;
    } else if (ch == '"') {
      in_string = true;
    } else if (ch == '[' || ch == '{') {
      if (++depth > max_depth) return c.here();
    } else if ((ch == ']' || ch == '}') && depth > 0) {
      --depth;
    }
    if (!c.done()) c.advance();
  }
  return {};
}

}  // namespace input_scan
}  // namespace dss
