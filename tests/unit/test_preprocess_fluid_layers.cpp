// The pore fluid's boundaries in the points file (docs/stages.md "Boundaries", docs/theory.md
// section 12): a drained (pore_pressure) boundary gets a layer outside the body as deep as the
// horizon, like a kinematic one, but only where no kinematic layer is (the mechanical layers and
// the body are those of the scene without it); a drained boundary selected like a kinematic one
// shares that layer (point_count 0, no extra points); a fluid flux tags body points like a
// traction, on the points no traction or pressure loads, or shares the loaded points of one
// selected the same way; competing selections are refused with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "common/input_error.hpp"
#include "test_preprocess_support.hpp"

using namespace mppm;
using mppm::test::count_region;
using mppm::test::scenes_dir;

namespace {

constexpr double kDx = 1e-3, kL = 0.1, kH = 0.04, kFactor = 3.05;
constexpr double kHorizon = kFactor * kDx;

// The crack-branching plate (100 x 40 mm, groups top, left, bottom, right) saturated, with the
// given conditions (YAML list items, one per line, indented by two spaces).
Scene fluid_plate(const std::string& conditions) {
  const std::string text =
      "mppm: 1\nname: fluid-layers\ndimension: 2\nthickness: 1 mm\n"
      "geometry:\n  file: ../../../geometry/branching_plate.geo\n  unit: m\n"
      "  spacing: 1 mm\n  horizon_factor: " +
      std::to_string(kFactor) +
      "\nmaterial:\n  density: 2650\n  solid_fraction: 0.65\n  lambda: 14 GPa\n  mu: 14 GPa\n"
      "  pore_fluid: {permeability: 1e-12 m^2, fluid_viscosity: 1 mPa*s, biot_modulus: 2 GPa}\n"
      "effects: [pore_fluid]\nboundary_conditions:\n" +
      conditions + "time: {end: 1 us, step: 0.025 us}\n";
  return parse_scene(text, scenes_dir() + "/fluid_layers_test.yaml");
}

const std::string kBottomFixed = "  - {boundary: bottom, type: velocity, value: [0, 0]}\n";
const std::string kTopLoaded = "  - {boundary: top, type: traction, value: [0, -1 MPa]}\n";
const std::string kTopDrained = "  - {boundary: top, type: pore_pressure, value: 0 Pa}\n";

std::string error_of(const Scene& scene) {
  try {
    pre::preprocess(scene);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

double distance_to_segment(double px, double py, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay;
  const double t = std::clamp(((px - ax) * ux + (py - ay) * uy) / (ux * ux + uy * uy), 0.0, 1.0);
  return std::hypot(px - ax - t * ux, py - ay - t * uy);
}

// The points of the cloud with a region / boundary id, by lattice cell.
std::map<std::pair<long, long>, int> cells(const PointCloud& c, bool by_region) {
  std::map<std::pair<long, long>, int> out;
  for (std::size_t p = 0; p < c.size(); ++p) {
    const int tag = by_region ? c.region[p] : (c.region[p] == 0 ? c.boundary_id[p] : 0);
    if (tag != 0) out[{std::lround(c.x[p] / kDx - 0.5), std::lround(c.y[p] / kDx - 0.5)}] = tag;
  }
  return out;
}

}  // namespace

// A consolidation plate: fixed on the bottom, loaded and drained on top.
TEST(PreprocessFluidLayers, DrainedLayerLiesOutsideAndLeavesTheMechanicalPointsAsTheyWere) {
  const PointCloud dry = pre::preprocess(fluid_plate(kBottomFixed + kTopLoaded)).cloud;
  const PointCloud wet = pre::preprocess(fluid_plate(kBottomFixed + kTopLoaded + kTopDrained)).cloud;
  ASSERT_EQ(wet.boundaries.size(), 3u);
  EXPECT_EQ(wet.boundaries[2].type, "pore_pressure");
  EXPECT_EQ(wet.boundaries[2].name, "top_pore_pressure");
  EXPECT_DOUBLE_EQ(wet.boundaries[2].depth, kHorizon);
  EXPECT_DOUBLE_EQ(wet.boundaries[2].area, kL * 1e-3);  // length x thickness
  // The body (in order), the kinematic layer and the loaded points are those of the dry scene.
  EXPECT_EQ(count_region(wet, 0), count_region(dry, 0));
  const auto n = static_cast<std::size_t>(count_region(dry, 0));
  ASSERT_EQ(count_region(dry, 0), 100 * 40);
  for (std::size_t p = 0; p < n; ++p) {
    ASSERT_EQ(wet.x[p], dry.x[p]);
    ASSERT_EQ(wet.y[p], dry.y[p]);
    ASSERT_EQ(wet.boundary_id[p], dry.boundary_id[p]);
  }
  auto wet_regions = cells(wet, true);
  auto dry_regions = cells(dry, true);
  std::map<std::pair<long, long>, int> drained;
  for (const auto& [cell, region] : wet_regions)
    if (region == 3) drained[cell] = region;
  for (const auto& [cell, region] : drained) wet_regions.erase(cell);
  EXPECT_EQ(wet_regions, dry_regions);
  EXPECT_EQ(cells(wet, false), cells(dry, false));
  // The drained layer: every lattice point outside the plate within the horizon of the top edge,
  // not nearer to another edge (it does not wrap around the corners).
  std::map<std::pair<long, long>, int> expected;
  for (long i = -8; i < 108; ++i)
    for (long j = -8; j < 48; ++j) {
      const double x = (i + 0.5) * kDx, y = (j + 0.5) * kDx;
      if (x > 0 && x < kL && y > 0 && y < kH) continue;
      const double top = distance_to_segment(x, y, 0, kH, kL, kH);
      const double others = std::min({distance_to_segment(x, y, 0, 0, 0, kH), distance_to_segment(x, y, 0, 0, kL, 0),
                                      distance_to_segment(x, y, kL, 0, kL, kH)});
      if (top <= kHorizon + 1e-9 * kDx && others >= top - 1e-9 * kDx) expected[{i, j}] = 3;
    }
  EXPECT_EQ(drained, expected);
  EXPECT_EQ(wet.boundaries[2].point_count, static_cast<std::int64_t>(expected.size()));
}

// A porous platen: the top moves and is drained. The layer is the kinematic one; no point is added.
TEST(PreprocessFluidLayers, DrainedKinematicBoundarySharesItsLayer) {
  const std::string platen = "  - {boundary: top, type: velocity, value: [0, -1 m/s]}\n";
  const PointCloud dry = pre::preprocess(fluid_plate(kBottomFixed + platen)).cloud;
  const PointCloud wet = pre::preprocess(fluid_plate(kBottomFixed + kTopDrained + platen)).cloud;
  ASSERT_EQ(wet.boundaries.size(), 3u);
  EXPECT_EQ(wet.size(), dry.size());
  EXPECT_EQ(wet.boundaries[1].point_count, 0);
  EXPECT_EQ(wet.boundaries[1].selector, wet.boundaries[2].selector);
  EXPECT_EQ(shared_boundary(wet.boundaries, 1), std::optional<std::size_t>(2));
  EXPECT_EQ(shared_boundary(wet.boundaries, 2), std::nullopt);  // not a fluid boundary
  EXPECT_EQ(count_region(wet, 2), 0);
  EXPECT_EQ(count_region(wet, 3), count_region(dry, 2));
  // The report says where the drained condition's points are.
  const Scene scene = fluid_plate(kBottomFixed + kTopDrained + platen);
  const std::string report = pre::format_report(scene, pre::preprocess(scene), "");
  EXPECT_NE(report.find("pore_pressure: the layer of [3]"), std::string::npos) << report;
}

// An inflow through the left edge: body points within its depth, except those a traction loads
// (the corner point nearer to nothing else goes to the traction: the mechanics keep their points).
TEST(PreprocessFluidLayers, FluxTagsFreeBodyPointsOrSharesALoadedBoundary) {
  const std::string feed = "  - {boundary: left, type: fluid_flux, value: 1e-6 m/s, depth: 2 mm}\n";
  const std::string left_loaded = "  - {boundary: left, type: pressure, value: 1 MPa, depth: 2 mm}\n";
  const PointCloud cloud = pre::preprocess(fluid_plate(kBottomFixed + kTopLoaded + feed)).cloud;
  const auto tags = cells(cloud, false);
  long fed = 0;
  for (const auto& [cell, id] : tags) {
    if (id != 3) continue;
    ++fed;
    EXPECT_LT(cell.first, 2) << "fed point deeper than 2 mm";
    EXPECT_LT(cell.second, 39) << "a point of the top traction";
  }
  // Two columns of 40, less the top one of each (the traction's, whose depth dx reaches row 39 only).
  EXPECT_EQ(fed, 2 * 39);
  EXPECT_EQ(cloud.boundaries[2].point_count, fed);
  EXPECT_EQ(cloud.boundaries[2].type, "fluid_flux");
  // A fed boundary that is also loaded takes the loaded points.
  const PointCloud shared = pre::preprocess(fluid_plate(kBottomFixed + left_loaded + feed)).cloud;
  EXPECT_EQ(shared.boundaries[2].point_count, 0);
  EXPECT_EQ(shared_boundary(shared.boundaries, 2), std::optional<std::size_t>(1));
}

TEST(PreprocessFluidLayers, CompetingSelectionsAreRefusedWithTheReason) {
  const std::string path = scenes_dir() + "/fluid_layers_test.yaml";
  // Two kinematic conditions on one boundary: the second would get no point.
  auto e =
      error_of(fluid_plate(kBottomFixed + "  - {name: base, boundary: bottom, type: displacement, value: [0, 0]}\n"));
  EXPECT_EQ(e.rfind(path + ":19: boundary_conditions[1]: displacement on 'bottom', the selection of "
                           "boundary_conditions[0] ('bottom', velocity): both would be carried by the same layer "
                           "points (one kinematic condition per layer",
                    0),
            0u)
      << e;
  e = error_of(fluid_plate(kTopLoaded + "  - {name: more, boundary: top, type: pressure, value: 1 MPa}\n"));
  EXPECT_NE(e.find("boundary_conditions[1]: pressure on 'top', the selection of boundary_conditions[0] ('top', "
                   "traction): both would be carried by the same loaded points"),
            std::string::npos)
      << e;
  // A flux sharing loaded points must have their depth.
  e = error_of(fluid_plate(kTopLoaded + "  - {boundary: top, type: fluid_flux, value: 1e-6 m/s, depth: 3 mm}\n"));
  EXPECT_NE(e.find("boundary_conditions[1]: fluid_flux on 'top', the selection of boundary_conditions[0] ('top', "
                   "traction): a fluid flux takes the loaded points of that condition, so its depth"),
            std::string::npos)
      << e;
  // A drained boundary selected otherwise than the kinematic one that covers it gets no layer.
  e = error_of(fluid_plate(kBottomFixed +
                           "  - {boundary: top, type: velocity, value: [0, 0]}\n"
                           "  - {box: [[-1 mm, 39.9 mm], [101 mm, 40.1 mm]], type: pore_pressure, value: 0 Pa}\n"));
  EXPECT_NE(e.find("boundary_conditions[2]: the drained layer of box [[-0.001, 0.0399], [0.101, 0.0401]] m lies "
                   "wholly in the layers of kinematic conditions (to drain a kinematic layer, select its boundary "
                   "exactly as its condition does)"),
            std::string::npos)
      << e;
}
