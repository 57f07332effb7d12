#include "ag_rough_surface.h"

#include "ag_hash.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// The blend weight f(t) = 6t^5 - 15t^4 + 10t^3 and its derivative: C2 across cell edges, so
// slopes (hence contact normals) change continuously as a grain slides.
double fade(double t) { return t * t * t * (t * (6.0 * t - 15.0) + 10.0); }
double fade_slope(double t) { return 30.0 * t * t * (t - 1.0) * (t - 1.0); }

// Statistics of unit value noise N (node values uniform in [-1, 1), variance 1/3), averaged over a
// cell: <f^2> = 181/462, <f'^2> = 10/7 (exact integrals), and <(1-f)^2 + f^2> = 2 <f^2>. Hence
//   <(dN/du)^2> = <f'^2> * 2 var * 2 <f^2>       (per lattice direction u)
//   <N^2>       = var * (2 <f^2>)^2
constexpr double NODE_VARIANCE = 1.0 / 3.0;
constexpr double BLEND_SQUARE = 2.0 * 181.0 / 462.0;
constexpr double SLOPE_VARIANCE = (10.0 / 7.0) * 2.0 * NODE_VARIANCE * BLEND_SQUARE;
constexpr double HEIGHT_VARIANCE = NODE_VARIANCE * BLEND_SQUARE * BLEND_SQUARE;
// Where in a cell the blend is steepest: f' peaks mid-cell.
constexpr double STEEPEST_FADE = 0.5;

std::int64_t wrap(std::int64_t i, std::int64_t n)
{
  if (n <= 0) return i;
  const std::int64_t r = i % n;
  return r < 0 ? r + n : r;
}

}    // namespace

Vec3 SurfacePoint::normal_up() const
{
  if (slope_x == 0.0 && slope_y == 0.0) return {0.0, 0.0, 1.0};    // flat: the common case
  const Vec3 n(-slope_x, -slope_y, 1.0);
  return n / norm(n);
}

RoughSurface::RoughSurface(double rms_slope, double correlation_length, std::uint64_t seed,
                           double period_x, double period_y) :
    hash_seed(seed)
{
  if (rms_slope <= 0.0) return;
  auto lattice = [&](double period, double &spacing, std::int64_t &cells) {
    spacing = correlation_length;
    if (period <= 0.0) return;
    cells = std::max<std::int64_t>(1, std::llround(period / correlation_length));
    spacing = period / static_cast<double>(cells);
  };
  lattice(period_x, lattice_x, cells_x);
  lattice(period_y, lattice_y, cells_y);
  // <|grad h|^2> = amplitude^2 <(dN/du)^2> (1/sx^2 + 1/sy^2) = rms_slope^2
  amplitude = rms_slope /
      std::sqrt(SLOPE_VARIANCE * (1.0 / (lattice_x * lattice_x) + 1.0 / (lattice_y * lattice_y)));
  // h blends node heights in [-amplitude, amplitude) with weights in [0, 1], so |h| <= amplitude;
  // along each lattice direction the slope is at most max f' = 15/8 times a node difference (at
  // most 2 amplitude) over the spacing.
  const double steepest = fade_slope(STEEPEST_FADE) * 2.0 * amplitude;
  const double slope_x = steepest / lattice_x, slope_y = steepest / lattice_y;
  normal_z_bound = 1.0 / std::sqrt(1.0 + slope_x * slope_x + slope_y * slope_y);
}

double RoughSurface::rms_height() const { return amplitude * std::sqrt(HEIGHT_VARIANCE); }

double RoughSurface::node_height(std::int64_t i, std::int64_t j) const
{
  return amplitude *
      uniform_symmetric(hash_words({hash_seed, static_cast<std::uint64_t>(wrap(i, cells_x)),
                                    static_cast<std::uint64_t>(wrap(j, cells_y))}));
}

SurfacePoint RoughSurface::at(double x, double y) const
{
  SurfacePoint p;
  if (flat()) return p;
  const double u = x / lattice_x, v = y / lattice_y;
  const double iu = std::floor(u), iv = std::floor(v);
  const double tu = u - iu, tv = v - iv;
  const auto i = static_cast<std::int64_t>(iu), j = static_cast<std::int64_t>(iv);
  const double h00 = node_height(i, j), h10 = node_height(i + 1, j);
  const double h01 = node_height(i, j + 1), h11 = node_height(i + 1, j + 1);
  const double fu = fade(tu), fv = fade(tv);
  const double lower = h00 + fu * (h10 - h00), upper = h01 + fu * (h11 - h01);
  p.height = lower + fv * (upper - lower);
  p.slope_x = fade_slope(tu) * ((1.0 - fv) * (h10 - h00) + fv * (h11 - h01)) / lattice_x;
  p.slope_y = fade_slope(tv) * (upper - lower) / lattice_y;
  return p;
}

}    // namespace ActiveGrain
