#include <catch2/catch.hpp>

#include <string>

#include "qv/core/JsonWriter.h"
#include "qv/core/Text.h"

using namespace qv;

namespace {
const std::string kRlo = "\xE2\x80\xAE";  // U+202E RIGHT-TO-LEFT OVERRIDE
const std::string kPdf = "\xE2\x80\xAC";  // U+202C POP DIRECTIONAL FORMATTING
const std::string kLri = "\xE2\x81\xA6";  // U+2066 LEFT-TO-RIGHT ISOLATE
const std::string kRlm = "\xE2\x80\x8F";  // U+200F RIGHT-TO-LEFT MARK
const std::string kFffd = "\xEF\xBF\xBD";
}  // namespace

TEST_CASE("UTF-8: well-formed text is recognised and kept byte for byte", "[core][text]") {
  for (const std::string s :
       {"", "Empire State Building", "Cin\xC3\xA9polis", "Saint Patrick\xE2\x80\x99s Cathedral",
        "\xE6\x9D\xB1\xE4\xBA\xAC", "\xF0\x9F\x8F\xA5 hospital", "\xD7\xA9\xD7\x9C\xD7\x95\xD7\x9D"}) {
    CHECK(isValidUtf8(s));
    CHECK(toValidUtf8(s) == s);
  }
}

TEST_CASE("UTF-8: each maximal invalid subpart becomes one U+FFFD", "[core][text]") {
  CHECK_FALSE(
      isValidUtf8("a\x80"
                  "b"));
  CHECK(toValidUtf8("a\x80"
                    "b") == "a" + kFffd + "b");
  // A truncated 3-byte sequence is one subpart; the byte after it is kept.
  CHECK(toValidUtf8("\xE2\x80"
                    "x") == kFffd + "x");
  // Overlong encodings, surrogates and code points above U+10FFFF are refused.
  CHECK(toValidUtf8("\xC0\xAF") == kFffd + kFffd);
  CHECK(toValidUtf8("\xED\xA0\x80") == kFffd + kFffd + kFffd);
  CHECK(toValidUtf8("\xF4\x90\x80\x80") == kFffd + kFffd + kFffd + kFffd);
  CHECK(toValidUtf8("\xFF") == kFffd);
  // Truncated at the end of the text.
  CHECK(toValidUtf8("ok\xF0\x9F\x8F") == "ok" + kFffd);
  CHECK(isValidUtf8(toValidUtf8("\xC3\x28\xA0\xA1\xE2\x28\xA1\xF0\x28\x8C\xBC")));
}

TEST_CASE("Display text: bidirectional controls cannot reorder the line around a name", "[core][text]") {
  // "Exe" spelt backwards after an override would read as "...exe" on screen.
  const std::string name = "Invoice " + kRlo + "fdp.exe" + kPdf + " office";
  CHECK(needsDisplayCleaning(name));
  CHECK(displaySafe(name) == "Invoice fdp.exe office");
  CHECK(displaySafe(kLri + "5th Ave" + "\xE2\x81\xA9") == "5th Ave");
  CHECK(displaySafe("Main St" + kRlm) == "Main St");
  // Right-to-left letters themselves are kept: only the controls go.
  const std::string hebrew = "\xD7\xA9\xD7\x9C\xD7\x95\xD7\x9D";
  CHECK(displaySafe(hebrew) == hebrew);
  CHECK_FALSE(needsDisplayCleaning(hebrew));
}

TEST_CASE("Display text: line breaks become spaces and other controls stay visible", "[core][text]") {
  CHECK(displaySafe("First line\nSecond\r\nThird\tcolumn") == "First line Second  Third column");
  CHECK(displaySafe("Bell\x07here") == "Bell" + kFffd + "here");
  CHECK(displaySafe(std::string("nul\0in", 6)) == "nul" + kFffd + "in");
  CHECK(displaySafe("del\x7F") == "del" + kFffd);
  CHECK(displaySafe("c1\xC2\x85next\xC2\x9B") == "c1 next" + kFffd);        // NEL, CSI
  CHECK(displaySafe("para\xE2\x80\xA8graph") == "para graph");              // U+2028
  CHECK(displaySafe("broken \xE2\x80 utf") == "broken " + kFffd + " utf");  // invalid UTF-8
  CHECK(displaySafe("=HYPERLINK(\"x\")") == "=HYPERLINK(\"x\")");           // no business of the screen
  CHECK_FALSE(needsDisplayCleaning("Plain ASCII, 5th Avenue #3"));
}

TEST_CASE("JSON strings are valid UTF-8 whatever bytes a name holds", "[core][text][json]") {
  JsonWriter w;
  w.beginObject().field("name", std::string_view("bad \xFF byte")).endObject();
  const std::string json = w.take();
  CHECK(isValidUtf8(json));
  CHECK(json == "{\"name\":\"bad " + kFffd + " byte\"}");
}
