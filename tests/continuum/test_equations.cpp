// The solver integrates the paper's equations 1-5 themselves, nonlinear terms included:
// from fields that are a few Fourier modes, one tiny first step (u1 - u0)/dt matches d/dt of
// rho, sigma (and P when it relaxes) evaluated here by hand with exact derivatives.
#include "continuum_solver.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace ActiveGrain::Continuum;

namespace {

constexpr double PI = 3.14159265358979323846;

// c cos(k.x + phase)
struct Wave {
  double c, kx, ky, phase;
};

struct Point {
  double value = 0, dx = 0, dy = 0, lap = 0;
};

Point evaluate(const std::vector<Wave> &waves, double x, double y)
{
  Point p;
  for (const Wave &w : waves) {
    const double arg = w.kx * x + w.ky * y + w.phase;
    p.value += w.c * std::cos(arg);
    p.dx -= w.c * w.kx * std::sin(arg);
    p.dy -= w.c * w.ky * std::sin(arg);
    p.lap -= w.c * (w.kx * w.kx + w.ky * w.ky) * std::cos(arg);
  }
  return p;
}

// the slaved P = (a - K lap)^{-1} (A grad rho + B grad sigma), wave by wave
std::vector<Wave> slaved(const std::vector<Wave> &waves, double coupling, const ModelParameters &p, bool x_component)
{
  std::vector<Wave> out;
  for (const Wave &w : waves) {   // d/dx c cos(arg) = c kx cos(arg + pi/2)
    const double k2 = w.kx * w.kx + w.ky * w.ky;
    out.push_back({coupling * w.c * (x_component ? w.kx : w.ky) / (p.a + p.K * k2), w.kx, w.ky, w.phase + PI / 2});
  }
  return out;
}

// D_rho(rho) with close packing: D_rho times Henderson's dPi/drho (theory.HendersonEOS.stiffness)
// at eta = rho/rho_close, over its value at the mean
double henderson_stiffness(double eta)
{
  return (1 + eta * eta / 8) / std::pow(1 - eta, 2) + eta * (eta / 4) / std::pow(1 - eta, 2) +
         eta * 2 * (1 + eta * eta / 8) / std::pow(1 - eta, 3);
}

double bead_diffusivity(const ModelParameters &p, double rho, double rho0)
{
  if (p.rho_close == 0) return p.D_rho;
  return p.D_rho * henderson_stiffness(rho / p.rho_close) / henderson_stiffness(rho0 / p.rho_close);
}

double bead_diffusivity_slope(const ModelParameters &p, double rho, double rho0)
{
  const double h = 1e-6;
  return (bead_diffusivity(p, rho + h, rho0) - bead_diffusivity(p, rho - h, rho0)) / (2 * h);
}

// refine: grid points per direction times this (the products of the few modes need none, but
// D_rho(rho) of close packing is no polynomial: its spectrum must decay inside the grid's band)
void check_first_step(const ModelParameters &p, int refine = 1, double tolerance = 1e-6)
{
  Grid g;
  g.dim = 2, g.nx = 32 * refine, g.ny = 24 * refine, g.lx = 10.0, g.ly = 7.0;
  const double kx = 2 * PI / g.lx, ky = 2 * PI / g.ly;
  const double rho0 = 1.0, sigma0 = 0.4;
  const std::vector<Wave> rho_waves = {{0.2, kx, 0, 0.3}, {0.1, 2 * kx, -ky, 1.1}, {0.05, 0, 3 * ky, -0.4}};
  const std::vector<Wave> sigma_waves = {{0.1, kx, 2 * ky, 0.7}, {0.07, 3 * kx, ky, 2.0}};
  const bool relaxed = p.tau > 0;
  // a relaxing P starts away from its slaved value
  std::vector<Wave> px = {{0.05, 2 * kx, ky, 0.2}, {0.03, kx, -2 * ky, 1.4}}, py = {{0.04, kx, 3 * ky, -1.0}};
  if (!relaxed) {
    px = slaved(rho_waves, p.A, p, true), py = slaved(rho_waves, p.A, p, false);
    for (const Wave &w : slaved(sigma_waves, p.B, p, true)) px.push_back(w);
    for (const Wave &w : slaved(sigma_waves, p.B, p, false)) py.push_back(w);
  }
  const int n = g.num_points();
  std::vector<double> rho(n), sigma(n), P(2 * n), rho_rate(n), sigma_rate(n), P_rate(2 * n);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      const double x = g.lx * i / g.nx, y = g.ly * j / g.ny;
      const int at = j * g.nx + i;
      const Point r = evaluate(rho_waves, x, y), s = evaluate(sigma_waves, x, y);
      const Point Px = evaluate(px, x, y), Py = evaluate(py, x, y);
      rho[at] = rho0 + r.value, sigma[at] = sigma0 + s.value, P[at] = Px.value, P[n + at] = Py.value;
      const double div_P = Px.dx + Py.dy;
      // d rho/dt = -div J_rho, J_rho = -D(rho) grad rho - D_rho_sigma c_rho grad sigma + alpha rho P
      const double grads = r.dx * s.dx + r.dy * s.dy;
      const double D = bead_diffusivity(p, rho[at], rho0), dD = bead_diffusivity_slope(p, rho[at], rho0);
      const double cross_rho = p.proportional_cross_diffusion ? (grads + rho[at] * s.lap) / rho0 : s.lap;
      const double cross_sigma = p.proportional_cross_diffusion ? (grads + sigma[at] * r.lap) / sigma0 : r.lap;
      rho_rate[at] = D * r.lap + dD * (r.dx * r.dx + r.dy * r.dy) + p.D_rho_sigma * cross_rho -
                     p.alpha * (r.dx * Px.value + r.dy * Py.value + rho[at] * div_P);
      sigma_rate[at] = p.D_sigma_rho * cross_sigma + p.D_sigma * s.lap -
                       p.u0 * (s.dx * Px.value + s.dy * Py.value + sigma[at] * div_P);
      // tau dP/dt = -(a - K lap) P + A grad rho + B grad sigma
      P_rate[at] = (-(p.a * Px.value - p.K * Px.lap) + p.A * r.dx + p.B * s.dx) / p.tau;
      P_rate[n + at] = (-(p.a * Py.value - p.K * Py.lap) + p.A * r.dy + p.B * s.dy) / p.tau;
    }
  const double dt = 1e-8;
  Solver solver(g, p, dt);
  solver.set_state(rho.data(), sigma.data(), relaxed ? P.data() : nullptr);
  std::vector<double> rho1(n), sigma1(n), P1(2 * n), P0(2 * n);
  solver.get_state(nullptr, nullptr, P0.data());
  solver.step(1);
  solver.get_state(rho1.data(), sigma1.data(), P1.data());
  double scale = 0, worst = 0;
  for (int at = 0; at < n; ++at) {
    scale = std::max({scale, std::abs(rho_rate[at]), std::abs(sigma_rate[at])});
    worst = std::max({worst, std::abs((rho1[at] - rho[at]) / dt - rho_rate[at]),
                      std::abs((sigma1[at] - sigma[at]) / dt - sigma_rate[at])});
    if (!relaxed) {   // the solver's slaved P is the one written out here
      EXPECT_NEAR(P0[at], P[at], 1e-14);
      EXPECT_NEAR(P0[n + at], P[n + at], 1e-14);
    }
  }
  if (relaxed)
    for (int at = 0; at < 2 * n; ++at) EXPECT_NEAR((P1[at] - P[at]) / dt, P_rate[at], 1e-5 * std::abs(P_rate[at]) + 1e-6);
  EXPECT_GT(scale, 0.05);
  EXPECT_LT(worst, tolerance * scale);
}

ModelParameters parameters(double tau, bool proportional = false)
{
  ModelParameters p;
  p.proportional_cross_diffusion = proportional;
  p.D_rho = 0.3, p.D_sigma = 0.2, p.D_rho_sigma = 0.4, p.D_sigma_rho = 0.1;
  p.alpha = 1.3, p.u0 = 0.7, p.A = 1.1, p.B = -0.6, p.a = 1.5, p.K = 0.8, p.tau = tau;
  return p;
}

}  // namespace

TEST(Equations, FirstStepMatchesRightHandSideSlaved) { check_first_step(parameters(0.0)); }

TEST(Equations, FirstStepMatchesRightHandSideRelaxed) { check_first_step(parameters(0.4)); }

TEST(Equations, FirstStepMatchesRightHandSideProportionalCrossDiffusion)
{
  check_first_step(parameters(0.0, true));
  check_first_step(parameters(0.4, true));
}

TEST(Equations, FirstStepMatchesRightHandSideClosePacking)
{
  ModelParameters p = parameters(0.0, true);
  p.rho_close = 1.6;   // rho spans 0.65 to 1.35 at the start: D_rho(rho) from 0.2 to 16 times D_rho
  check_first_step(p, 4, 1e-5);   // what remains is aliasing of D_rho(rho) grad rho, 2e-6
  p.tau = 0.4;
  check_first_step(p, 4, 1e-5);
}
