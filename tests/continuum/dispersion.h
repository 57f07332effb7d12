// The exact linear dispersion relation of the continuum equations, written out here from
// the paper's eqs. 1-5 and independently of the solver: the mode matrix M(k) of
// d(delta rho, delta sigma [, P_parallel])/dt = M (...) about (rho0, sigma0), its eigenvalues
// and left eigenvectors (to pick one eigenmode out of a random perturbation), and the paper's
// eqs. 1-2, M's expansion to 4th order in k.
#pragma once

#include "continuum_solver.h"

#include <array>
#include <cmath>
#include <complex>
#include <vector>

namespace ActiveGrain::Continuum::testing {

using Complex = std::complex<double>;
using Matrix = std::vector<std::vector<Complex>>;

struct Background {
  ModelParameters p;
  double rho0, sigma0;
};

// Slaved P: 2 x 2. Relaxed P: 3 x 3 in (rho, sigma, P_parallel = khat . P); the transverse part
// of P only relaxes. With expanded = true the paper's eqs. 1-2 (slaved only).
inline Matrix mode_matrix(const Background &b, double k, bool expanded = false)
{
  const ModelParameters &p = b.p;
  const double k2 = k * k;
  const double c[2] = {b.rho0 * p.alpha, b.sigma0 * p.u0}, g[2] = {p.A, p.B};
  const double D[2][2] = {{p.D_rho, p.D_rho_sigma}, {p.D_sigma_rho, p.D_sigma}};
  if (p.tau == 0.0) {
    const double response = expanded ? k2 / p.a - p.K * k2 * k2 / (p.a * p.a) : k2 / (p.a + p.K * k2);
    Matrix M(2, std::vector<Complex>(2));
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) M[i][j] = -D[i][j] * k2 + c[i] * g[j] * response;
    return M;
  }
  const Complex ik(0.0, k);
  Matrix M(3, std::vector<Complex>(3));
  for (int i = 0; i < 2; ++i) {
    for (int j = 0; j < 2; ++j) M[i][j] = -D[i][j] * k2;
    M[i][2] = -c[i] * ik;            // - c_i div P
    M[2][i] = ik * g[i] / p.tau;      // (A, B) grad / tau
  }
  M[2][2] = -(p.a + p.K * k2) / p.tau;
  return M;
}

inline Complex det3(const Matrix &M)
{
  return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
         M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
}

// Eigenvalues: 2 x 2 in closed form; 3 x 3 as the roots of the characteristic polynomial
// lambda^3 - t lambda^2 + s lambda - d (Durand-Kerner iteration, then Newton polishing).
inline std::vector<Complex> eigenvalues(const Matrix &M)
{
  if (M.size() == 2) {
    const Complex tr = M[0][0] + M[1][1], det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
    const Complex root = std::sqrt(tr * tr / 4.0 - det);
    return {tr / 2.0 + root, tr / 2.0 - root};
  }
  const Complex t = M[0][0] + M[1][1] + M[2][2];
  const Complex s = M[0][0] * M[1][1] - M[0][1] * M[1][0] + M[0][0] * M[2][2] - M[0][2] * M[2][0] +
                    M[1][1] * M[2][2] - M[1][2] * M[2][1];
  const Complex d = det3(M);
  auto poly = [&](Complex x) { return ((x - t) * x + s) * x - d; };
  auto dpoly = [&](Complex x) { return (3.0 * x - 2.0 * t) * x + s; };
  const double scale = 1.0 + std::abs(t) + std::sqrt(std::abs(s)) + std::cbrt(std::abs(d));
  std::vector<Complex> z = {Complex(0.4, 0.9) * scale, Complex(0.4, 0.9) * Complex(0.4, 0.9) * scale,
                            Complex(0.4, 0.9) * Complex(0.4, 0.9) * Complex(0.4, 0.9) * scale};
  for (int it = 0; it < 500; ++it)
    for (int i = 0; i < 3; ++i) {
      Complex denominator = 1.0;
      for (int j = 0; j < 3; ++j)
        if (j != i) denominator *= z[i] - z[j];
      z[i] -= poly(z[i]) / denominator;
    }
  for (Complex &x : z)
    for (int it = 0; it < 3; ++it) x -= poly(x) / dpoly(x);
  return z;
}

// w with w^T M = lambda w^T: orthogonal (without conjugation) to the columns of M - lambda.
inline std::vector<Complex> left_eigenvector(const Matrix &M, Complex lambda)
{
  const size_t n = M.size();
  Matrix X = M;
  for (size_t i = 0; i < n; ++i) X[i][i] -= lambda;
  if (n == 2) {
    const std::vector<Complex> a = {X[1][0], -X[0][0]}, b = {-X[1][1], X[0][1]};
    return std::abs(a[0]) + std::abs(a[1]) >= std::abs(b[0]) + std::abs(b[1]) ? a : b;
  }
  std::vector<Complex> best(3);
  double best_norm = -1.0;
  for (int c1 = 0; c1 < 3; ++c1)
    for (int c2 = c1 + 1; c2 < 3; ++c2) {
      const std::vector<Complex> w = {X[1][c1] * X[2][c2] - X[2][c1] * X[1][c2],
                                      X[2][c1] * X[0][c2] - X[0][c1] * X[2][c2],
                                      X[0][c1] * X[1][c2] - X[1][c1] * X[0][c2]};
      const double norm = std::abs(w[0]) + std::abs(w[1]) + std::abs(w[2]);
      if (norm > best_norm) best = w, best_norm = norm;
    }
  return best;
}

}  // namespace ActiveGrain::Continuum::testing
