// Physical quantities written as text ("0.5 mm", "8 MPa", "0.01 MPa*s") converted to SI,
// with the dimension checked. Hand-written: no Debian-packaged C++ library parses unit
// strings at run time (Boost.Units is compile-time only).
#pragma once
#include <array>
#include <string>
#include <string_view>

namespace mppm {

// Exponents of the SI base dimensions used here: length, mass, time, plus angle
// (kept apart so that "35 deg" is never accepted as a plain number by mistake... but an
// angle is dimensionless in SI, so a bare number is accepted where an angle is expected).
struct Dimension {
  std::array<int, 3> exponent{0, 0, 0};  // L, M, T
  bool is_angle = false;

  friend bool operator==(const Dimension&, const Dimension&) = default;
  std::string to_string() const;  // e.g. "kg m^-1 s^-2 (pressure)"
};

namespace dim {
inline constexpr Dimension none{};
inline constexpr Dimension length{{1, 0, 0}};
inline constexpr Dimension area{{2, 0, 0}};  // m^2 (intrinsic permeability)
inline constexpr Dimension mass{{0, 1, 0}};
inline constexpr Dimension time{{0, 0, 1}};
inline constexpr Dimension angle{{0, 0, 0}, true};
inline constexpr Dimension density{{-3, 1, 0}};
inline constexpr Dimension pressure{{-1, 1, -2}};        // Pa = N/m^2
inline constexpr Dimension force{{1, 1, -2}};            // N
inline constexpr Dimension velocity{{1, 0, -1}};         // m/s
inline constexpr Dimension acceleration{{1, 0, -2}};     // m/s^2
inline constexpr Dimension energy_per_area{{0, 1, -2}};  // N/m = J/m^2
inline constexpr Dimension viscosity{{-1, 1, -1}};       // Pa s
inline constexpr Dimension rate{{0, 0, -1}};             // 1/s (rotation rate)
}  // namespace dim

struct Quantity {
  double value = 0.0;  // SI
  Dimension dimension;
};

// Parses "8 MPa", "0.5mm", "1e-3", "0.01 MPa*s", "160 N/m", "2650 kg/m^3", "35 deg".
// Throws std::invalid_argument with a message saying what could not be read.
Quantity parse_quantity(std::string_view text);

// Parses and checks the dimension; a bare number is SI of the expected dimension.
// Throws std::invalid_argument naming the expected and the given unit.
double parse_quantity_as(std::string_view text, const Dimension& expected);

// Converts a length-unit name ("m", "mm", "cm", "um", "in", "ft") to metres.
double length_unit_in_metres(std::string_view unit);

}  // namespace mppm
