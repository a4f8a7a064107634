#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "qv/core/JsonWriter.h"

using qv::JsonWriter;

TEST_CASE("JsonWriter nests objects and arrays with commas in the right places", "[core][json]") {
  JsonWriter w;
  w.beginObject();
  w.field("a", 1).field("b", "two");
  w.key("c").beginArray().value(1.5).value(true).null().endArray();
  w.key("d").beginObject().endObject();
  w.endObject();
  CHECK(w.str() == R"({"a":1,"b":"two","c":[1.5,true,null],"d":{}})");
}

TEST_CASE("JsonWriter escapes strings", "[core][json]") {
  JsonWriter w;
  w.value(std::string_view("quote\" backslash\\ newline\n tab\t ctrl\x01"));
  CHECK(w.str() == R"("quote\" backslash\\ newline\n tab\t ctrl\u0001")");
}

TEST_CASE("JsonWriter writes non-finite numbers as null and doubles that round-trip", "[core][json]") {
  JsonWriter w;
  w.beginArray();
  w.value(std::numeric_limits<double>::quiet_NaN());
  w.value(std::numeric_limits<double>::infinity());
  w.value(0.1);
  w.value(443.2);
  w.value(1.0 / 3.0);
  w.endArray();
  CHECK(w.str().rfind("[null,null,0.1,443.2,", 0) == 0);
  const std::string third = w.str().substr(w.str().rfind(',') + 1);
  CHECK(std::strtod(third.c_str(), nullptr) == 1.0 / 3.0);
}
