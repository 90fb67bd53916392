// XML text must be UTF-8 before tinyxml reads it: tinyxml 2.6 steps over a multi-byte
// character by the length its first byte announces, so a lead byte at the end of a file made
// it read past the buffer (AddressSanitizer: heap-buffer-overflow; found by fuzz/fuzz_srdf).
// The scan (src/common/utf8_scan.h) against a byte-by-byte decoder of RFC 3629, and the
// readers' errors with the file, line and column.
#include <boost/test/unit_test.hpp>
#include <random>
#include <stdexcept>
#include <string>

#include "../../src/common/utf8_scan.h"
#include "dss/robot/srdf.h"
#include "dss/robot/urdf_loader.h"
#include "support/thrown_message.h"

namespace {

// Reference: decode every code point and check it against RFC 3629's ranges.
bool validUtf8(const std::string& s) {
  for (std::size_t i = 0; i < s.size();) {
    const unsigned c = static_cast<unsigned char>(s[i]);
    std::size_t len = c < 0x80         ? 1
                      : (c >> 5) == 6  ? 2
                      : (c >> 4) == 14 ? 3
                      : (c >> 3) == 30 ? 4
                                       : 0;
    if (len == 0 || i + len > s.size()) return false;
    unsigned cp = len == 1 ? c : len == 2 ? (c & 0x1F) : len == 3 ? (c & 0x0F) : (c & 0x07);
    for (std::size_t k = 1; k < len; ++k) {
      const unsigned b = static_cast<unsigned char>(s[i + k]);
      if ((b >> 6) != 2) return false;
      cp = (cp << 6) | (b & 0x3F);
    }
    const unsigned least[] = {0, 0, 0x80, 0x800, 0x10000};
    if (cp < least[len] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
    i += len;
  }
  return true;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(xml_utf8)

BOOST_AUTO_TEST_CASE(the_scan_agrees_with_a_decoder) {
  std::mt19937_64 rng(29);
  // Short strings over bytes that matter (ASCII, continuation, every lead byte range, the
  // edges of the overlong, surrogate and U+10FFFF ranges).
  const unsigned char bytes[] = {'a',  '\n', 0x7F, 0x80, 0x8F, 0x90, 0x9F, 0xA0, 0xBF,
                                 0xC0, 0xC1, 0xC2, 0xDF, 0xE0, 0xE1, 0xEC, 0xED, 0xEE,
                                 0xEF, 0xF0, 0xF1, 0xF3, 0xF4, 0xF5, 0xFF};
  std::uniform_int_distribution<int> pick(0, sizeof bytes - 1), length(0, 6);
  int valid = 0;
  for (int n = 0; n < 200000; ++n) {
    std::string s;
    for (int k = length(rng); k > 0; --k) s += static_cast<char>(bytes[pick(rng)]);
    const bool expected = validUtf8(s);
    valid += expected;
    BOOST_TEST_REQUIRE(!dss::input_scan::firstInvalidUtf8(s).found == expected);
  }
  BOOST_TEST(valid > 1000);
  // Every code point's encoding is valid; truncated, it is not.
  for (unsigned cp :
       {0x7Fu, 0x80u, 0x7FFu, 0x800u, 0xD7FFu, 0xE000u, 0xFFFFu, 0x10000u, 0x10FFFFu}) {
    std::string s;
    if (cp < 0x80) {
      s += char(cp);
    } else if (cp < 0x800) {
      s += char(0xC0 | cp >> 6), s += char(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      s += char(0xE0 | cp >> 12), s += char(0x80 | ((cp >> 6) & 0x3F)),
          s += char(0x80 | (cp & 0x3F));
    } else {
      s += char(0xF0 | cp >> 18), s += char(0x80 | ((cp >> 12) & 0x3F));
      s += char(0x80 | ((cp >> 6) & 0x3F)), s += char(0x80 | (cp & 0x3F));
    }
    BOOST_TEST(!dss::input_scan::firstInvalidUtf8(s).found, std::hex << cp);
    if (s.size() > 1)
      BOOST_TEST(dss::input_scan::firstInvalidUtf8(s.substr(0, s.size() - 1)).found);
  }
}

BOOST_AUTO_TEST_CASE(readers_refuse_text_that_is_not_utf8) {
  // The reproducer's shape: a lead byte of a three-byte character at the very end.
  const std::string srdf =
      "<?xml version=\"1.0\"?>\n<robot name=\"r\">\n  <group name=\"g\"/> <\xE1";
  BOOST_TEST(dss_test::thrownMessage([&] { dss::parseSrdf(srdf, "bad.srdf"); }) ==
             "bad.srdf:3:22: the text is not UTF-8 (byte 0xE1); XML files are read as UTF-8");
  const std::string urdf =
      "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"caf\xE9\"/></robot>\n";
  BOOST_TEST(dss_test::thrownMessage([&] { dss::loadUrdfString(urdf, "latin1.urdf", "."); }) ==
             "latin1.urdf:2:32: the text is not UTF-8 (byte 0xE9); XML files are read as UTF-8");
  // The same name in UTF-8 is read.
  const std::string utf8 =
      "<?xml version=\"1.0\"?>\n<robot name=\"r\"><link name=\"caf\xC3\xA9\"/></robot>\n";
  BOOST_TEST(dss::loadUrdfString(utf8, "utf8.urdf", ".").links.size() == 1u);
}

BOOST_AUTO_TEST_SUITE_END()
