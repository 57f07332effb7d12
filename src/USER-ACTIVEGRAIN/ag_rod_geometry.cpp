#include "ag_rod_geometry.h"

#include "ag_math.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ActiveGrain {

std::string rod_parameter_error(const RodParameters &p)
{
  if (!(p.length > 0.0)) return "length must be > 0";
  if (!(p.tail_diameter > 0.0)) return "tail diameter must be > 0";
  if (!(p.nose_diameter > 0.0)) return "nose diameter must be > 0";
  if (!(p.density > 0.0)) return "density must be > 0";
  if (p.nspheres < MIN_ROD_SPHERES)
    return "a rod needs at least " + std::to_string(MIN_ROD_SPHERES) + " spheres";
  if (std::max(p.tail_diameter, p.nose_diameter) >= p.length)
    return "length must exceed both diameters";
  return "";
}

RodGeometry rod_solid(const RodParameters &p)
{
  const double L = p.length, a = 0.5 * p.tail_diameter, b = 0.5 * p.nose_diameter;
  const double k = (b - a) / L;    // slope of the radius r(x) = a + k x

  // Closed forms for the frustum (integrals of pi r^2, pi r^2 x, pi r^4 / 2, pi r^2 x^2
  // over 0..L with r linear in x).
  RodGeometry g;
  const double s2 = a * a + a * b + b * b;
  g.volume = PI * L * s2 / 3.0;
  g.mass = p.density * g.volume;
  g.com = L * (a * a + 2.0 * a * b + 3.0 * b * b) / (4.0 * s2);
  const double s4 = a * a * a * a + a * a * a * b + a * a * b * b + a * b * b * b + b * b * b * b;
  g.inertia_axial = p.density * PI * L * s4 / 10.0;
  // Transverse: thin-disc term pi r^4 / 4 plus the parallel-axis term pi r^2 x^2 about the tail
  // face, then shifted to the COM.
  const double x2_moment = a * a * L * L * L / 3.0 + a * k * L * L * L * L / 2.0 + k * k * std::pow(L, 5) / 5.0;
  const double about_tail = p.density * PI * (L * s4 / 20.0 + x2_moment);
  g.inertia_transverse = about_tail - g.mass * g.com * g.com;
  return g;
}

RodGeometry make_rod_geometry(const RodParameters &p)
{
  RodGeometry g = rod_solid(p);
  const double L = p.length, a = 0.5 * p.tail_diameter, b = 0.5 * p.nose_diameter;
  const double k = (b - a) / L;

  // Sphere centres: the end spheres touch the end faces (x - r(x) = 0, x + r(x) = L).
  const int n = p.nspheres;
  const double x_first = a / (1.0 - k), x_last = (L - a) / (1.0 + k);
  const double spacing = (x_last - x_first) / (n - 1);
  auto radius_at = [&](double x) { return a + k * x; };
  for (int i = 0; i < n; ++i) {
    const double x = x_first + i * spacing;
    g.spheres.push_back({x, radius_at(x), 0.0});
  }

  // Envelope: two neighbouring spheres meet on a circle of radius h at axial position xm; the
  // frustum there has radius r(xm). The dip r(xm) - h measures how bumpy the contact surface is.
  for (int i = 0; i + 1 < n; ++i) {
    const double r1 = g.spheres[i].radius, r2 = g.spheres[i + 1].radius;
    if (spacing >= r1 + r2 || spacing <= std::fabs(r1 - r2))
      throw std::invalid_argument("neighbouring spheres do not intersect: use more spheres");
    const double d1 = (spacing * spacing + r1 * r1 - r2 * r2) / (2.0 * spacing);
    const double h = std::sqrt(r1 * r1 - d1 * d1);
    g.max_envelope_dip = std::max(g.max_envelope_dip, radius_at(g.spheres[i].x + d1) - h);
  }

  // Point masses: the frustum slab between the midpoints around each centre (ends: to the end
  // faces), then a linear tilt m_i -> m_i (1 + lambda (x_i - x_w)) that keeps the total and moves
  // the first moment onto the solid's COM exactly.
  auto slab_volume = [&](double x0, double x1) {
    const double r0 = radius_at(x0), r1 = radius_at(x1);
    return PI * (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
  };
  double first_moment = 0.0;
  for (int i = 0; i < n; ++i) {
    const double lo = i == 0 ? 0.0 : 0.5 * (g.spheres[i - 1].x + g.spheres[i].x);
    const double hi = i == n - 1 ? L : 0.5 * (g.spheres[i].x + g.spheres[i + 1].x);
    g.spheres[i].mass = p.density * slab_volume(lo, hi);
    first_moment += g.spheres[i].mass * g.spheres[i].x;
  }
  const double x_w = first_moment / g.mass;
  double spread = 0.0;
  for (const auto &s : g.spheres) spread += s.mass * (s.x - x_w) * (s.x - x_w);
  const double lambda = g.mass * (g.com - x_w) / spread;
  for (auto &s : g.spheres) {
    s.mass *= 1.0 + lambda * (s.x - x_w);
    if (!(s.mass > 0.0)) throw std::invalid_argument("no positive sphere masses reproduce the rod's centre of mass");
  }
  return g;
}

}    // namespace ActiveGrain
