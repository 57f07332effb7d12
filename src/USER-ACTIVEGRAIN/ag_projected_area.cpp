#include "ag_projected_area.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ActiveGrain {

namespace {
// Area of the part of a disc of radius r centred at c that lies left of the line x = a.
double disc_area_left_of(double a, double c, double r)
{
  const double u = std::clamp((a - c) / r, -1.0, 1.0);
  return r * r * (PI / 2 + std::asin(u) + u * std::sqrt(1.0 - u * u));
}
}    // namespace

std::vector<double> disc_chain_area_shares(const std::vector<double> &centres,
                                           const std::vector<double> &radii)
{
  const std::size_t n = centres.size();
  std::vector<double> shares(n, 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    // With collinear centres every power-diagram boundary is a line across the axis: disc k's
    // cell is the slab between the tightest radical lines with the discs on either side.
    double lo = -std::numeric_limits<double>::infinity();
    double hi = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j) {
      if (j == k) continue;
      const double ds = centres[k] - centres[j];
      if (ds == 0.0) {
        // Concentric: the larger disc owns the overlap; equal discs split it by index.
        if (radii[j] > radii[k] || (radii[j] == radii[k] && j < k)) hi = lo;
        continue;
      }
      const double radical = 0.5 * (centres[k] + centres[j]) +
          0.5 * (radii[j] * radii[j] - radii[k] * radii[k]) / ds;
      if (ds > 0) lo = std::max(lo, radical);
      else hi = std::min(hi, radical);
    }
    if (lo < hi) {
      const double c = centres[k], r = radii[k];
      shares[k] = disc_area_left_of(hi, c, r) - disc_area_left_of(lo, c, r);
    }
  }
  return shares;
}

}    // namespace ActiveGrain

namespace ActiveGrain {

RodChain project_rod_chain(const std::vector<Vec3> &centres, const std::vector<double> &radii)
{
  RodChain rod;
  const std::size_t n = centres.size();
  if (n == 0) return rod;
  std::size_t tail = 0, nose = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (radii[k] > radii[tail]) tail = k;
    if (radii[k] < radii[nose]) nose = k;
  }
  const Vec3 span = centres[nose] - centres[tail];
  if (radii[tail] > radii[nose] && norm2(span) > 0) rod.axis = span / norm(span);
  const Vec3 flat(rod.axis.x, rod.axis.y, 0.0);
  if (norm2(flat) > 0) rod.polar = flat / norm(flat);

  // Positions along the rod's projection on the plane: any in-plane direction through the
  // chain works, the widest-to-farthest sphere gives a well-defined one even without taper.
  std::size_t far = 0;
  double far2 = -1;
  for (std::size_t k = 0; k < n; ++k) {
    const Vec3 d = centres[k] - centres[tail];
    const double d2 = d.x * d.x + d.y * d.y;
    if (d2 > far2) { far2 = d2; far = k; }
  }
  Vec3 along = centres[far] - centres[tail];
  along.z = 0;
  const double len = norm(along);
  std::vector<double> s(n, 0.0);
  if (len > 0)
    for (std::size_t k = 0; k < n; ++k) s[k] = dot(centres[k] - centres[tail], along) / len;
  rod.shares = disc_chain_area_shares(s, radii);
  return rod;
}

}    // namespace ActiveGrain
