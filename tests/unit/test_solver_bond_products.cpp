// The force kernel's pass-2 bond products (solver/bond_products.hpp): where the instruction set has
// vectors and fused multiply-adds (AVX2 and FMA), a 2-D bond's two rows of A xi + C U are the two
// lanes of one vector. Each lane does its row's scalar operations in their order, so the lane form
// and the scalar loop agree to the bit (compared as bytes: a zero's sign included) for the
// neighbour's share with the force it accumulates over a family, and for the bond work's pair force.
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <random>

#include "solver/bond_products.hpp"

namespace mppm::solver {
namespace {

#ifdef MPPM_VECTOR_LANES
// A bond's inputs with the magnitudes of a run (tensors ~1e12 Pa/m^2, bond vectors ~1e-3 m,
// displacements ~1e-6 m), one entry in seven a zero of either sign, so that the sign of a zero
// sum is compared too.
struct RandomBond {
  std::array<double, 4> a, ai;
  std::array<double, 3> ck, cki;
  std::array<double, 2> xi, U, U0;
  double vj;
};

class RandomBonds {
 public:
  RandomBond next() {
    RandomBond b;
    for (double& v : b.a) v = value(1e12);
    for (double& v : b.ai) v = value(1e12);
    for (double& v : b.ck) v = value(1e12);
    for (double& v : b.cki) v = value(1e12);
    for (double& v : b.xi) v = value(1e-3);
    for (double& v : b.U) v = value(1e-6);
    for (double& v : b.U0) v = value(1e-6);
    b.vj = 1e-9 * (1.0 + uniform_(rng_));
    return b;
  }

 private:
  double value(double scale) {
    const int k = static_cast<int>(++count_ % 7);
    if (k == 0) return (count_ % 2) ? 0.0 : -0.0;
    return scale * uniform_(rng_);
  }
  std::mt19937_64 rng_{11};
  std::uniform_real_distribution<double> uniform_{-1.0, 1.0};
  std::uint64_t count_ = 0;
};

TEST(BondProducts, TwoDimensionalLanesGiveTheScalarNeighbourShareBitForBit) {
  RandomBonds bonds;
  // A family's force accumulated bond by bond in each form: the sums compared after every bond.
  double force_scalar[2] = {0.0, -0.0}, force_vector[2] = {0.0, -0.0};
  for (int k = 0; k < 20000; ++k) {
    const RandomBond b = bonds.next();
    double t_scalar[2], t_vector[2];
    kernel::neighbour_share_scalar<2>(b.a.data(), b.ck.data(), b.xi.data(), b.U.data(), b.vj, t_scalar, force_scalar);
    kernel::neighbour_share_vector_2d(b.a.data(), b.ck.data(), b.xi.data(), b.U.data(), b.vj, t_vector, force_vector);
    ASSERT_EQ(std::memcmp(t_scalar, t_vector, sizeof t_scalar), 0) << "bond " << k;
    ASSERT_EQ(std::memcmp(force_scalar, force_vector, sizeof force_scalar), 0) << "bond " << k;
  }
}

TEST(BondProducts, TwoDimensionalLanesGiveTheScalarPairForceBitForBit) {
  RandomBonds bonds;
  for (int k = 0; k < 20000; ++k) {
    const RandomBond b = bonds.next();
    double scalar[2], vector[2];
    kernel::pair_force_sum_scalar<2>(b.ai.data(), b.a.data(), b.cki.data(), b.ck.data(), b.xi.data(), b.U0.data(),
                                     b.U.data(), scalar);
    kernel::pair_force_sum_vector_2d(b.ai.data(), b.a.data(), b.cki.data(), b.ck.data(), b.xi.data(), b.U0.data(),
                                     b.U.data(), vector);
    ASSERT_EQ(std::memcmp(scalar, vector, sizeof scalar), 0) << "bond " << k;
  }
}
#else
TEST(BondProducts, TwoDimensionalLanesGiveTheScalarNeighbourShareBitForBit) {
  GTEST_SKIP() << "this build's instruction set has no AVX2 and FMA: the kernel forms bond products in scalars only";
}
#endif

}  // namespace
}  // namespace mppm::solver
