// The force kernel's pass-1 bond sums (solver/bond_sums.hpp): in 3-D, where the instruction set has
// 4-lane vectors and fused multiply-adds, the kernel sums a bond's components as vector lanes. Each
// lane does the scalar loop's operations in its order, so the two forms agree to the bit (compared
// as bytes: a zero's sign included), on every effect set, with broken bonds skipped, and with the
// bond vectors from the positions or stored (periodic lattices).
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "solver/bond_sums.hpp"
#include "tests/verification/solver_test_lattice.hpp"

namespace mppm::solver {
namespace {

using testing::make_lattice;
using testing::make_model;
using testing::make_scene;

#ifdef MPPM_BOND_SUMS_VECTOR
using kernel::BondSums;

// Every point's sums by both forms, compared as bytes; the number of points compared.
template <class Effects, bool StoredXi>
int compare_every_point(const Model& m) {
  int compared = 0;
  for (std::size_t i = 0; i < m.points.owned; ++i) {
    BondSums<3, 3> scalar{}, vector{};
    kernel::bond_sums_scalar<3, Effects, StoredXi>(m.points, m.bonds, i, scalar);
    kernel::bond_sums_vector<Effects, StoredXi>(m.points, m.bonds, i, vector);
    EXPECT_EQ(std::memcmp(&scalar, &vector, sizeof scalar), 0) << "point " << i;
    ++compared;
  }
  return compared;
}

// A 3-D lattice with random displacements and rotations (zeros of both signs among them) and, with
// damage, every fifth bond entry broken.
Model random_model(bool micropolar, bool damage, bool periodic) {
  constexpr double dx = 1e-3;
  Scene s = make_scene(3, micropolar, dx, 2.05);
  if (damage) {
    s.effects.damage = true;
    s.material.damage = DamageParameters{100.0, 0.0, DamageCalibration::lattice, std::nullopt};
  }
  const std::array<double, 3> period =
      periodic ? std::array<double, 3>{5 * dx, 5 * dx, 5 * dx} : std::array<double, 3>{0.0, 0.0, 0.0};
  Model m = make_model(make_lattice(3, {5, 5, 5}, dx), s, period);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> g(-1e-6, 1e-6);
  std::size_t k = 0;
  for (auto& u : m.points.displacement) u = (++k % 7 == 0) ? (k % 2 ? 0.0 : -0.0) : g(rng);
  for (auto& w : m.points.rotation) w = (++k % 5 == 0) ? -0.0 : 1e3 * g(rng);
  if (damage)
    for (std::int64_t b = 0; b < m.bonds.offset[m.points.owned]; b += 5) m.bonds.break_bond(b);
  return m;
}

TEST(BondSumsPath, VectorLanesGiveTheScalarSumsBitForBit) {
  for (const bool periodic : {false, true}) {
    SCOPED_TRACE(periodic ? "stored bond vectors" : "bond vectors from the positions");
    const bool stored = periodic;
    auto run = [&]<class E>(bool micropolar, bool damage) {
      const Model m = random_model(micropolar, damage, periodic);
      ASSERT_EQ(!m.bonds.xi.empty(), stored);
      const int n = stored ? compare_every_point<E, true>(m) : compare_every_point<E, false>(m);
      EXPECT_EQ(n, 125);
    };
    run.template operator()<CompiledEffects<false, false, false>>(false, false);
    run.template operator()<CompiledEffects<true, false, false>>(true, false);
    run.template operator()<CompiledEffects<true, true, false>>(true, true);
    run.template operator()<CompiledEffects<false, true, false>>(false, true);
  }
}
#else
TEST(BondSumsPath, VectorLanesGiveTheScalarSumsBitForBit) {
  GTEST_SKIP() << "this build's instruction set has no AVX2 and FMA: the kernel sums bonds in scalars only";
}
#endif

}  // namespace
}  // namespace mppm::solver
