// Past onset, in the nonlinear regime: the mass of rho and sigma is conserved to round-off, and
// the solution converges with the time step (at second order, SBDF2) and with the grid
// (spectrally).
#include "continuum_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <utility>
#include <vector>

using namespace ActiveGrain::Continuum;

namespace {

constexpr double PI = 3.14159265358979323846;

ModelParameters non_reciprocal(double tau)
{
  ModelParameters p;
  p.D_rho = 0.05, p.D_sigma = 0.05, p.D_rho_sigma = 1.0, p.D_sigma_rho = 0.0;
  p.alpha = 1.0, p.u0 = 1.0, p.A = 1.0, p.B = 0.0, p.a = 1.0, p.K = 1.0, p.tau = tau;
  return p;
}

ModelParameters reciprocal(double tau)
{
  ModelParameters p;
  p.D_rho = 0.1, p.D_sigma = 0.1, p.D_rho_sigma = 0.05, p.D_sigma_rho = 0.02;
  p.alpha = 1.0, p.u0 = 1.0, p.A = 1.0, p.B = 0.5, p.a = 2.0, p.K = 1.0, p.tau = tau;
  return p;
}

// beads jam at 1.6 (the mean is 1): D_rho(rho) varies several-fold over the run
ModelParameters close_packed(ModelParameters p)
{
  p.rho_close = 1.6;
  return p;
}

struct Fields {
  std::vector<double> rho, sigma, P;
};

// A smooth start of a few long waves (no grid dependence: it is the same function on any grid).
Fields smooth_start(const Grid &g, double rho0, double sigma0, double amplitude)
{
  const int n = g.num_points();
  Fields f{std::vector<double>(n), std::vector<double>(n), std::vector<double>(static_cast<size_t>(g.dim) * n, 0.0)};
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = 2 * PI * i / g.nx, y = 2 * PI * j / g.ny;
      const double wave = std::cos(x) + 0.5 * std::sin(2 * x + 0.3) + (g.dim == 2 ? 0.7 * std::cos(y - x + 1.0) : 0.0);
      f.rho[static_cast<size_t>(j) * g.nx + i] = rho0 + amplitude * wave;
      f.sigma[static_cast<size_t>(j) * g.nx + i] = sigma0 + amplitude * (0.8 * std::sin(x + 0.5) + 0.3 * std::cos(3 * x));
    }
  return f;
}

Fields run(const Grid &g, const ModelParameters &p, double dt, double t_end, double amplitude)
{
  Solver solver(g, p, dt);
  Fields f = smooth_start(g, 1.0, 0.5, amplitude);
  solver.set_state(f.rho.data(), f.sigma.data(), p.tau > 0 ? f.P.data() : nullptr);
  solver.step(static_cast<int>(std::lround(t_end / dt)));
  solver.get_state(f.rho.data(), f.sigma.data(), f.P.data());
  return f;
}

// Largest difference at the coarse grid's points (the fine grid refines it by an integer factor).
double max_difference(const Fields &coarse, const Grid &gc, const Fields &fine, const Grid &gf)
{
  const int rx = gf.nx / gc.nx, ry = gc.dim == 2 ? gf.ny / gc.ny : 1;
  double worst = 0.0;
  for (int j = 0; j < gc.ny; ++j)
    for (int i = 0; i < gc.nx; ++i) {
      const size_t c = static_cast<size_t>(j) * gc.nx + i, f = static_cast<size_t>(j * ry) * gf.nx + i * rx;
      worst = std::max({worst, std::abs(coarse.rho[c] - fine.rho[f]), std::abs(coarse.sigma[c] - fine.sigma[f])});
    }
  return worst;
}

double max_deviation(const Fields &f, double rho0)
{
  double worst = 0.0;
  for (double v : f.rho) worst = std::max(worst, std::abs(v - rho0));
  return worst;
}

Grid line(int nx)
{
  Grid g;
  g.dim = 1, g.nx = nx, g.lx = 4 * PI;
  return g;
}

}  // namespace

TEST(Conservation, MassToRoundOffIn2DNonlinearRuns)
{
  for (double tau : {0.0, 0.3}) {
    Grid g;
    g.dim = 2, g.nx = 64, g.ny = 48, g.lx = 8 * PI, g.ly = 6 * PI;
    const ModelParameters p = non_reciprocal(tau);
    Solver solver(g, p, 2e-3);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(-0.05, 0.05);
    Fields f{std::vector<double>(g.num_points()), std::vector<double>(g.num_points()),
             std::vector<double>(2 * g.num_points())};
    for (double &v : f.rho) v = 1.0 + noise(rng);
    for (double &v : f.sigma) v = 0.5 + noise(rng);
    for (double &v : f.P) v = noise(rng);
    solver.set_state(f.rho.data(), f.sigma.data(), tau > 0 ? f.P.data() : nullptr);
    solver.get_state(f.rho.data(), f.sigma.data(), nullptr);
    const double rho_mass = std::accumulate(f.rho.begin(), f.rho.end(), 0.0);
    const double sigma_mass = std::accumulate(f.sigma.begin(), f.sigma.end(), 0.0);
    solver.step(3000);
    solver.get_state(f.rho.data(), f.sigma.data(), nullptr);
    const double deviation = max_deviation(f, 1.0);
    std::printf("tau %.1f: max |rho - rho0| %.3f at t = %.1f, mass changes %.2e %.2e\n", tau, deviation,
                solver.time(), std::accumulate(f.rho.begin(), f.rho.end(), 0.0) / rho_mass - 1,
                std::accumulate(f.sigma.begin(), f.sigma.end(), 0.0) / sigma_mass - 1);
    EXPECT_GT(deviation, 0.2);   // nonlinear by then
    EXPECT_NEAR(std::accumulate(f.rho.begin(), f.rho.end(), 0.0) / rho_mass, 1.0, 1e-13);
    EXPECT_NEAR(std::accumulate(f.sigma.begin(), f.sigma.end(), 0.0) / sigma_mass, 1.0, 1e-13);
  }
}

// Errors against a run with dt / 8 halve, quarter...: log2 of successive error ratios ~ 2.
TEST(Convergence, SecondOrderInTimeStep)
{
  const std::pair<const char *, ModelParameters> cases[] = {
      {"non-reciprocal, slaved", non_reciprocal(0.0)}, {"reciprocal, slaved", reciprocal(0.0)},
      {"non-reciprocal, relaxed", non_reciprocal(0.3)}, {"reciprocal, close packing", close_packed(reciprocal(0.0))}};
  for (const auto &[name, p] : cases) {
    const Grid g = line(64);
    const double t_end = 4.0, dt = 0.02;
    const Fields reference = run(g, p, dt / 16, t_end, 0.1);
    ASSERT_GT(max_deviation(reference, 1.0), 0.15) << "not nonlinear yet";
    std::vector<double> errors;
    for (double h : {dt, dt / 2, dt / 4})
      errors.push_back(max_difference(run(g, p, h, t_end, 0.1), g, reference, g));
    for (size_t i = 0; i + 1 < errors.size(); ++i) {
      const double order = std::log2(errors[i] / errors[i + 1]);
      std::printf("%s, dt %.4f: error %.3e, order %.2f\n", name, dt / (1 << i), errors[i], order);
      EXPECT_NEAR(order, 2.0, 0.25);
    }
  }
}

// The same smooth start on finer and finer grids: the differences to the finest fall faster
// than any power of the spacing, down to round-off.
TEST(Convergence, SpectralInGridSize)
{
  for (const ModelParameters &p : {non_reciprocal(0.0), non_reciprocal(0.3)}) {
    const double t_end = 4.0, dt = 5e-3;
    const Grid finest = line(192);
    const Fields reference = run(finest, p, dt, t_end, 0.1);
    ASSERT_GT(max_deviation(reference, 1.0), 0.15) << "not nonlinear yet";
    std::vector<double> errors;
    for (int n : {24, 32, 48, 64, 96}) {
      errors.push_back(max_difference(run(line(n), p, dt, t_end, 0.1), line(n), reference, finest));
      std::printf("tau %.1f n %d: error %.3e\n", p.tau, n, errors.back());
    }
    for (size_t i = 0; i + 1 < errors.size(); ++i) EXPECT_LT(errors[i + 1], errors[i]);
    // doubling the points: a method of order q gains 2^q; here far more, more with each doubling
    EXPECT_LT(errors[3], 1e-2 * errors[1]);   // 32 -> 64
    EXPECT_LT(errors[4], 1e-3 * errors[2]);   // 48 -> 96
    EXPECT_LT(errors[4], 1e-6);
  }
}
