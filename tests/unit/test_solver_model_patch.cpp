// A patch of a model (solver/model_patch.hpp): on a field that vanishes outside the patch, its
// operator gives the whole model's force and moment at the patch's points.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "solver/model_patch.hpp"
#include "solver/point_stability.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

// The force and moment of the field `u`, `w` from the model's start-up operator.
std::vector<double> response(Model& m, const std::vector<double>& u, const std::vector<double>& w) {
  m.points.displacement = u;
  m.points.rotation = w;
  m.linear_operator_kernel()(m.points, m.bonds, m.constants, nullptr);
  std::vector<double> both = m.points.force;
  both.insert(both.end(), m.points.moment.begin(), m.points.moment.end());
  return both;
}

// Every kernel term of a patch point reads only the patch's points and their neighbours, with the
// whole model's shape tensors; a neighbour's bonds to points outside carry no displacement. So the
// force and moment of the patch's points are the whole model's. They are compared exactly: the
// patch keeps the whole model's bond order, and the bonds it leaves out would add products of
// zeros.
TEST(ModelPatch, ForceOfAFieldOnThePatchIsTheWholeModels) {
  for (const int d : {2, 3}) {
    const double dx = 1e-3;
    Scene s = make_scene(d, true, dx, 3.05);
    const std::array<int, 3> n = d == 2 ? std::array<int, 3>{30, 26, 1} : std::array<int, 3>{16, 15, 14};
    Model m = make_model(make_lattice(d, n, dx, s.thickness), s);
    const auto D = static_cast<std::size_t>(d);
    const auto R = static_cast<std::size_t>(m.points.rotation_components);
    // The centre: the point nearest the middle of the lattice's lower x face, so that the patch
    // holds surface points and interior ones.
    std::size_t centre = 0;
    double nearest = 1e300;
    for (std::size_t i = 0; i < m.points.owned; ++i) {
      double r2 = std::pow(m.points.position[i * D] - 0.5 * dx, 2);
      for (std::size_t a = 1; a < D; ++a) r2 += std::pow(m.points.position[i * D + a] - 0.5 * n[a] * dx, 2);
      if (r2 < nearest) nearest = r2, centre = i;
    }
    const double radius = 2.0 * 3.05 * dx;
    std::array<double, 3> at{0.0, 0.0, 0.0};
    for (std::size_t a = 0; a < D; ++a) at[a] = m.points.position[centre * D + a];
    ModelPatch patch = cut_patch(m, at, radius);
    ASSERT_GT(patch.points_inside, 10u);
    ASSERT_LT(patch.points_inside, patch.model.points.owned);  // neighbours beside the patch's own
    ASSERT_LT(patch.model.points.owned, m.points.owned);
    // The same field on both: random on the patch's own points, zero elsewhere.
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> g(-1e-6, 1e-6);
    std::vector<double> u(m.points.owned * D, 0.0), w(m.points.owned * R, 0.0);
    std::vector<double> pu(patch.model.points.owned * D, 0.0), pw(patch.model.points.owned * R, 0.0);
    std::vector<std::size_t> whole_index;
    for (std::size_t i = 0; i < m.points.owned; ++i) {
      double r2 = 0.0;
      for (std::size_t a = 0; a < D; ++a)
        r2 += std::pow(m.points.position[i * D + a] - m.points.position[centre * D + a], 2);
      bool member = r2 <= radius * radius;
      for (std::int64_t b = m.bonds.offset[i]; !member && b < m.bonds.offset[i + 1]; ++b) {
        const std::size_t j = m.bonds.neighbor_of(b);
        double q2 = 0.0;
        for (std::size_t a = 0; a < D; ++a)
          q2 += std::pow(m.points.position[j * D + a] - m.points.position[centre * D + a], 2);
        member = q2 <= radius * radius;
      }
      if (member) whole_index.push_back(i);  // the patch's members, in the model's order
    }
    ASSERT_EQ(whole_index.size(), patch.model.points.owned);
    for (std::size_t s2 = 0; s2 < whole_index.size(); ++s2) {
      const std::size_t i = whole_index[s2];
      for (std::size_t a = 0; a < D; ++a)
        ASSERT_EQ(patch.model.points.position[s2 * D + a], m.points.position[i * D + a]);
      if (!patch.inside[s2]) continue;
      for (std::size_t a = 0; a < D; ++a) u[i * D + a] = pu[s2 * D + a] = g(rng);
      for (std::size_t a = 0; a < R; ++a) w[i * R + a] = pw[s2 * R + a] = 1e3 * g(rng);
    }
    const std::vector<double> whole = response(m, u, w);
    const std::vector<double> part = response(patch.model, pu, pw);
    const std::size_t wn = m.points.owned, pn = patch.model.points.owned;
    int compared = 0;
    for (std::size_t s2 = 0; s2 < pn; ++s2) {
      if (!patch.inside[s2]) continue;
      const std::size_t i = whole_index[s2];
      for (std::size_t a = 0; a < D; ++a) EXPECT_EQ(part[s2 * D + a], whole[i * D + a]) << d << "-D point " << i;
      for (std::size_t a = 0; a < R; ++a)
        EXPECT_EQ(part[pn * D + s2 * R + a], whole[wn * D + i * R + a]) << d << "-D point " << i;
      compared += 1;
    }
    EXPECT_EQ(static_cast<std::size_t>(compared), patch.points_inside);
  }
}

// The naming's centre is the stiffest point of all, the fictitious layers' included: the corner
// of a layer, whose family is cut on two sides, is stiffer than any body point here (as on the 3-D
// Kalthoff-Winkler specimen, where the highest mode lives there). The damage limit's largest block
// is over the body points only, as before. Both are the first of the largest, checked against the
// point blocks one by one.
TEST(StiffestPoints, TheLayersCountForThePatchAndNotForTheDamageLimit) {
  const double dx = 1e-3;
  Scene s = make_scene(2, true, dx, 3.05);
  PointCloud cloud = make_lattice(2, {24, 12, 1}, dx, s.thickness);
  testing::add_end_layers(cloud, 24, 3, "displacement", "velocity");
  Model m = make_model(cloud, s);
  const StiffestPoints found = stiffest_points(m.points, m.bonds, m.constants);
  StiffestPoint body, any;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    const double v = point_block_eigenvalue(m.points, m.bonds, m.constants, i);
    if (v > any.block_eigenvalue) any = {i, v};
    if (m.points.region[i] == 0 && v > body.block_eigenvalue) body = {i, v};
  }
  EXPECT_EQ(found.any.index, any.index);
  EXPECT_EQ(found.any.block_eigenvalue, any.block_eigenvalue);
  EXPECT_EQ(found.body.index, body.index);
  EXPECT_EQ(found.body.block_eigenvalue, body.block_eigenvalue);
  EXPECT_EQ(found.body.block_eigenvalue, max_point_block_eigenvalue(m.points, m.bonds, m.constants));
  EXPECT_EQ(m.points.region[found.body.index], 0);
  EXPECT_GT(m.points.region[found.any.index], 0);
  EXPECT_GT(found.any.block_eigenvalue, found.body.block_eigenvalue);
}

// The patch is cut only where its operator is the whole model's at rest: not with the pore fluid,
// not once the model holds history (a broken bond). (A distributed run's patch is cut across its
// processes: tests/mpi.)
TEST(ModelPatch, IsCutOnlyWhereItsOperatorIsTheWholeModels) {
  Scene s = make_scene(2, true, 1e-3, 3.05);
  s.effects.damage = true;
  s.material.damage = DamageParameters{100.0, 0.0, DamageCalibration::lattice, std::nullopt};
  Model m = make_model(make_lattice(2, {10, 9, 1}, 1e-3, s.thickness), s);
  EXPECT_TRUE(can_cut_patches(m));
  m.bonds.break_bond(0);
  EXPECT_FALSE(can_cut_patches(m));
  EXPECT_THROW(cut_patch(m, {0.0, 0.0, 0.0}, 1e-3), std::logic_error);
  Model wet = make_model(make_lattice(2, {10, 9, 1}, 1e-3, s.thickness), make_scene(2, true, 1e-3, 3.05));
  EXPECT_TRUE(can_cut_patches(wet));
  wet.effects.pore_fluid = true;
  EXPECT_FALSE(can_cut_patches(wet));
}

}  // namespace
}  // namespace mppm::solver
