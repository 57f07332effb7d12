// Small fixed-size vector and matrix types for the contact core. Header-only, no LAMMPS.
#pragma once

#include <cmath>

namespace ActiveGrain {

constexpr double PI = 3.14159265358979323846;

// Doubles a Vec3 takes in a packed array (Vec3(const double *), store, add_to).
constexpr int VEC3_SIZE = 3;
// Components of a symmetric 3x3 tensor (a virial, an inverse inertia) in a packed array, in
// LAMMPS's order.
enum SymmetricComponent { XX = 0, YY, ZZ, XY, XZ, YZ, NSYMMETRIC };

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;

  constexpr Vec3() = default;
  constexpr Vec3(double x_value, double y_value, double z_value) : x(x_value), y(y_value), z(z_value) {}
  explicit Vec3(const double *a) : x(a[0]), y(a[1]), z(a[2]) {}

  void store(double *a) const { a[0] = x; a[1] = y; a[2] = z; }
  void add_to(double *a) const { a[0] += x; a[1] += y; a[2] += z; }

  Vec3 operator+(const Vec3 &b) const { return {x + b.x, y + b.y, z + b.z}; }
  Vec3 operator-(const Vec3 &b) const { return {x - b.x, y - b.y, z - b.z}; }
  Vec3 operator-() const { return {-x, -y, -z}; }
  Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
  Vec3 operator/(double s) const { return {x / s, y / s, z / s}; }
  Vec3 &operator+=(const Vec3 &b) { x += b.x; y += b.y; z += b.z; return *this; }
  Vec3 &operator-=(const Vec3 &b) { x -= b.x; y -= b.y; z -= b.z; return *this; }
  Vec3 &operator*=(double s) { x *= s; y *= s; z *= s; return *this; }
};

inline Vec3 operator*(double s, const Vec3 &a) { return a * s; }
inline double dot(const Vec3 &a, const Vec3 &b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(const Vec3 &a, const Vec3 &b)
{
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm2(const Vec3 &a) { return dot(a, a); }
inline double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }
// Adds scale times the outer product a (x) b to a virial v (SymmetricComponent order).
inline void add_outer_product(double *v, const Vec3 &a, const Vec3 &b, double scale = 1.0)
{
  v[XX] += scale * a.x * b.x;
  v[YY] += scale * a.y * b.y;
  v[ZZ] += scale * a.z * b.z;
  v[XY] += scale * a.x * b.y;
  v[XZ] += scale * a.x * b.z;
  v[YZ] += scale * a.y * b.z;
}

// Row-major 3x3 matrix.
struct Mat3 {
  double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};

  static Mat3 identity(double s = 1.0)
  {
    Mat3 r;
    r.m[0][0] = r.m[1][1] = r.m[2][2] = s;
    return r;
  }
  static Mat3 diagonal(const Vec3 &d)
  {
    Mat3 r;
    r.m[0][0] = d.x; r.m[1][1] = d.y; r.m[2][2] = d.z;
    return r;
  }
  // Symmetric matrix from its packed components (SymmetricComponent order).
  static Mat3 symmetric(const double *s)
  {
    Mat3 r;
    r.m[0][0] = s[XX]; r.m[1][1] = s[YY]; r.m[2][2] = s[ZZ];
    r.m[0][1] = r.m[1][0] = s[XY];
    r.m[0][2] = r.m[2][0] = s[XZ];
    r.m[1][2] = r.m[2][1] = s[YZ];
    return r;
  }
  // Columns are the vectors a, b, c.
  static Mat3 from_columns(const Vec3 &a, const Vec3 &b, const Vec3 &c)
  {
    Mat3 r;
    const Vec3 col[3] = {a, b, c};
    for (int j = 0; j < 3; ++j) {
      r.m[0][j] = col[j].x; r.m[1][j] = col[j].y; r.m[2][j] = col[j].z;
    }
    return r;
  }
  // [a]x: the matrix with [a]x b = a x b.
  static Mat3 skew(const Vec3 &a)
  {
    Mat3 r;
    r.m[0][1] = -a.z; r.m[0][2] = a.y;
    r.m[1][0] = a.z;  r.m[1][2] = -a.x;
    r.m[2][0] = -a.y; r.m[2][1] = a.x;
    return r;
  }

  Vec3 operator*(const Vec3 &v) const
  {
    return {m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z,
            m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z,
            m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z};
  }
  Mat3 operator*(const Mat3 &b) const
  {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[i][j] = m[i][0] * b.m[0][j] + m[i][1] * b.m[1][j] + m[i][2] * b.m[2][j];
    return r;
  }
  Mat3 operator+(const Mat3 &b) const
  {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][j] + b.m[i][j];
    return r;
  }
  Mat3 operator-(const Mat3 &b) const { return *this + b * -1.0; }
  Mat3 operator*(double s) const
  {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[i][j] * s;
    return r;
  }
  Mat3 transpose() const
  {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r.m[i][j] = m[j][i];
    return r;
  }
  double trace() const { return m[0][0] + m[1][1] + m[2][2]; }
  double determinant() const
  {
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
        m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
        m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  }
  // Inverse of a non-singular matrix (callers guarantee it: K is positive definite).
  Mat3 inverse() const
  {
    Mat3 r;
    const double inv = 1.0 / determinant();
    r.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) * inv;
    r.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) * inv;
    r.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) * inv;
    r.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) * inv;
    r.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) * inv;
    r.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) * inv;
    r.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) * inv;
    r.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) * inv;
    r.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) * inv;
    return r;
  }
};

}    // namespace ActiveGrain
