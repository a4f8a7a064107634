// JsonWriter: builds compact JSON text (objects, arrays, numbers, strings) for the JS API and the
// tools' --json output. Non-finite numbers are written as null (JSON has no NaN).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace qv {

class JsonWriter {
 public:
  JsonWriter& beginObject();
  JsonWriter& endObject();
  JsonWriter& beginArray();
  JsonWriter& endArray();
  /// Inside an object: the next value's key.
  JsonWriter& key(std::string_view name);
  JsonWriter& value(double number);
  /// Shortest text that reads back as the same float ("443.2", not "443.20001220703125").
  JsonWriter& value(float number);
  JsonWriter& value(std::int64_t number);
  JsonWriter& value(std::uint64_t number);
  JsonWriter& value(int number) { return value(static_cast<std::int64_t>(number)); }
  JsonWriter& value(unsigned number) { return value(static_cast<std::uint64_t>(number)); }
  JsonWriter& value(bool flag);
  JsonWriter& value(std::string_view text);
  JsonWriter& value(const char* text) { return value(std::string_view(text)); }
  JsonWriter& null();
  /// Puts the next value on a new line (after its separating comma), for readable large output.
  JsonWriter& breakLine() {
    breakLine_ = true;
    return *this;
  }
  /// Inserts already-serialized JSON as one value.
  JsonWriter& raw(std::string_view json);

  template <typename T>
  JsonWriter& field(std::string_view name, const T& v) {
    key(name);
    return value(v);
  }

  [[nodiscard]] const std::string& str() const { return out_; }
  std::string take() { return std::move(out_); }

  /// Appends `text` as a quoted, escaped JSON string.
  static void appendQuoted(std::string& out, std::string_view text);

 private:
  void separate();
  std::string out_;
  std::vector<bool> needComma_;  // one entry per open container
  bool afterKey_ = false;
  bool breakLine_ = false;
};

}  // namespace qv
