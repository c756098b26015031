// The force kernel's pass-2 bond products (solver/bond_products.hpp): where the instruction set has
// vectors and fused multiply-adds (AVX2 and FMA), a bond's rows of A xi + C U are the lanes of one
// vector (2 in 2-D, 3 of 4 in 3-D). Each lane does its row's scalar operations in their order, so
// the lane form and the scalar loop agree to the bit (compared as bytes: a zero's sign included)
// for the neighbour's share with the force it accumulates over a family, for the bond work's pair
// force, and in 3-D for their moment counterparts.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <random>
#include <vector>

#include "solver/bond_products.hpp"

namespace mppm::solver {
namespace {

#ifdef MPPM_VECTOR_LANES
// A bond's inputs with the magnitudes of a run (tensors ~1e12 Pa/m^2, bond vectors ~1e-3 m,
// displacements ~1e-6 m), one entry in seven a zero of either sign, so that the sign of a zero
// sum is compared too. The tensors sit at the end of their arrays, as the last point's do: the
// lane forms must not read past them (the address sanitizer build would catch it).
template <int D>
struct RandomBond {
  std::vector<double> a, ai, ck, cki;           // D * D and D (D + 1) / 2 entries
  std::vector<double> q, qi, wi, wj, wi0, wj0;  // D * D and D entries (3-D)
  double xi[D], U[D], U0[D], t[4];
  double vj, g;
};

template <int D>
class RandomBonds {
 public:
  RandomBond<D> next() {
    RandomBond<D> b;
    for (auto* tensor : {&b.a, &b.ai}) fill(*tensor, D * D, 1e12);
    for (auto* tensor : {&b.ck, &b.cki}) fill(*tensor, D * (D + 1) / 2, 1e12);
    for (auto* tensor : {&b.q, &b.qi}) fill(*tensor, D * D, 1e5);
    for (auto* rotation : {&b.wi, &b.wj, &b.wi0, &b.wj0}) fill(*rotation, D, 1e-3);
    for (double& v : b.t) v = value(1e9);
    b.g = 1e14 * (1.0 + uniform_(rng_));
    for (int k = 0; k < D; ++k) {
      b.xi[k] = value(1e-3);
      b.U[k] = value(1e-6);
      b.U0[k] = value(1e-6);
    }
    b.vj = 1e-9 * (1.0 + uniform_(rng_));
    return b;
  }

 private:
  void fill(std::vector<double>& tensor, int size, double scale) {
    tensor.resize(static_cast<std::size_t>(size));
    for (double& v : tensor) v = value(scale);
  }
  double value(double scale) {
    const int k = static_cast<int>(++count_ % 7);
    if (k == 0) return (count_ % 2) ? 0.0 : -0.0;
    return scale * uniform_(rng_);
  }
  std::mt19937_64 rng_{11};
  std::uniform_real_distribution<double> uniform_{-1.0, 1.0};
  std::uint64_t count_ = 0;
};

// The vector forms of D (3-D writes 4 doubles to t, force and the pair force).
template <int D>
void neighbour_share_vector(const RandomBond<D>& b, double* t, double* force) {
  if constexpr (D == 2)
    kernel::neighbour_share_vector_2d(b.a.data(), b.ck.data(), b.xi, b.U, b.vj, t, force);
  else
    kernel::neighbour_share_vector_3d(b.a.data(), b.ck.data(), b.xi, b.U, b.vj, t, force);
}
template <int D>
void pair_force_sum_vector(const RandomBond<D>& b, double* both) {
  if constexpr (D == 2)
    kernel::pair_force_sum_vector_2d(b.ai.data(), b.a.data(), b.cki.data(), b.ck.data(), b.xi, b.U0, b.U, both);
  else
    kernel::pair_force_sum_vector_3d(b.ai.data(), b.a.data(), b.cki.data(), b.ck.data(), b.xi, b.U0, b.U, both);
}

template <int D>
void compare_neighbour_shares() {
  RandomBonds<D> bonds;
  // A family's force accumulated bond by bond in each form: the sums compared after every bond.
  double force_scalar[4] = {0.0, -0.0, 0.0, 0.0}, force_vector[4] = {0.0, -0.0, 0.0, 0.0};
  for (int k = 0; k < 20000; ++k) {
    const RandomBond<D> b = bonds.next();
    double t_scalar[4], t_vector[4];
    kernel::neighbour_share_scalar<D>(b.a.data(), b.ck.data(), b.xi, b.U, b.vj, t_scalar, force_scalar);
    neighbour_share_vector<D>(b, t_vector, force_vector);
    ASSERT_EQ(std::memcmp(t_scalar, t_vector, D * sizeof(double)), 0) << D << "-D, bond " << k;
    ASSERT_EQ(std::memcmp(force_scalar, force_vector, D * sizeof(double)), 0) << D << "-D, bond " << k;
  }
}

template <int D>
void compare_pair_forces() {
  RandomBonds<D> bonds;
  for (int k = 0; k < 20000; ++k) {
    const RandomBond<D> b = bonds.next();
    double scalar[4], vector[4];
    kernel::pair_force_sum_scalar<D>(b.ai.data(), b.a.data(), b.cki.data(), b.ck.data(), b.xi, b.U0, b.U, scalar);
    pair_force_sum_vector<D>(b, vector);
    ASSERT_EQ(std::memcmp(scalar, vector, D * sizeof(double)), 0) << D << "-D, bond " << k;
  }
}

// 3-D: the moment's share accumulated over a family, and the pair moment with its rotation change.
void compare_moments() {
  RandomBonds<3> bonds;
  double moment_scalar[4] = {0.0, -0.0, 0.0, 0.0}, moment_vector[4] = {0.0, -0.0, 0.0, 0.0};
  for (int k = 0; k < 20000; ++k) {
    const RandomBond<3> b = bonds.next();
    kernel::neighbour_moment_scalar<3, 3>(b.q.data(), b.g, b.wi.data(), b.wj.data(), b.xi, b.t, b.vj, moment_scalar);
    kernel::neighbour_moment_vector_3d(b.q.data(), b.g, b.wi.data(), b.wj.data(), b.xi, b.t, b.vj, moment_vector);
    ASSERT_EQ(std::memcmp(moment_scalar, moment_vector, 3 * sizeof(double)), 0) << "bond " << k;
    double both_scalar[4], change_scalar[4], both_vector[4], change_vector[4];
    kernel::pair_moment_sum_scalar<3, 3>(b.qi.data(), b.q.data(), b.g, b.wi.data(), b.wj.data(), b.wi0.data(),
                                         b.wj0.data(), b.xi, both_scalar, change_scalar);
    kernel::pair_moment_sum_vector_3d(b.qi.data(), b.q.data(), b.g, b.wi.data(), b.wj.data(), b.wi0.data(),
                                      b.wj0.data(), b.xi, both_vector, change_vector);
    ASSERT_EQ(std::memcmp(both_scalar, both_vector, 3 * sizeof(double)), 0) << "bond " << k;
    ASSERT_EQ(std::memcmp(change_scalar, change_vector, 3 * sizeof(double)), 0) << "bond " << k;
  }
}

TEST(BondProducts, VectorLanesGiveTheScalarMomentsBitForBit) { compare_moments(); }

TEST(BondProducts, VectorLanesGiveTheScalarNeighbourShareBitForBit) {
  compare_neighbour_shares<2>();
  compare_neighbour_shares<3>();
}

TEST(BondProducts, VectorLanesGiveTheScalarPairForceBitForBit) {
  compare_pair_forces<2>();
  compare_pair_forces<3>();
}
#else
TEST(BondProducts, VectorLanesGiveTheScalarNeighbourShareBitForBit) {
  GTEST_SKIP() << "this build's instruction set has no AVX2 and FMA: the kernel forms bond products in scalars only";
}
#endif

}  // namespace
}  // namespace mppm::solver
