// The force kernel's pass-1 bond sums (solver/bond_sums.hpp): where the instruction set has vectors
// and fused multiply-adds (AVX2 and FMA), the kernel sums a bond's components as vector lanes (4
// lanes in 3-D, 2 in 2-D). Each
// lane does the scalar loop's operations in its order, so the two forms agree to the bit (compared
// as bytes: a zero's sign included), on every effect set, with broken bonds skipped, and with the
// bond vectors from the positions or stored (periodic lattices).
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <random>

#include "solver/bond_sums.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

#ifdef MPPM_VECTOR_LANES
using kernel::BondSums;

// Every point's sums by both forms, compared as bytes; the number of points compared.
template <int D, class Effects, bool StoredXi>
int compare_every_point(const Model& m) {
  int compared = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    BondSums<D, rotation_components<D>> scalar{}, vector{};
    kernel::bond_sums_scalar<D, Effects, StoredXi>(m.points, m.bonds, i, scalar);
    if constexpr (D == 3)
      kernel::bond_sums_vector<Effects, StoredXi>(m.points, m.bonds, i, vector);
    else
      kernel::bond_sums_vector_2d<Effects, StoredXi>(m.points, m.bonds, i, vector);
    // Every sum; not the vector form's spill of its fourth lanes (BondSums::lane_spill).
    EXPECT_EQ(std::memcmp(&scalar, &vector, offsetof(decltype(scalar), lane_spill)), 0) << D << "-D, point " << i;
    ++compared;
  }
  return compared;
}

// A lattice (5^3 points in 3-D at horizon factor 2.05; 7^2 in 2-D at 3.05, the crack-branching
// plate's family size; a period must exceed two horizons) with random displacements and rotations (zeros of both
// signs among them) and, with damage, every fifth bond entry broken.
Model random_model(int dimension, bool micropolar, bool damage, bool periodic) {
  constexpr double dx = 1e-3;
  Scene s = make_scene(dimension, micropolar, dx, dimension == 3 ? 2.05 : 3.05);
  if (damage) {
    s.effects.damage = true;
    s.material.damage = DamageParameters{100.0, 0.0, DamageCalibration::lattice, std::nullopt};
  }
  const int n = dimension == 3 ? 5 : 7;
  const double side = n * dx;
  const std::array<double, 3> period =
      periodic ? std::array<double, 3>{side, side, dimension == 3 ? side : 0.0} : std::array<double, 3>{0.0, 0.0, 0.0};
  Model m = make_model(make_lattice(dimension, {n, n, dimension == 3 ? n : 1}, dx, s.thickness), s, period);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> g(-1e-6, 1e-6);
  std::size_t k = 0;
  for (auto& u : m.points.displacement) u = (++k % 7 == 0) ? (k % 2 ? 0.0 : -0.0) : g(rng);
  for (auto& w : m.points.rotation) w = (++k % 5 == 0) ? -0.0 : 1e3 * g(rng);
  if (damage)
    for (std::int64_t b = 0; b < m.bonds.offset[m.points.owned]; b += 5) m.bonds.break_bond(b);
  return m;
}

template <int D>
void compare_every_effect_set() {
  for (const bool periodic : {false, true}) {
    SCOPED_TRACE(periodic ? "stored bond vectors" : "bond vectors from the positions");
    const bool stored = periodic;
    auto run = [&]<class E>(bool micropolar, bool damage) {
      const Model m = random_model(D, micropolar, damage, periodic);
      ASSERT_EQ(!m.bonds.xi.empty(), stored);
      const int n = stored ? compare_every_point<D, E, true>(m) : compare_every_point<D, E, false>(m);
      EXPECT_EQ(n, D == 3 ? 125 : 49);
    };
    run.template operator()<CompiledEffects<false, false, false>>(false, false);
    run.template operator()<CompiledEffects<true, false, false>>(true, false);
    run.template operator()<CompiledEffects<true, true, false>>(true, true);
    run.template operator()<CompiledEffects<false, true, false>>(false, true);
  }
}

TEST(BondSumsPath, VectorLanesGiveTheScalarSumsBitForBit) {
  compare_every_effect_set<3>();
  compare_every_effect_set<2>();
}
#else
TEST(BondSumsPath, VectorLanesGiveTheScalarSumsBitForBit) {
  GTEST_SKIP() << "this build's instruction set has no AVX2 and FMA: the kernel sums bonds in scalars only";
}
#endif

}  // namespace
}  // namespace mppm::solver
