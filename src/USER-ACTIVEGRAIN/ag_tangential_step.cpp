#include "ag_tangential_step.h"

#include <cmath>

namespace ActiveGrain {

namespace {

// The tangent frame is built from the x axis, or from the y axis where n is within 53 degrees of
// x (|n.x| >= 0.6): the cross product with n stays far from zero.
constexpr double AXIS_CHOICE_COSINE = 0.6;

}    // namespace

TangentialStep::TangentialStep(const Mat3 &K, const Vec3 &n)
{
  TangentPlane &p = tangent_plane;
  const Vec3 a = std::fabs(n.x) < AXIS_CHOICE_COSINE ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  p.tangent1 = cross(n, a);
  p.tangent1 = p.tangent1 / norm(p.tangent1);
  p.tangent2 = cross(n, p.tangent1);
  const Vec3 Kt1 = K * p.tangent1, Kt2 = K * p.tangent2, Kn = K * n;
  const double a11 = dot(p.tangent1, Kt1), a12 = dot(p.tangent1, Kt2), a22 = dot(p.tangent2, Kt2);
  const double det = a11 * a22 - a12 * a12;
  p.inv11 = a22 / det;
  p.inv12 = -a12 / det;
  p.inv22 = a11 / det;
  p.kn1 = dot(p.tangent1, Kn);
  p.kn2 = dot(p.tangent2, Kn);
  const double s1 = p.inv11 * p.kn1 + p.inv12 * p.kn2, s2 = p.inv12 * p.kn1 + p.inv22 * p.kn2;
  stick_ratio = std::sqrt(s1 * s1 + s2 * s2);
}

Vec3 TangentialStep::stick(double b1, double b2) const
{
  const TangentPlane &p = tangent_plane;
  return p.tangent1 * (p.inv11 * b1 + p.inv12 * b2) + p.tangent2 * (p.inv12 * b1 + p.inv22 * b2);
}

Vec3 TangentialStep::friction(const Vec3 &u, double mu, double dp, bool &stuck) const
{
  const TangentPlane &p = tangent_plane;
  const double b1 = -dot(p.tangent1, u) - dp * p.kn1, b2 = -dot(p.tangent2, u) - dp * p.kn2;
  const Vec3 sticking = stick(b1, b2);
  const double limit = mu * dp;
  stuck = norm(sticking) <= limit;
  if (stuck) return sticking;
  // Against the slip the step would reach without friction: the current slip where it is large,
  // the slip the normal impulse itself drives where it starts from rest.
  const Vec3 slip = -(p.tangent1 * b1 + p.tangent2 * b2);
  return slip * (-limit / norm(slip));
}

}    // namespace ActiveGrain
