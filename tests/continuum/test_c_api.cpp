// The C interface: status codes and messages that name the parameter, and a state round trip.
#include "activegrain_continuum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace {

ag_continuum_config valid_config()
{
  ag_continuum_config c{};
  c.dim = 1, c.nx = 32, c.ny = 1, c.lx = 10.0, c.ly = 1.0, c.dt = 1e-2;
  c.D_rho = 0.1, c.D_sigma = 0.1, c.D_rho_sigma = 0.0, c.D_sigma_rho = 0.0;
  c.alpha = 1.0, c.u0 = 1.0, c.A = 1.0, c.B = 0.0, c.a = 1.0, c.K = 1.0, c.tau = 0.0;
  return c;
}

std::string create_error(const ag_continuum_config &c)
{
  ag_continuum *s = nullptr;
  const int status = ag_continuum_create(&c, &s);
  EXPECT_EQ(status, AG_CONTINUUM_BAD_ARGUMENT);
  EXPECT_EQ(s, nullptr);
  return ag_continuum_last_error();
}

}  // namespace

TEST(CInterface, BadParametersAreNamed)
{
  EXPECT_EQ(ag_continuum_abi_version(), AG_CONTINUUM_ABI_VERSION);
  ag_continuum_config c = valid_config();
  c.dt = 0;
  EXPECT_EQ(create_error(c).rfind("dt:", 0), 0u);
  c = valid_config(), c.dim = 3;
  EXPECT_EQ(create_error(c).rfind("dim:", 0), 0u);
  c = valid_config(), c.nx = 2;
  EXPECT_EQ(create_error(c).rfind("nx:", 0), 0u);
  c = valid_config(), c.a = -1;
  EXPECT_EQ(create_error(c).rfind("a:", 0), 0u);
  c = valid_config(), c.tau = -1;
  EXPECT_EQ(create_error(c).rfind("tau:", 0), 0u);
  c = valid_config(), c.K = NAN;
  EXPECT_EQ(create_error(c).rfind("parameters:", 0), 0u);
  // the paper's limit D_rho = D_sigma = D_sigma_rho = 0 is ill-posed: refused
  c = valid_config(), c.D_rho = c.D_sigma = 0, c.D_rho_sigma = 1;
  const std::string message = create_error(c);
  EXPECT_EQ(message.rfind("D_rho, D_sigma", 0), 0u);
  EXPECT_NE(message.find("ill-posed"), std::string::npos);
}

TEST(CInterface, StateRoundTripAndMisuse)
{
  const ag_continuum_config c = valid_config();
  ag_continuum *s = nullptr;
  ASSERT_EQ(ag_continuum_create(&c, &s), AG_CONTINUUM_OK);
  EXPECT_EQ(ag_continuum_step(s, 1), AG_CONTINUUM_BAD_ARGUMENT);   // no state yet
  EXPECT_NE(std::string(ag_continuum_last_error()).find("set_state"), std::string::npos);

  std::vector<double> rho(c.nx), sigma(c.nx), P(c.nx), back(c.nx), sigma_back(c.nx);
  for (int i = 0; i < c.nx; ++i) {   // band-limited (modes 0..3 of 10 kept): survives dealiasing
    rho[i] = 1.0 + 0.1 * std::cos(2 * M_PI * 3 * i / c.nx);
    sigma[i] = 0.5 + 0.1 * std::sin(2 * M_PI * i / c.nx);
  }
  EXPECT_EQ(ag_continuum_set_state(s, rho.data(), sigma.data(), P.data()), AG_CONTINUUM_BAD_ARGUMENT);
  EXPECT_EQ(std::string(ag_continuum_last_error()).rfind("P:", 0), 0u);
  ASSERT_EQ(ag_continuum_set_state(s, rho.data(), sigma.data(), nullptr), AG_CONTINUUM_OK);
  ASSERT_EQ(ag_continuum_get_state(s, back.data(), sigma_back.data(), P.data()), AG_CONTINUUM_OK);
  for (int i = 0; i < c.nx; ++i) {
    EXPECT_NEAR(back[i], rho[i], 1e-14);
    EXPECT_NEAR(sigma_back[i], sigma[i], 1e-14);
    // slaved P of rho's single wave: A d/dx rho / (a + K k^2)
    const double k = 2 * M_PI * 3 / c.lx;
    EXPECT_NEAR(P[i], -0.1 * k * std::sin(2 * M_PI * 3 * i / c.nx) / (c.a + c.K * k * k), 1e-14);
  }
  ASSERT_EQ(ag_continuum_step(s, 10), AG_CONTINUUM_OK);
  double t = 0;
  ASSERT_EQ(ag_continuum_time(s, &t), AG_CONTINUUM_OK);
  EXPECT_NEAR(t, 10 * c.dt, 1e-15);
  rho[0] = NAN;
  EXPECT_EQ(ag_continuum_set_state(s, rho.data(), sigma.data(), nullptr), AG_CONTINUUM_BAD_ARGUMENT);
  ag_continuum_destroy(s);
}

TEST(CInterface, BlowUpIsReportedNotReturned)
{
  ag_continuum_config c = valid_config();
  c.dt = 0.2;   // far too large a step for the explicit terms of this strongly unstable state
  c.D_rho = c.D_sigma = 0.01;
  c.alpha = c.u0 = 5.0;
  ag_continuum *s = nullptr;
  ASSERT_EQ(ag_continuum_create(&c, &s), AG_CONTINUUM_OK);
  std::vector<double> rho(c.nx), sigma(c.nx);
  for (int i = 0; i < c.nx; ++i) rho[i] = 1.0 + 0.5 * std::cos(2 * M_PI * i / c.nx), sigma[i] = 1.0;
  ASSERT_EQ(ag_continuum_set_state(s, rho.data(), sigma.data(), nullptr), AG_CONTINUUM_OK);
  EXPECT_EQ(ag_continuum_step(s, 2000), AG_CONTINUUM_NOT_FINITE);
  EXPECT_NE(std::string(ag_continuum_last_error()).find("smaller dt"), std::string::npos);
  ag_continuum_destroy(s);
}
