// JSON serialization: two-space indentation, arrays of scalars on one line.
#include "postprocess/json_value.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace mppm::post {

JsonValue& JsonValue::set(const std::string& key, JsonValue value) {
  kind_ = Kind::object;
  for (auto& member : members_)
    if (member.first == key) {
      member.second = std::move(value);
      return member.second;
    }
  members_.emplace_back(key, std::move(value));
  return members_.back().second;
}

JsonValue& JsonValue::push(JsonValue value) {
  kind_ = Kind::array;
  items_.push_back(std::move(value));
  return items_.back();
}

void JsonValue::write(std::ostream& out, int indent) const {
  const std::string pad(static_cast<std::size_t>(indent + 2), ' ');
  switch (kind_) {
    case Kind::null:
      out << "null";
      break;
    case Kind::boolean:
      out << (boolean_ ? "true" : "false");
      break;
    case Kind::number: {
      if (!std::isfinite(number_)) {
        out << "null";
      } else if (integer_) {
        out << static_cast<long long>(number_);
      } else {
        char buffer[32];
        std::snprintf(buffer, sizeof buffer, "%.17g", number_);
        // Shortest representation that reads back to the same double.
        for (int precision = 6; precision < 17; ++precision) {
          char shorter[32];
          std::snprintf(shorter, sizeof shorter, "%.*g", precision, number_);
          if (std::strtod(shorter, nullptr) == number_) {
            std::snprintf(buffer, sizeof buffer, "%s", shorter);
            break;
          }
        }
        out << buffer;
      }
      break;
    }
    case Kind::string:
      out << json_quote(string_);
      break;
    case Kind::array: {
      bool scalars = true;
      for (const auto& item : items_)
        if (item.kind_ == Kind::array || item.kind_ == Kind::object) scalars = false;
      if (items_.empty()) {
        out << "[]";
      } else if (scalars) {
        out << "[";
        for (std::size_t i = 0; i < items_.size(); ++i) {
          if (i) out << ", ";
          items_[i].write(out, indent);
        }
        out << "]";
      } else {
        out << "[\n";
        for (std::size_t i = 0; i < items_.size(); ++i) {
          out << pad;
          items_[i].write(out, indent + 2);
          out << (i + 1 < items_.size() ? ",\n" : "\n");
        }
        out << std::string(static_cast<std::size_t>(indent), ' ') << "]";
      }
      break;
    }
    case Kind::object: {
      if (members_.empty()) {
        out << "{}";
        break;
      }
      out << "{\n";
      for (std::size_t i = 0; i < members_.size(); ++i) {
        out << pad << json_quote(members_[i].first) << ": ";
        members_[i].second.write(out, indent + 2);
        out << (i + 1 < members_.size() ? ",\n" : "\n");
      }
      out << std::string(static_cast<std::size_t>(indent), ' ') << "}";
      break;
    }
  }
}

std::string JsonValue::dump() const {
  std::ostringstream out;
  write(out);
  out << "\n";
  return out.str();
}

}  // namespace mppm::post
