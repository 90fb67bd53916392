// A check of raw text before an XML parser sees it (internal to the readers): the text must be
// UTF-8. tinyxml 2.6 takes the length of a multi-byte character from its first byte and steps
// over it without looking, so a lead byte near the end of the text makes it read past the
// buffer (found by fuzz/fuzz_srdf); urdfdom's tinyxml2 also reads its input as UTF-8.
#pragma once

#include <cstddef>
#include <string>

namespace dss {
namespace input_scan {

/// The first byte that does not belong to well-formed UTF-8 (RFC 3629: no overlong forms, no
/// surrogates, nothing above U+10FFFF, no truncated sequence); `found` false when there is none.
struct Utf8Error {
  bool found = false;
  std::size_t line = 0;    ///< 1-based
  std::size_t column = 0;  ///< 1-based, in bytes
  unsigned byte = 0;       ///< the offending byte
};

inline Utf8Error firstInvalidUtf8(const std::string& text) {
  std::size_t line = 1, line_start = 0;
  const std::size_t n = text.size();
  auto at = [&text](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  for (std::size_t i = 0; i < n;) {
    const unsigned c = at(i);
    std::size_t len = 0;
    unsigned lo = 0x80, hi = 0xBF;  // range of the second byte
    if (c < 0x80) {
      if (c == '\n') {
        ++line;
        line_start = i + 1;
      }
      ++i;
      continue;
    } else if (c >= 0xC2 && c <= 0xDF) {
      len = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      if (c == 0xE0) lo = 0xA0;  // overlong
      if (c == 0xED) hi = 0x9F;  // surrogates
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      if (c == 0xF0) lo = 0x90;  // overlong
      if (c == 0xF4) hi = 0x8F;  // above U+10FFFF
    }
    bool ok = len > 0 && i + len <= n;
    for (std::size_t k = 1; ok && k < len; ++k) {
      const unsigned b = at(i + k);
      ok = k == 1 ? (b >= lo && b <= hi) : (b >= 0x80 && b <= 0xBF);
    }
    if (!ok) return Utf8Error{true, line, i - line_start + 1, c};
    i += len;
  }
  return Utf8Error{};
}

/// "FILE:LINE:COLUMN: the text is not UTF-8 (byte 0xE1)" for an error found in `file`.
inline std::string utf8Message(const std::string& file, const Utf8Error& e) {
  static const char* const kHex = "0123456789ABCDEF";
  return file + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) +
         ": the text is not UTF-8 (byte 0x" + kHex[(e.byte >> 4) & 15] + kHex[e.byte & 15] +
         "); XML files are read as UTF-8";
}

}  // namespace input_scan
}  // namespace dss
