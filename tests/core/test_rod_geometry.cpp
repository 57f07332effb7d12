// Rod mass properties against independent references: the cylinder and cone textbook formulas
// and a numerical integration of the frustum (slices of thin discs).
#include "ag_math.h"
#include "ag_rod_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace ActiveGrain;

namespace {
RodParameters paper_rod(int n = 9)
{
  // SI units: 4.5 mm brass rod tapered from 1.1 mm to 0.7 mm.
  return {4.5e-3, 1.1e-3, 0.7e-3, n, 8500.0};
}

// Mass, COM and inertia by the midpoint rule over thin discs: independent of the closed forms.
struct Integrated {
  double mass = 0, com = 0, axial = 0, transverse = 0;
};
Integrated integrate(const RodParameters &p, int slices = 200000)
{
  Integrated r;
  const double dx = p.length / slices;
  double m1 = 0, m2 = 0;
  for (int i = 0; i < slices; ++i) {
    const double x = (i + 0.5) * dx;
    const double rad = 0.5 * (p.tail_diameter + (p.nose_diameter - p.tail_diameter) * x / p.length);
    const double dm = p.density * PI * rad * rad * dx;
    r.mass += dm;
    m1 += dm * x;
    m2 += dm * x * x;
    r.axial += 0.5 * dm * rad * rad;
    r.transverse += 0.25 * dm * rad * rad;
  }
  r.com = m1 / r.mass;
  r.transverse += m2 - r.mass * r.com * r.com;
  return r;
}

void expect_rel(double got, double want, double tol, const char *what)
{
  EXPECT_NEAR(got / want, 1.0, tol) << what << ": got " << got << " want " << want;
}
}    // namespace

TEST(RodGeometry, PaperRodMatchesNumericalIntegration)
{
  const auto p = paper_rod();
  const auto g = make_rod_geometry(p);
  const auto num = integrate(p);
  expect_rel(g.mass, num.mass, 1e-3, "mass");
  expect_rel(g.com, num.com, 1e-3, "com");
  expect_rel(g.inertia_axial, num.axial, 1e-3, "axial inertia");
  expect_rel(g.inertia_transverse, num.transverse, 1e-3, "transverse inertia");
  // docs/model.rst: 2.91 mm^3, 24.7 mg.
  EXPECT_NEAR(g.volume * 1e9, 2.91, 0.005);
  EXPECT_NEAR(g.mass * 1e6, 24.7, 0.05);
}

TEST(RodGeometry, CylinderLimit)
{
  const RodParameters p{5.0, 1.0, 1.0, 8, 2.0};
  const auto g = make_rod_geometry(p);
  const double R = 0.5, m = 2.0 * PI * R * R * 5.0;
  expect_rel(g.mass, m, 1e-12, "mass");
  expect_rel(g.com, 2.5, 1e-12, "com");
  expect_rel(g.inertia_axial, 0.5 * m * R * R, 1e-12, "axial");
  expect_rel(g.inertia_transverse, m * (3 * R * R + 25.0) / 12.0, 1e-12, "transverse");
}

TEST(RodGeometry, ConeLimit)
{
  // A nose of 1e-9 of the tail: a cone to well below the tolerance.
  const RodParameters p{4.0, 1.0, 1e-9, 0, 1.0};
  const auto g = rod_solid(p);
  const double R = 0.5, h = 4.0, m = PI * R * R * h / 3.0;
  expect_rel(g.mass, m, 1e-6, "mass");
  expect_rel(g.com, h / 4.0, 1e-6, "com");
  expect_rel(g.inertia_axial, 0.3 * m * R * R, 1e-6, "axial");
  expect_rel(g.inertia_transverse, 3.0 / 80.0 * m * (4 * R * R + h * h), 1e-6, "transverse");
}

TEST(RodGeometry, SphereMassesReproduceSolidMassAndCom)
{
  for (int n : {6, 9, 17}) {
    const auto g = make_rod_geometry(paper_rod(n));
    double m = 0, m1 = 0;
    for (const auto &s : g.spheres) {
      EXPECT_GT(s.mass, 0.0);
      m += s.mass;
      m1 += s.mass * s.x;
    }
    expect_rel(m, g.mass, 1e-12, "sum of sphere masses");
    expect_rel(m1 / m, g.com, 1e-12, "sphere COM");
  }
}

TEST(RodGeometry, SphereLayoutFollowsTaper)
{
  const auto p = paper_rod(9);
  const auto g = make_rod_geometry(p);
  ASSERT_EQ(g.spheres.size(), 9u);
  // First sphere = tail, widest; last = nose, narrowest; both touch the end faces.
  EXPECT_NEAR(g.spheres.front().x - g.spheres.front().radius, 0.0, 1e-15);
  EXPECT_NEAR(g.spheres.back().x + g.spheres.back().radius, p.length, 1e-15);
  for (size_t i = 1; i < g.spheres.size(); ++i) {
    EXPECT_LT(g.spheres[i].radius, g.spheres[i - 1].radius);
    EXPECT_GT(g.spheres[i].x, g.spheres[i - 1].x);
    // Each radius is the frustum's local radius.
    const double r = 0.5 * (p.tail_diameter + (p.nose_diameter - p.tail_diameter) * g.spheres[i].x / p.length);
    EXPECT_NEAR(g.spheres[i].radius, r, 1e-15);
  }
  // 9 spheres: the envelope dips by about 20% of the nose radius between spheres.
  EXPECT_GT(g.max_envelope_dip, 0.0);
  EXPECT_LT(g.max_envelope_dip, 0.25 * 0.35e-3);
  // More spheres, smoother envelope.
  EXPECT_LT(make_rod_geometry(paper_rod(17)).max_envelope_dip, g.max_envelope_dip);
}

TEST(RodGeometry, ReversedTaperMirrorsCom)
{
  auto p = paper_rod();
  const auto g = make_rod_geometry(p);
  std::swap(p.tail_diameter, p.nose_diameter);
  const auto r = make_rod_geometry(p);
  expect_rel(r.com, p.length - g.com, 1e-12, "mirrored com");
  expect_rel(r.inertia_transverse, g.inertia_transverse, 1e-12, "transverse");
  EXPECT_GT(r.spheres.back().radius, r.spheres.front().radius);
}

TEST(RodGeometry, BadParametersAreNamed)
{
  EXPECT_EQ(rod_parameter_error(paper_rod()), "");
  auto p = paper_rod();
  p.length = 0;
  EXPECT_NE(rod_parameter_error(p).find("length"), std::string::npos);
  p = paper_rod();
  p.tail_diameter = -1e-3;
  EXPECT_NE(rod_parameter_error(p).find("tail"), std::string::npos);
  p = paper_rod();
  p.nose_diameter = 0;
  EXPECT_NE(rod_parameter_error(p).find("nose"), std::string::npos);
  p = paper_rod();
  p.density = 0;
  EXPECT_NE(rod_parameter_error(p).find("density"), std::string::npos);
  p = paper_rod(1);
  EXPECT_NE(rod_parameter_error(p).find("spheres"), std::string::npos);
  // Three spheres on a 4.5 mm rod cannot overlap.
  EXPECT_THROW(make_rod_geometry(paper_rod(3)), std::invalid_argument);
}
