// The one Cosserat law (docs/theory.md section 5): the elastic kernel's form, the return map's
// form and the plane-strain stress of the viscoplastic points are the same law, term for term.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "solver/cosserat_material.hpp"
#include "solver/plasticity/cosserat_elasticity.hpp"
#include "solver/viscoplastic_point.hpp"

namespace mppm::solver {
namespace {

using Mat2 = Eigen::Matrix<double, 2, 2, Eigen::RowMajor>;
using Mat3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;

// Moduli of no particular material, all different, so that a swapped term shows.
CosseratConstants constants() {
  return {.lambda = 1.7e9, .mu = 2.9e9, .mu_c = 0.8e9, .a1 = 13.0, .a2 = 41.0, .a3 = 23.0, .bending_modulus = 23.0};
}

template <class M>
M random_tensor(std::mt19937& rng) {
  std::uniform_real_distribution<double> g(-1e-3, 1e-3);
  M m;
  for (int k = 0; k < m.size(); ++k) m.data()[k] = g(rng);
  return m;
}

// The kernel's law and the return map's law give the same bits: one expression, one order of terms.
TEST(CosseratLaw, KernelAndReturnMapUseTheSameLaw) {
  const CosseratConstants c = constants();
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 eps = random_tensor<Mat3>(rng);
    const Eigen::Matrix3d stress = plasticity::cosserat_stress(Eigen::Matrix3d(eps), viscoplastic::elasticity_3d(c));
    EXPECT_EQ(Eigen::Matrix3d(cosserat_stress<3>(eps, c)), stress);
    const Mat3 kap = random_tensor<Mat3>(rng);
    EXPECT_EQ(Eigen::Matrix3d(couple_stress<3, 3>(kap, c)),
              plasticity::couple_stress(Eigen::Matrix3d(kap), viscoplastic::elasticity_3d(c)));
  }
}

// Its symmetric part alone gives sigma = lambda tr(e) 1 + 2 mu e (the classical law), its
// skew part 2 mu_c e: checked against the textbook form to rounding (1e-15 of the largest term).
TEST(CosseratLaw, SplitsIntoTheClassicalLawAndTheCoupleModulusTerm) {
  const CosseratConstants c = constants();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 100; ++trial) {
    const Mat3 eps = random_tensor<Mat3>(rng);
    const Mat3 sym = 0.5 * (eps + eps.transpose()), skew = 0.5 * (eps - eps.transpose());
    const Mat3 expected = c.lambda * eps.trace() * Mat3::Identity() + 2.0 * c.mu * sym + 2.0 * c.mu_c * skew;
    EXPECT_LE((cosserat_stress<3>(eps, c) - expected).norm(), 1e-15 * (c.lambda + 2.0 * c.mu) * eps.norm() * 4.0);
  }
}

// Plane strain: the viscoplastic points' stress is the law of the 3 x 3 strain with the
// out-of-plane component. sigma_zz is its zz entry to the bit; the in-plane block is summed as the
// elastic kernel sums it (so eps_vp = 0 gives the kernel's bits), which is the 3 x 3 law's block to
// rounding, and with eps_zz = 0 it is the 2 x 2 law to the bit.
TEST(CosseratLaw, PlaneStrainStressIsTheLawOfTheEmbeddedStrain) {
  const CosseratConstants c = constants();
  std::mt19937 rng(7);
  for (int trial = 0; trial < 100; ++trial) {
    viscoplastic::ElasticStrain<2> e;
    e.in_plane = random_tensor<Mat2>(rng);
    e.zz = random_tensor<Eigen::Matrix<double, 1, 1>>(rng)(0, 0);
    Mat3 embedded = Mat3::Zero();
    embedded.topLeftCorner<2, 2>() = e.in_plane;
    embedded(2, 2) = e.zz;
    const Mat3 law = plasticity::isotropic_cosserat_law(embedded, c.lambda, c.mu + c.mu_c, c.mu - c.mu_c);
    const viscoplastic::ElasticStress<2> s = viscoplastic::elastic_stress<2>(e, c);
    EXPECT_EQ(s.zz, law(2, 2));
    EXPECT_LE((s.in_plane - law.topLeftCorner<2, 2>()).norm(), 4e-16 * law.norm());
    e.zz = 0.0;
    EXPECT_EQ(viscoplastic::elastic_stress<2>(e, c).in_plane, cosserat_stress<2>(e.in_plane, c));
  }
}

}  // namespace
}  // namespace mppm::solver
