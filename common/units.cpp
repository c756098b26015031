// Unit-string parsing: "<number> [unit expression]" where the expression multiplies ('*', ' ')
// and divides ('/') unit tokens with optional integer powers ("kg/m^3", "kg/m3", "MPa*s").
#include "common/units.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mppm {
namespace {

struct UnitDef {
  std::string_view name;
  double factor;
  Dimension dimension;
  bool prefixable;
};

// Base units; `prefixable` ones take the SI prefixes below.
constexpr UnitDef kUnits[] = {
    {"m", 1.0, dim::length, true},
    {"g", 1e-3, dim::mass, true},
    {"s", 1.0, dim::time, true},
    {"N", 1.0, dim::force, true},
    {"Pa", 1.0, dim::pressure, true},
    {"J", 1.0, {{2, 1, -2}}, true},
    {"W", 1.0, {{2, 1, -3}}, true},
    {"Hz", 1.0, dim::rate, true},
    {"bar", 1e5, dim::pressure, false},
    {"rad", 1.0, dim::angle, false},
    {"deg", std::numbers::pi / 180.0, dim::angle, false},
    {"in", 0.0254, dim::length, false},
    {"ft", 0.3048, dim::length, false},
    {"min", 60.0, dim::time, false},
    {"h", 3600.0, dim::time, false},
};

struct Prefix {
  std::string_view symbol;
  double factor;
};
constexpr Prefix kPrefixes[] = {
    {"G", 1e9}, {"M", 1e6}, {"k", 1e3}, {"c", 1e-2}, {"m", 1e-3}, {"u", 1e-6}, {"\xC2\xB5", 1e-6} /* µ */, {"n", 1e-9}};

struct Scaled {
  double factor = 1.0;
  Dimension dimension;
};

Scaled combine(const Scaled& a, const Scaled& b, int power) {
  Scaled r = a;
  r.factor *= std::pow(b.factor, power);
  for (int k = 0; k < 3; ++k) r.dimension.exponent[k] += power * b.dimension.exponent[k];
  r.dimension.is_angle = a.dimension.is_angle || b.dimension.is_angle;
  return r;
}

bool lookup_token(std::string_view token, Scaled& out) {
  for (const auto& u : kUnits) {
    if (token == u.name) {
      out = {u.factor, u.dimension};
      return true;
    }
  }
  for (const auto& p : kPrefixes) {
    if (token.size() > p.symbol.size() && token.substr(0, p.symbol.size()) == p.symbol) {
      const auto rest = token.substr(p.symbol.size());
      for (const auto& u : kUnits) {
        // "c" is accepted only for centimetres: "cs" or "cN" are almost certainly typos.
        if (u.prefixable && rest == u.name && (p.symbol != "c" || u.name == "m")) {
          out = {p.factor * u.factor, u.dimension};
          return true;
        }
      }
    }
  }
  return false;
}

bool is_unit_char(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || static_cast<unsigned char>(c) >= 0x80;
}

Scaled parse_unit_expression(std::string_view text, std::string_view whole) {
  Scaled result;
  std::size_t pos = 0;
  int sign = +1;  // +1 multiply, -1 divide (applies to the next token only)
  bool expect_token = true;
  while (pos < text.size()) {
    const char c = text[pos];
    if (c == ' ' || c == '\t') {
      ++pos;
      continue;
    }
    if (c == '*' || c == '/') {
      if (expect_token)
        throw std::invalid_argument("misplaced '" + std::string(1, c) + "' in \"" + std::string(whole) + "\"");
      sign = c == '/' ? -1 : +1;
      expect_token = true;
      ++pos;
      continue;
    }
    if (c == '1' && expect_token && sign == +1 && pos + 1 < text.size() && text[pos + 1] == '/') {
      ++pos;  // "1/s"
      expect_token = false;
      continue;
    }
    if (!is_unit_char(c)) {
      throw std::invalid_argument("cannot read the unit of \"" + std::string(whole) + "\" at '" +
                                  std::string(text.substr(pos)) + "'");
    }
    std::size_t end = pos;
    while (end < text.size() && is_unit_char(text[end])) ++end;
    const auto token = text.substr(pos, end - pos);
    Scaled unit;
    if (!lookup_token(token, unit)) {
      throw std::invalid_argument("unknown unit '" + std::string(token) + "' in \"" + std::string(whole) +
                                  "\" (known: m, g, s, N, Pa, J, W, Hz with prefixes G M k m u n, "
                                  "and cm, bar, rad, deg, in, ft, min, h)");
    }
    pos = end;
    int power = 1;
    if (pos < text.size() &&
        (text[pos] == '^' || std::isdigit(static_cast<unsigned char>(text[pos])) || text[pos] == '-')) {
      if (text[pos] == '^') ++pos;
      int value = 0;
      const auto [ptr, ec] = std::from_chars(text.data() + pos, text.data() + text.size(), value);
      // Bounded so that summing exponents cannot overflow an int (undefined behaviour).
      if (ec != std::errc() || value < -99 || value > 99) {
        throw std::invalid_argument("bad power in \"" + std::string(whole) +
                                    "\" (expected a small integer, e.g. m^3 or s^-2)");
      }
      pos = static_cast<std::size_t>(ptr - text.data());
      power = value;
    }
    result = combine(result, unit, sign * power);
    sign = +1;
    expect_token = false;
  }
  if (expect_token && !text.empty())
    throw std::invalid_argument("unit expression ends early in \"" + std::string(whole) + "\"");
  return result;
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

const char* dimension_name(const Dimension& d) {
  struct Named {
    Dimension d;
    const char* name;
  };
  static const Named names[] = {
      {dim::none, "a plain number"},
      {dim::length, "a length (e.g. m, mm)"},
      {dim::area, "an area (e.g. m^2, mm^2)"},
      {dim::mass, "a mass (e.g. kg)"},
      {dim::time, "a time (e.g. s, us)"},
      {dim::angle, "an angle (e.g. deg, rad)"},
      {dim::density, "a density (e.g. kg/m^3)"},
      {dim::pressure, "a pressure or stress (e.g. Pa, MPa)"},
      {dim::force, "a force (e.g. N, kN)"},
      {dim::velocity, "a velocity (e.g. m/s)"},
      {dim::acceleration, "an acceleration (e.g. m/s^2)"},
      {dim::energy_per_area, "an energy per area or force per length (e.g. N/m, J/m^2)"},
      {dim::viscosity, "a viscosity (e.g. Pa*s, MPa*s)"},
      {dim::rate, "a rate (e.g. 1/s, rad/s)"},
      {{{2, 1, -2}}, "an energy (e.g. J)"},
  };
  for (const auto& n : names) {
    if (n.d.exponent == d.exponent && (n.d.is_angle == d.is_angle || n.d.exponent != std::array<int, 3>{0, 0, 0}))
      return n.name;
  }
  return nullptr;
}

}  // namespace

std::string Dimension::to_string() const {
  if (const char* name = dimension_name(*this)) return name;
  std::ostringstream out;
  const char* base[] = {"m", "kg", "s"};
  bool first = true;
  for (int k = 0; k < 3; ++k) {
    if (exponent[k] == 0) continue;
    if (!first) out << ' ';
    out << base[k];
    if (exponent[k] != 1) out << '^' << exponent[k];
    first = false;
  }
  return "a quantity in " + out.str();
}

Quantity parse_quantity(std::string_view text_in) {
  const auto text = trim(text_in);
  if (text.empty()) throw std::invalid_argument("empty value (expected a number with an optional unit)");
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc()) {
    throw std::invalid_argument("\"" + std::string(text) + "\" is not a number (expected e.g. \"0.5 mm\" or 2.5e-3)");
  }
  if (!std::isfinite(value)) throw std::invalid_argument("\"" + std::string(text) + "\" is not a finite number");
  const auto unit_text = text.substr(static_cast<std::size_t>(ptr - text.data()));
  const Scaled unit = parse_unit_expression(trim(unit_text), text);
  // A finite number times a unit power can still overflow ("1e300 GPa") or be 0 * inf.
  if (!std::isfinite(value * unit.factor)) {
    throw std::invalid_argument("\"" + std::string(text) + "\" is out of range (not a finite number in SI units)");
  }
  return {value * unit.factor, unit.dimension};
}

double parse_quantity_as(std::string_view text, const Dimension& expected) {
  const Quantity q = parse_quantity(text);
  // A bare number is SI of whatever dimension is expected (docs/scene.md "Quantities").
  const auto t = trim(text);
  double ignored = 0.0;
  if (const auto r = std::from_chars(t.data(), t.data() + t.size(), ignored); r.ptr == t.data() + t.size())
    return q.value;
  const bool exponents_match = q.dimension.exponent == expected.exponent;
  // Angles are dimensionless in SI, but an angle unit where no angle is expected is a slip.
  const bool angle_ok = !q.dimension.is_angle || expected.is_angle;
  if (!exponents_match || !angle_ok) {
    throw std::invalid_argument("\"" + std::string(trim(text)) + "\" is " + q.dimension.to_string() + ", expected " +
                                expected.to_string());
  }
  return q.value;
}

double length_unit_in_metres(std::string_view unit) {
  const auto name = trim(unit);
  Scaled s;
  if (!lookup_token(name, s) || s.dimension != dim::length) {
    throw std::invalid_argument("\"" + std::string(name) +
                                "\" is not a length unit (expected m, mm, cm, um, in or ft)");
  }
  return s.factor;
}

}  // namespace mppm
