// Unit strings: conversion to SI and dimension checking (docs/scene.md "Quantities").
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/units.hpp"

using namespace mppm;

TEST(Units, ConvertsTheSceneExamplesToSI) {
  EXPECT_DOUBLE_EQ(parse_quantity_as("0.5 mm", dim::length), 0.5e-3);
  EXPECT_DOUBLE_EQ(parse_quantity_as("8 MPa", dim::pressure), 8e6);
  EXPECT_DOUBLE_EQ(parse_quantity_as("6.25 us", dim::time), 6.25e-6);
  EXPECT_DOUBLE_EQ(parse_quantity_as("0.05 m/s", dim::velocity), 0.05);
  EXPECT_DOUBLE_EQ(parse_quantity_as("160 N/m", dim::energy_per_area), 160.0);
  EXPECT_DOUBLE_EQ(parse_quantity_as("35 deg", dim::angle), 35.0 * std::numbers::pi / 180.0);
  EXPECT_DOUBLE_EQ(parse_quantity_as("83.3 N", dim::force), 83.3);
  EXPECT_DOUBLE_EQ(parse_quantity_as("56 kN", dim::force), 56e3);
  EXPECT_DOUBLE_EQ(parse_quantity_as("0.01 MPa*s", dim::viscosity), 1e4);
  EXPECT_DOUBLE_EQ(parse_quantity_as("14 GPa", dim::pressure), 14e9);
  EXPECT_DOUBLE_EQ(parse_quantity_as("2650 kg/m^3", dim::density), 2650.0);
  EXPECT_DOUBLE_EQ(parse_quantity_as("2650 kg/m3", dim::density), 2650.0);
  EXPECT_DOUBLE_EQ(parse_quantity_as("9.81 m/s^2", dim::acceleration), 9.81);
  EXPECT_DOUBLE_EQ(parse_quantity_as("2 1/s", dim::rate), 2.0);
  EXPECT_DOUBLE_EQ(parse_quantity_as("1 cm", dim::length), 0.01);
  EXPECT_DOUBLE_EQ(parse_quantity_as("25deg", dim::angle), 25.0 * std::numbers::pi / 180.0);
}

TEST(Units, BareNumbersAreSI) {
  EXPECT_DOUBLE_EQ(parse_quantity_as("2.5e-3", dim::length), 2.5e-3);
  EXPECT_DOUBLE_EQ(parse_quantity_as("14e9", dim::pressure), 14e9);
  EXPECT_DOUBLE_EQ(parse_quantity_as("4.05", dim::none), 4.05);
}

TEST(Units, WrongDimensionNamesBothUnits) {
  try {
    parse_quantity_as("8 mm", dim::pressure);
    FAIL() << "a length was accepted as a pressure";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("8 mm"), std::string::npos) << what;
    EXPECT_NE(what.find("length"), std::string::npos) << what;
    EXPECT_NE(what.find("pressure"), std::string::npos) << what;
  }
  // An angle where a plain number is expected is a slip, although angles are dimensionless.
  EXPECT_THROW(parse_quantity_as("35 deg", dim::none), std::invalid_argument);
  EXPECT_THROW(parse_quantity_as("83.3 kN", dim::pressure), std::invalid_argument);
}

TEST(Units, RejectsMalformedText) {
  for (const char* bad : {"", "mm", "abc", "1 furlong", "1 mm/", "1 *mm", "nan", "1e999 m", "1 cs"}) {
    EXPECT_THROW(parse_quantity(bad), std::invalid_argument) << bad;
  }
}

TEST(Units, LengthUnitNames) {
  EXPECT_DOUBLE_EQ(length_unit_in_metres("mm"), 1e-3);
  EXPECT_DOUBLE_EQ(length_unit_in_metres("m"), 1.0);
  EXPECT_DOUBLE_EQ(length_unit_in_metres("in"), 0.0254);
  EXPECT_THROW(length_unit_in_metres("s"), std::invalid_argument);
  EXPECT_THROW(length_unit_in_metres("parsec"), std::invalid_argument);
}
