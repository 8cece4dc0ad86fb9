// Lemke's pivoting (contact/complementarity.hpp) against hand-solved problems and against the enumeration of every
// complementary set, which for a P-matrix holds exactly one solution.
#include <cmath>
#include <optional>
#include <random>
#include <vector>

#include <doctest/doctest.h>

#include "contact/complementarity.hpp"

using namespace fretwear;

namespace {

// The solution of LCP(A, q) found by trying every set S of positive z: A_SS z_S = −q_S with z_S ≥ 0 and w ≥ 0.
std::optional<Eigen::VectorXd> enumerate(const Eigen::MatrixXd& A, const Eigen::VectorXd& q) {
  const int n = int(q.size());
  for (unsigned set = 0; set < (1u << n); ++set) {
    std::vector<int> S;
    for (int i = 0; i < n; ++i)
      if (set & (1u << i)) S.push_back(i);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
    if (!S.empty()) {
      const Eigen::VectorXd zs = Eigen::MatrixXd(A(S, S)).partialPivLu().solve(Eigen::VectorXd(-q(S)));
      for (std::size_t k = 0; k < S.size(); ++k) z(S[k]) = zs(Eigen::Index(k));
    }
    const Eigen::VectorXd w = A * z + q;
    if (z.minCoeff() >= -1e-12 && w.minCoeff() >= -1e-10) return z;
  }
  return std::nullopt;
}

void check_complementary(const LcpSolution& s, const Eigen::MatrixXd& A, const Eigen::VectorXd& q) {
  const double scale = q.cwiseAbs().maxCoeff();
  CHECK(s.z.minCoeff() >= 0.0);
  CHECK(s.w.minCoeff() >= -1e-10 * scale);
  CHECK((s.w - (A * s.z + q)).cwiseAbs().maxCoeff() <= 1e-12 * scale);
  CHECK(std::abs(s.w.dot(s.z)) <= 1e-10 * scale * s.z.cwiseAbs().sum());
}

}  // namespace

TEST_CASE("LCP: q >= 0 is solved by z = 0, without a pivot") {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3);
  const Eigen::VectorXd q = Eigen::Vector3d(1.0, 0.0, 2.0);
  const auto s = solve_lcp(A, q, 10);
  REQUIRE(s);
  CHECK(s->z.isZero());
  CHECK(s->pivots == 0);
}

TEST_CASE("LCP: two hand-solved problems, one with both z positive and one with one") {
  Eigen::MatrixXd A(2, 2);
  A << 2.0, 1.0, 1.0, 2.0;
  // 2 z₁ + z₂ = 5, z₁ + 2 z₂ = 6: z = (4/3, 7/3), w = 0.
  auto s = solve_lcp(A, Eigen::Vector2d(-5.0, -6.0), 10);
  REQUIRE(s);
  CHECK(s->z(0) == doctest::Approx(4.0 / 3.0).epsilon(1e-14));
  CHECK(s->z(1) == doctest::Approx(7.0 / 3.0).epsilon(1e-14));
  CHECK(s->w.cwiseAbs().maxCoeff() < 1e-14);
  // 2 z₁ − 2 = 0 with z₂ = 0: w₂ = 1 + 3 = 4.
  s = solve_lcp(A, Eigen::Vector2d(-2.0, 3.0), 10);
  REQUIRE(s);
  CHECK(s->z(0) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(s->z(1) == 0.0);
  CHECK(s->w(1) == doctest::Approx(4.0).epsilon(1e-14));
}

TEST_CASE("LCP: a problem without a solution ends on a ray, not in a loop") {
  // w = −z − 1 < 0 for every z ≥ 0.
  const Eigen::MatrixXd A = -Eigen::MatrixXd::Identity(2, 2);
  CHECK_FALSE(solve_lcp(A, Eigen::Vector2d(-1.0, -1.0), 100));
}

TEST_CASE("LCP: random P-matrices, unsymmetric, agree with the enumeration of every complementary set") {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 40; ++trial) {
    CAPTURE(trial);
    const int n = 3 + trial % 6;
    // A diagonally dominant matrix with a positive diagonal is a P-matrix; an unsymmetric part as friction gives.
    Eigen::MatrixXd A(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) A(i, j) = normal(rng);
    for (int i = 0; i < n; ++i) A(i, i) = A.row(i).cwiseAbs().sum() + 0.1;
    Eigen::VectorXd q(n);
    for (int i = 0; i < n; ++i) q(i) = normal(rng);
    const auto s = solve_lcp(A, q, 50 * n);
    REQUIRE(s);
    check_complementary(*s, A, q);
    const auto e = enumerate(A, q);
    REQUIRE(e);
    CHECK((s->z - *e).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + e->cwiseAbs().maxCoeff()));
  }
}

TEST_CASE("LCP: a degenerate problem (equal q, repeated rows) does not cycle") {
  // A = I + J (J all ones), q = −(4/3)(1, 1, 1): the first ratio tests all tie, and z_i + Σ_j z_j = 4/3 gives
  // z_i = 1/3.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(3, 3) + Eigen::MatrixXd::Ones(3, 3);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(3, -4.0 / 3.0);
  const auto s = solve_lcp(A, q, 30);
  REQUIRE(s);
  check_complementary(*s, A, q);
  for (int i = 0; i < 3; ++i) CHECK(s->z(i) == doctest::Approx(1.0 / 3.0).epsilon(1e-13));
}
