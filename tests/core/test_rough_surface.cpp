// The rough plate's height field: the asked rms slope, a correlation length, slopes that are the
// derivatives of the heights, continuity, periodicity, and reproducibility from the seed alone.
#include "ag_rough_surface.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using ActiveGrain::RoughSurface;
using ActiveGrain::SurfacePoint;

namespace {
constexpr double SLOPE = 0.02, LENGTH = 1.0e-3;

// Mean of |grad h|^2 and of h^2 over n random points of a large patch.
void sample_moments(const RoughSurface &s, int n, double &slope_sq, double &height_sq)
{
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-500.0 * LENGTH, 500.0 * LENGTH);
  slope_sq = height_sq = 0.0;
  for (int k = 0; k < n; ++k) {
    const SurfacePoint p = s.at(U(rng), U(rng));
    slope_sq += p.slope_x * p.slope_x + p.slope_y * p.slope_y;
    height_sq += p.height * p.height;
  }
  slope_sq /= n;
  height_sq /= n;
}
}    // namespace

TEST(RoughSurface, FlatByDefaultAndAtZeroSlope)
{
  for (const RoughSurface &s : {RoughSurface(), RoughSurface(0.0, LENGTH, 1)}) {
    EXPECT_TRUE(s.flat());
    const SurfacePoint p = s.at(0.3e-3, -2.1e-3);
    EXPECT_EQ(p.height, 0.0);
    EXPECT_EQ(p.slope_x, 0.0);
    EXPECT_EQ(p.slope_y, 0.0);
    EXPECT_EQ(p.normal_up().z, 1.0);
  }
}

TEST(RoughSurface, RmsSlopeAndHeightAreTheAskedAndPredictedOnes)
{
  const RoughSurface s(SLOPE, LENGTH, 42);
  double slope_sq, height_sq;
  sample_moments(s, 400000, slope_sq, height_sq);
  EXPECT_NEAR(std::sqrt(slope_sq), SLOPE, 0.02 * SLOPE);
  EXPECT_NEAR(std::sqrt(height_sq), s.rms_height(), 0.02 * s.rms_height());
  // Small tilts: the rms angle of the normal is the rms slope.
  EXPECT_NEAR(std::acos(s.at(0.1e-3, 0.2e-3).normal_up().z),
              std::atan(std::hypot(s.at(0.1e-3, 0.2e-3).slope_x, s.at(0.1e-3, 0.2e-3).slope_y)), 1e-12);
}

TEST(RoughSurface, HeightAndTiltStayWithinTheirBounds)
{
  // fix wall/impulse skips atoms that cannot reach a plate within a step from these bounds,
  // without evaluating the surface: they must hold everywhere, and be tight enough to be of use.
  const RoughSurface s(0.06, 5e-6, 3), flat;
  EXPECT_EQ(flat.max_height(), 0.0);
  EXPECT_EQ(flat.min_normal_z(), 1.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-2e-3, 2e-3);
  double highest = 0.0, lowest_nz = 1.0;
  for (int k = 0; k < 400000; ++k) {
    const SurfacePoint p = s.at(U(rng), U(rng));
    highest = std::max(highest, std::fabs(p.height));
    lowest_nz = std::min(lowest_nz, p.normal_up().z);
  }
  std::printf("[ measured ] largest |h| %.3g of its bound %.3g; smallest normal z %.5f, bound %.5f\n",
              highest, s.max_height(), lowest_nz, s.min_normal_z());
  EXPECT_LE(highest, s.max_height());
  EXPECT_GT(highest, 0.5 * s.max_height());
  EXPECT_GE(lowest_nz, s.min_normal_z());
  EXPECT_LT(1.0 - lowest_nz, 1.0 - s.min_normal_z());
  EXPECT_GT(1.0 - lowest_nz, 0.1 * (1.0 - s.min_normal_z()));
}

TEST(RoughSurface, SlopesAreTheDerivativesOfTheHeight)
{
  const RoughSurface s(SLOPE, LENGTH, 3);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(-20.0 * LENGTH, 20.0 * LENGTH);
  const double h = 1e-4 * LENGTH;
  for (int k = 0; k < 1000; ++k) {
    const double x = U(rng), y = U(rng);
    const SurfacePoint p = s.at(x, y);
    const double dx = (s.at(x + h, y).height - s.at(x - h, y).height) / (2 * h);
    const double dy = (s.at(x, y + h).height - s.at(x, y - h).height) / (2 * h);
    EXPECT_NEAR(p.slope_x, dx, 5e-4 * SLOPE);
    EXPECT_NEAR(p.slope_y, dy, 5e-4 * SLOPE);
  }
}

TEST(RoughSurface, ContinuousAcrossCellEdges)
{
  const RoughSurface s(SLOPE, LENGTH, 5);
  for (int i = -5; i <= 5; ++i) {
    const double edge = i * s.spacing_x(), eps = 1e-9 * LENGTH;
    const SurfacePoint a = s.at(edge - eps, 0.37e-3), b = s.at(edge + eps, 0.37e-3);
    EXPECT_NEAR(a.height, b.height, 1e-6 * s.rms_height());
    EXPECT_NEAR(a.slope_x, b.slope_x, 1e-6 * SLOPE);
    EXPECT_NEAR(a.slope_y, b.slope_y, 1e-6 * SLOPE);
  }
}

TEST(RoughSurface, SlopesDecorrelateBeyondTheCorrelationLength)
{
  const RoughSurface s(SLOPE, LENGTH, 9);
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> U(-300.0 * LENGTH, 300.0 * LENGTH);
  auto correlation = [&](double shift) {
    double ab = 0, aa = 0, bb = 0;
    for (int k = 0; k < 100000; ++k) {
      const double x = U(rng), y = U(rng);
      const double a = s.at(x, y).slope_x, b = s.at(x + shift, y).slope_x;
      ab += a * b;
      aa += a * a;
      bb += b * b;
    }
    return ab / std::sqrt(aa * bb);
  };
  EXPECT_GT(correlation(0.05 * LENGTH), 0.9);
  EXPECT_LT(std::fabs(correlation(3.0 * LENGTH)), 0.02);
}

TEST(RoughSurface, SameSeedSameSurfaceOtherSeedAnother)
{
  const RoughSurface a(SLOPE, LENGTH, 1), b(SLOPE, LENGTH, 1), c(SLOPE, LENGTH, 2);
  int differ = 0;
  for (int k = 0; k < 100; ++k) {
    const double x = 0.37e-3 * k, y = -0.23e-3 * k;
    EXPECT_EQ(a.at(x, y).height, b.at(x, y).height);
    differ += a.at(x, y).height != c.at(x, y).height;
  }
  EXPECT_GT(differ, 95);
}

TEST(RoughSurface, PeriodicDirectionsRepeatWithTheBox)
{
  const double Lx = 80.3e-3, Ly = 12.1e-3;
  const RoughSurface s(SLOPE, LENGTH, 17, Lx, Ly);
  EXPECT_NEAR(Lx / s.spacing_x(), std::round(Lx / LENGTH), 1e-9);
  for (int k = 0; k < 50; ++k) {
    const double x = 0.77e-3 * k, y = 0.31e-3 * k;
    const SurfacePoint p = s.at(x, y), q = s.at(x + Lx, y - 2 * Ly);
    EXPECT_NEAR(p.height, q.height, 1e-12 * s.rms_height());
    EXPECT_NEAR(p.slope_x, q.slope_x, 1e-9 * SLOPE);
    EXPECT_NEAR(p.slope_y, q.slope_y, 1e-9 * SLOPE);
  }
}
