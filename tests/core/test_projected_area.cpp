// The shares of a disc chain's union area: exact for known shapes, and they add up to the union.
#include "ag_math.h"
#include "ag_projected_area.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <random>

using ActiveGrain::disc_chain_area_shares;
using ActiveGrain::PI;

namespace {
double total(const std::vector<double> &v) { return std::accumulate(v.begin(), v.end(), 0.0); }

// Union area by midpoint quadrature across the axis: at each x the union's cross-section is the
// union of the discs' chords, which are intervals centred on the axis, so the widest one.
double union_area_numeric(const std::vector<double> &c, const std::vector<double> &r)
{
  double xmin = 1e300, xmax = -1e300;
  for (std::size_t k = 0; k < c.size(); ++k) {
    xmin = std::min(xmin, c[k] - r[k]);
    xmax = std::max(xmax, c[k] + r[k]);
  }
  const int n = 400000;
  const double h = (xmax - xmin) / n;
  double area = 0;
  for (int i = 0; i < n; ++i) {
    const double x = xmin + (i + 0.5) * h;
    double half = 0;
    for (std::size_t k = 0; k < c.size(); ++k) {
      const double d = x - c[k];
      if (std::fabs(d) < r[k]) half = std::max(half, std::sqrt(r[k] * r[k] - d * d));
    }
    area += 2 * half * h;
  }
  return area;
}
}    // namespace

TEST(ProjectedArea, SingleDiscIsPiRSquared)
{
  auto s = disc_chain_area_shares({0.3}, {0.55});
  ASSERT_EQ(s.size(), 1u);
  EXPECT_NEAR(s[0], PI * 0.55 * 0.55, 1e-14);
}

TEST(ProjectedArea, SeparateDiscsKeepTheirArea)
{
  auto s = disc_chain_area_shares({0.0, 3.0}, {1.0, 0.5});
  EXPECT_NEAR(s[0], PI, 1e-14);
  EXPECT_NEAR(s[1], PI * 0.25, 1e-14);
}

TEST(ProjectedArea, TwoEqualDiscsSplitTheLensEvenly)
{
  const double r = 1.0, d = 1.2;
  // Lens of two unit discs at distance d: 2 r^2 acos(d/2r) - (d/2) sqrt(4r^2 - d^2).
  const double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
  auto s = disc_chain_area_shares({0.0, d}, {r, r});
  EXPECT_NEAR(s[0], s[1], 1e-14);
  EXPECT_NEAR(total(s), 2 * PI * r * r - lens, 1e-12);
}

TEST(ProjectedArea, DiscInsideAnotherAddsNothing)
{
  auto s = disc_chain_area_shares({0.0, 0.2}, {1.0, 0.3});
  EXPECT_NEAR(s[1], 0.0, 1e-14);
  EXPECT_NEAR(total(s), PI, 1e-14);
  auto same = disc_chain_area_shares({0.5, 0.5}, {0.4, 0.4});
  EXPECT_NEAR(total(same), PI * 0.16, 1e-14);
}

TEST(ProjectedArea, TaperedRodChainMatchesTheUnion)
{
  // The paper's rod: 4.5 long, 1.1 to 0.7 wide, as 9 overlapping spheres.
  std::vector<double> c, r;
  const int n = 9;
  for (int k = 0; k < n; ++k) {
    const double rk = 0.55 - 0.2 * k / (n - 1);
    r.push_back(rk);
    c.push_back(0.55 + k * (4.5 - 0.55 - 0.35) / (n - 1));
  }
  auto s = disc_chain_area_shares(c, r);
  EXPECT_NEAR(total(s), union_area_numeric(c, r), 1e-6);
  for (double share : s) EXPECT_GT(share, 0.0);
  EXPECT_LT(total(s), std::accumulate(r.begin(), r.end(), 0.0, [](double a, double x) { return a + PI * x * x; }));
}

TEST(ProjectedArea, RandomChainsAddUpToTheUnion)
{
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> pos(0.0, 5.0), rad(0.1, 1.0);
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 2 + trial % 7;
    std::vector<double> c(n), r(n);
    for (int k = 0; k < n; ++k) { c[k] = pos(rng); r[k] = rad(rng); }
    std::sort(c.begin(), c.end());
    auto s = disc_chain_area_shares(c, r);
    for (double share : s) EXPECT_GE(share, 0.0);
    EXPECT_NEAR(total(s), union_area_numeric(c, r), 1e-5) << "trial " << trial;
  }
}

TEST(RodChain, AxisPointsFromTailToNoseWhateverTheOrder)
{
  using ActiveGrain::Vec3;
  const Vec3 p(std::cos(0.7), std::sin(0.7), 0.0);
  std::vector<Vec3> x;
  std::vector<double> r;
  for (int k : {3, 0, 4, 1, 2}) {   // shuffled constituents
    x.push_back(Vec3(1, 2, 0.5) + p * (0.5 * k));
    r.push_back(0.55 - 0.05 * k);
  }
  auto rod = ActiveGrain::project_rod_chain(x, r);
  EXPECT_NEAR(rod.axis.x, p.x, 1e-12);
  EXPECT_NEAR(rod.axis.y, p.y, 1e-12);
  EXPECT_NEAR(rod.axis.z, 0.0, 1e-12);
  // Same shares as the chain laid out along a line.
  std::vector<double> s;
  for (int k : {3, 0, 4, 1, 2}) s.push_back(0.5 * k);
  auto expected = disc_chain_area_shares(s, r);
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_NEAR(rod.shares[k], expected[k], 1e-12);
}

TEST(RodChain, TiltShortensTheProjection)
{
  using ActiveGrain::Vec3;
  std::vector<Vec3> flat, tilted;
  std::vector<double> r = {0.5, 0.45, 0.4};
  const double tilt = 0.3;
  for (int k = 0; k < 3; ++k) {
    flat.emplace_back(0.6 * k, 0, 0);
    tilted.emplace_back(0.6 * k * std::cos(tilt), 0, 0.6 * k * std::sin(tilt));
  }
  const double a_flat = total(ActiveGrain::project_rod_chain(flat, r).shares);
  const double a_tilt = total(ActiveGrain::project_rod_chain(tilted, r).shares);
  std::vector<double> s;
  for (int k = 0; k < 3; ++k) s.push_back(0.6 * k * std::cos(tilt));
  EXPECT_LT(a_tilt, a_flat);
  EXPECT_NEAR(a_tilt, total(disc_chain_area_shares(s, r)), 1e-12);
  EXPECT_NEAR(ActiveGrain::project_rod_chain(tilted, r).axis.z, std::sin(tilt), 1e-12);
}

TEST(RodChain, UntaperedChainHasNoPolarAxis)
{
  using ActiveGrain::Vec3;
  auto rod = ActiveGrain::project_rod_chain({Vec3(0, 0, 0), Vec3(1, 0, 0)}, {0.5, 0.5});
  EXPECT_EQ(norm2(rod.axis), 0.0);
  EXPECT_EQ(norm2(rod.polar), 0.0);
  EXPECT_GT(total(rod.shares), PI * 0.25);
}

// The polarization seen from above: a tilted rod's polar axis is its in-plane direction, of
// unit length whatever the tilt (the 3-D axis keeps the tilt).
TEST(RodChain, PolarAxisIsTheUnitInPlaneDirection)
{
  using ActiveGrain::Vec3;
  const double tilt = 0.2, heading = -2.4;
  const Vec3 along(std::cos(tilt) * std::cos(heading), std::cos(tilt) * std::sin(heading), std::sin(tilt));
  std::vector<Vec3> x;
  for (int k = 0; k < 4; ++k) x.push_back(Vec3(3, -1, 0.5) + along * (0.4 * k));
  auto rod = ActiveGrain::project_rod_chain(x, {0.55, 0.5, 0.45, 0.35});
  EXPECT_NEAR(rod.polar.x, std::cos(heading), 1e-12);
  EXPECT_NEAR(rod.polar.y, std::sin(heading), 1e-12);
  EXPECT_EQ(rod.polar.z, 0.0);
  EXPECT_NEAR(rod.axis.z, std::sin(tilt), 1e-12);
}
