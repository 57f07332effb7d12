#include "ag_impulse.h"

#include <algorithm>
#include <cmath>

namespace ActiveGrain {

namespace {

// Substeps per compression (or restitution) phase when an impact is integrated; the phase
// ends are found exactly within the last substep. A cap stops impacts whose normal velocity
// cannot grow (Painleve-like configurations with large friction).
constexpr int SUBSTEPS = 64;
constexpr int MAX_PHASE_LENGTHS = 200;    // the cap, in units of SUBSTEPS
constexpr int MAX_SUBSTEPS = MAX_PHASE_LENGTHS * SUBSTEPS;

// Slip is "constant in direction" when the post-impact slip is within this cosine tolerance of
// the initial one.
constexpr double DIRECTION_TOLERANCE = 1.0e-9;

// Once a stuck contact stays stuck, u is linear in p: a substep grows to this many times the
// impulse that changes u.n by |u.n| + |u| + the separation target, more than any remaining
// phase needs (its end is still found exactly within the substep).
constexpr double STUCK_STEP_MARGIN = 4.0;

// Integrate the impact in impulse space with the normal impulse p as the independent variable.
// Compression lasts while u.n < 0 and the normal impulse does work W_c < 0 then; restitution
// ends when its work reaches e_work^2 |W_c|. A target beyond the approach speed (an overlap's
// minimum separation velocity, or a contact inside a multi-contact solve) adds a separation
// phase that raises u.n by the excess: the result is continuous in the target and equals the
// closed forms wherever slip keeps its direction. An impact that starts separating has only
// that phase, up to the target.
enum class ImpactPhase { COMPRESSION, RESTITUTION, SEPARATION };

Vec3 integrate_impact(const Mat3 &K, const Vec3 &u0, const Vec3 &n, const TangentialModel &friction,
                      double e_work, double target_separation)
{
  const TangentialStep tangential(K, n);
  const double mu = friction.mu;
  const double un0 = dot(u0, n);
  const double knn = dot(n, K * n);
  // The substep resolves the larger of the normal phases and the sliding phase (slip can take
  // more normal impulse to stop than compression needs when friction drives the contact in).
  const double ktt = 0.5 * (K.m[0][0] + K.m[1][1] + K.m[2][2] - knn);
  const double slip = norm(u0 - n * un0);
  const double normal_scale = std::max(std::fabs(un0), target_separation) / knn;
  const double slip_scale = mu > 0.0 ? slip / (mu * ktt) : 0.0;
  double dp = std::max(normal_scale, slip_scale) / SUBSTEPS;

  Vec3 u = u0, J;
  double work_compression = 0.0, work_restitution = 0.0;
  ImpactPhase phase = un0 < 0.0 ? ImpactPhase::COMPRESSION : ImpactPhase::SEPARATION;
  const double excess = un0 < 0.0 ? std::max(0.0, target_separation + un0) : 0.0;
  double separation_end = target_separation;    // u.n at which the separation phase ends
  for (int step = 0; step < MAX_SUBSTEPS; ++step) {
    bool stuck = false;
    const Vec3 dJ = n * dp + friction.friction(tangential, u, dp, stuck);
    const Vec3 du = K * dJ;
    const double un = dot(u, n), dun = dot(du, n);
    // The fraction s of this substep after which the phase ends (within a substep u.n is
    // linear in the impulse).
    double s = 1.0;
    bool phase_ends = false;
    switch (phase) {
      case ImpactPhase::COMPRESSION:
        if (un + dun >= 0.0) { s = dun > 0.0 ? -un / dun : 0.0; phase_ends = true; }
        work_compression += dp * s * (un + 0.5 * s * dun);
        break;
      case ImpactPhase::RESTITUTION: {
        const double needed = e_work * e_work * -work_compression - work_restitution;
        const double gain = dp * (un + 0.5 * dun);
        if (gain >= needed) {
          // Solve dp (un s + dun s^2 / 2) = needed for s in [0, 1] (the root without cancellation).
          const double a = 0.5 * dp * dun, b = dp * un;
          const double denominator = b + std::sqrt(std::max(0.0, b * b + 4.0 * a * needed));
          s = denominator > 0.0 ? std::clamp(2.0 * needed / denominator, 0.0, 1.0) : 1.0;
          phase_ends = true;
        }
        work_restitution += dp * s * (un + 0.5 * s * dun);
        break;
      }
      case ImpactPhase::SEPARATION:
        if (un + dun >= separation_end) {
          s = dun > 0.0 ? (separation_end - un) / dun : 0.0;
          phase_ends = true;
        }
        break;
    }
    J += dJ * s;
    u += du * s;
    // Once stuck (zero slip) where the cone holds the sticking impulse direction, the contact
    // stays stuck (K is constant) and u is linear in p: one substep can then cover each
    // remaining phase, ended exactly as above.
    if (stuck && dun > 0.0 && tangential.sticking_ratio() <= mu)
      dp = std::max(dp, STUCK_STEP_MARGIN * (std::fabs(dot(u, n)) + separation_end + norm(u)) * dp / dun);
    if (phase_ends) {
      if (phase == ImpactPhase::SEPARATION) break;
      phase = phase == ImpactPhase::COMPRESSION && e_work > 0.0 && work_compression < 0.0
          ? ImpactPhase::RESTITUTION : ImpactPhase::SEPARATION;
      if (phase == ImpactPhase::SEPARATION) {
        cap_energy(K, u0, J);
        if (excess <= 0.0) break;
        u = u0 + K * J;
        separation_end = dot(u, n) + excess;
      }
    }
  }
  return J;
}

// The sticking impulse: the contact leaves with zero slip and normal velocity target_separation.
Vec3 stick_impulse(const Mat3 &K, const Vec3 &u, const Vec3 &n, double target_separation)
{
  return K.inverse() * (n * target_separation - u);
}

bool inside_friction_cone(const Vec3 &J, const Vec3 &n, const TangentialModel &friction)
{
  const double jn = dot(J, n);
  return jn >= 0.0 && norm(J - n * jn) <= friction.limit(jn);
}

// Stronge's e_work of an impact that restitution must bring to target_separation: e where the
// slip keeps its direction (there Newton's and Stronge's coefficients agree), at most 1 (any
// further separation is the integrated impact's last phase).
double energetic_restitution(double un, double target_separation)
{
  return un < 0.0 ? std::min(1.0, target_separation / -un) : 0.0;
}

}    // namespace

Mat3 contact_matrix(const RigidBodyState &body1, const Vec3 &r1, const RigidBodyState &body2,
                    const Vec3 &r2)
{
  const Mat3 s1 = Mat3::skew(r1), s2 = Mat3::skew(r2);
  return Mat3::identity(body1.inv_mass + body2.inv_mass) - s1 * body1.inv_inertia * s1 -
      s2 * body2.inv_inertia * s2;
}

double impulse_energy_change(const Mat3 &K, const Vec3 &u, const Vec3 &J)
{
  return dot(J, u + K * J * 0.5);
}

void cap_energy(const Mat3 &K, const Vec3 &u0, Vec3 &J)
{
  if (impulse_energy_change(K, u0, J) <= 0.0) return;
  J *= std::max(0.0, -2.0 * dot(J, u0) / dot(J, K * J));
}

Vec3 contact_law_impulse(const Mat3 &K, const Vec3 &u, const Vec3 &n, const ContactModel &model,
                         double target_separation)
{
  const double un = dot(u, n);
  if (un >= target_separation) return {};

  const Vec3 ut = u - n * un;
  const double slip = norm(ut);
  const double e_work = energetic_restitution(un, target_separation);

  // Stick. This closed form is the impact's outcome when the contact sticks throughout (no
  // initial slip) or when tangential and normal motion are uncoupled (K n parallel to n:
  // spheres). Otherwise the slip stops part-way and the impact is integrated below: with
  // coupling, the closed form can gain energy.
  const Vec3 stick = stick_impulse(K, u, n, target_separation);
  if (inside_friction_cone(stick, n, model.tangential)) {
    const Vec3 Kn = K * n;
    const double coupling = norm(Kn - n * dot(Kn, n)) / dot(Kn, n);
    const double scale = std::max(std::fabs(un), target_separation);
    if (slip <= DIRECTION_TOLERANCE * scale || coupling <= DIRECTION_TOLERANCE) return stick;
    return integrate_impact(K, u, n, model.tangential, e_work, target_separation);
  }

  // Slide along the initial slip direction t: J = j_n (n - mu t). Valid while the slip keeps
  // its direction through the impact; then the normal velocity is linear in j_n and Newton's,
  // Poisson's and Stronge's restitution coincide.
  const Vec3 t = slip > 0.0 ? ut / slip : Vec3();
  const Vec3 direction = n - t * model.tangential.mu;
  const double k_dir = dot(n, K * direction);
  if (k_dir > 0.0) {
    const Vec3 slide = direction * ((target_separation - un) / k_dir);
    if (model.tangential.mu == 0.0) return slide;
    const Vec3 u_after = u + K * slide;
    const Vec3 ut_after = u_after - n * dot(u_after, n);
    if (dot(ut_after, t) >= (1.0 - DIRECTION_TOLERANCE) * norm(ut_after)) return slide;
  }

  // Slip stops, reverses or turns during the impact.
  return integrate_impact(K, u, n, model.tangential, e_work, target_separation);
}

Vec3 collision_impulse(const RigidBodyState &body1, const RigidBodyState &body2, const Vec3 &point,
                       const Vec3 &n, const ContactModel &model)
{
  const Vec3 r1 = point - body1.com, r2 = point - body2.com;
  const Vec3 u = body2.velocity_at(point) - body1.velocity_at(point);
  const double un = dot(u, n);
  if (un >= 0.0) return {};
  const Mat3 K = contact_matrix(body1, r1, body2, r2);
  return contact_law_impulse(K, u, n, model, model.normal.target_separation(-un, 0.0));
}

}    // namespace ActiveGrain
