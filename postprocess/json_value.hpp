// A small JSON document model for the postprocessor's outputs (summary.json): ordered object
// keys (so summaries diff cleanly), numbers printed round-trip exact, non-finite -> null.
// Hand-written because no JSON library is among the project's dependencies.
#pragma once
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "common/json_quote.hpp"

namespace mppm::post {

class JsonValue {
 public:
  enum class Kind { null, boolean, number, string, array, object };

  JsonValue() = default;  // null
  JsonValue(std::nullptr_t) {}
  JsonValue(bool b) : kind_(Kind::boolean), boolean_(b) {}
  JsonValue(double v) : kind_(Kind::number), number_(v) {}
  JsonValue(int v) : kind_(Kind::number), number_(v), integer_(true) {}
  JsonValue(std::int64_t v) : kind_(Kind::number), number_(static_cast<double>(v)), integer_(true) {}
  JsonValue(std::uint64_t v) : kind_(Kind::number), number_(static_cast<double>(v)), integer_(true) {}
  JsonValue(const char* s) : kind_(Kind::string), string_(s) {}
  JsonValue(std::string s) : kind_(Kind::string), string_(std::move(s)) {}
  template <class T>
  JsonValue(const std::optional<T>& v) {
    if (v) *this = JsonValue(*v);
  }

  static JsonValue array() {
    JsonValue v;
    v.kind_ = Kind::array;
    return v;
  }
  static JsonValue object() {
    JsonValue v;
    v.kind_ = Kind::object;
    return v;
  }

  Kind kind() const { return kind_; }
  // Object: sets (or replaces) a key, keeping first-insertion order.
  JsonValue& set(const std::string& key, JsonValue value);
  // Array: appends.
  JsonValue& push(JsonValue value);

  void write(std::ostream& out, int indent = 0) const;
  std::string dump() const;

 private:
  Kind kind_ = Kind::null;
  bool boolean_ = false;
  double number_ = 0.0;
  bool integer_ = false;
  std::string string_;
  std::vector<JsonValue> items_;
  std::vector<std::pair<std::string, JsonValue>> members_;
};

// JSON string literal with escapes (common/json_quote.hpp).
using mppm::json_quote;

}  // namespace mppm::post
