// The paper's coarse-grained theory (its eqs. 1-5, docs/continuum.rst) as a pseudo-spectral solver on a periodic
// 1D or 2D grid. No LAMMPS in here; FFTW does the transforms.
//
// Fields: bead density rho, rod density sigma, polarization P (d components).
//   d rho/dt   = D_rho lap rho + D_rho_sigma div(c_rho grad sigma) - alpha div(rho P)
//   d sigma/dt = D_sigma_rho div(c_sigma grad rho) + D_sigma lap sigma - u0 div(sigma P)
// with c_rho = c_sigma = 1 (the paper's constant cross-diffusivities), or, with
// proportional_cross_diffusion, c_rho = rho/rho0 and c_sigma = sigma/sigma0: the same linear
// theory, but a species is no longer pushed where it is absent, so densities stay positive
// (with constant D_rho_sigma > 0 beads flee rods into negative density).
//   slaved (tau = 0):   (a - K lap) P = A grad rho + B grad sigma
//   relaxed (tau > 0):  tau dP/dt = -(a - K lap) P + A grad rho + B grad sigma
//
// Time stepping (SBDF2, semi-implicit BDF2): with rho = rho0 + delta rho (rho0 the conserved
// mean, likewise sigma), every term linear in the deviations -- diffusion, alpha rho0 div P,
// u0 sigma0 div P and the P dynamics -- is the operator L(k), one small matrix per Fourier mode,
// taken implicitly; the rest, N = -(alpha div(delta rho P), u0 div(delta sigma P)) (and the
// proportional cross-diffusion's div(delta rho grad sigma) / rho0, ...), explicitly:
//   (3 - 2 dt L) u^{n+1} = 4 u^n - u^{n-1} + 2 dt (2 N^n - N^{n-1}),
// started by one IMEX Euler step. (3 - 2 dt L)^{-1} is computed once per mode when the state is
// set, so a small perturbation follows the exact linear dynamics of the scheme, and stiff
// diffusion and fast P relaxation cost nothing in step size. Products are formed on the grid and
// dealiased by the 2/3 rule: only modes with 3 |m| < n (each direction) are kept, in the state too.
//
// Close packing (rho_close > 0): the bead current -D_rho grad rho becomes -D_rho(rho) grad rho
// with D_rho(rho) = D_rho h(rho/rho_close) / h(rho0/rho_close), h(eta) = dPi/drho of Henderson's
// hard-disk pressure Pi = rho T (1 + eta^2/8) / (1 - eta)^2 at area fraction eta = rho/rho_close
// (theory.HendersonEOS): the stiffness diverges as rho -> rho_close, and at the mean it is D_rho,
// so the linear theory is unchanged. L(k) takes the bead diffusivity D_implicit >= max D_rho(rho)
// (raised by half again when the state exceeds it, with one IMEX Euler step to restart), and the
// rest, div((D_rho(rho) - D_implicit) grad rho), is explicit (a stabilised split).
//
// Well-posedness: with D_rho = D_sigma = D_sigma_rho = 0 the growth rate tends to a positive
// constant (tr(c g)/K) as k -> infinity, slaved or relaxed P alike, so the grid scale grows as
// fast as any other and nothing converges with resolution. The constructor therefore demands a
// diffusivity matrix with eigenvalues of positive real part (trace > 0, determinant > 0): then
// Re lambda ~ -k^2 eig(D) at large k. Small diffusivities suffice.
#pragma once

#include <complex>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ActiveGrain::Continuum {

struct Grid {
  int dim = 1;          // 1 or 2
  int nx = 64, ny = 1;  // points; ny is 1 in 1D
  double lx = 1.0, ly = 1.0;
  int num_points() const { return nx * (dim == 2 ? ny : 1); }
};

struct ModelParameters {
  double D_rho = 0.0, D_sigma = 0.0, D_rho_sigma = 0.0, D_sigma_rho = 0.0;
  double alpha = 0.0, u0 = 0.0, A = 0.0, B = 0.0, a = 1.0, K = 0.0;
  double tau = 0.0;     // 0: P slaved to the gradients; > 0: P relaxes on this time scale
  bool proportional_cross_diffusion = false;
  double rho_close = 0.0;  // 0: constant D_rho; > 0: bead stiffness of a hard-disk fluid jamming there
};

// Thrown by Solver::step when the state stops being finite.
struct StateNotFinite : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Solver {
 public:
  // Throws std::invalid_argument whose message starts with the offending parameter's name.
  Solver(const Grid &grid, const ModelParameters &params, double dt);
  ~Solver();
  Solver(const Solver &) = delete;
  Solver &operator=(const Solver &) = delete;

  // Fields on the grid, row-major [ny][nx] (x fastest); P as dim such arrays one after the
  // other. P must be null when P is slaved, and is then computed by get_state. set_state
  // projects the fields onto the dealiased modes, resets the time to zero and factorises
  // L(k) about the new means.
  void set_state(const double *rho, const double *sigma, const double *P = nullptr);
  void get_state(double *rho, double *sigma, double *P) const;

  // Advance by steps steps of dt; throws StateNotFinite if the state stops being finite.
  void step(int steps);

  double time() const { return time_; }
  bool relaxed_polarization() const { return params_.tau > 0.0; }

 private:
  struct Workspace;
  using Complex = std::complex<double>;

  void build_modes();
  // L(k) of mode m into out (num_fields_^2, row-major).
  void linear_operator(int m, Complex *out) const;
  // out[m] = (c0 - c1 dt L(k_m))^{-1}, one matrix per mode.
  void factorise(double c0, double c1, std::vector<Complex> &out) const;
  void slaved_polarization(const Complex *rho_hat, const Complex *sigma_hat, int component,
                           Complex *out) const;
  void nonlinear_terms(const std::vector<Complex> &state, std::vector<Complex> &out);
  void to_grid(const Complex *spectrum, double *values) const;
  void from_grid(const double *values, Complex *spectrum) const;
  void check_finite() const;
  double bead_diffusivity(double rho) const;

  Grid grid_;
  ModelParameters params_;
  double dt_;
  double time_ = 0.0;
  bool has_state_ = false;
  int steps_taken_ = 0;            // since set_state
  bool restart_ = true;            // the next step is IMEX Euler (after set_state, or a new L)
  double D_implicit_ = 0.0;        // bead diffusivity in L(k): D_rho, or >= max D_rho(rho)
  double max_bead_diffusivity_ = 0.0;   // of the state nonlinear_terms last saw
  int num_fields_;                 // rho, sigma (, P components when relaxed)
  int num_modes_;                  // r2c modes: ny x (nx/2 + 1)
  double rho0_ = 0.0, sigma0_ = 0.0;

  std::vector<double> kx_, ky_;    // wavevector of each mode
  std::vector<char> kept_;         // inside the 2/3-rule band
  // Spectral fields, field-major: state[f * num_modes_ + m]; normalised so that the
  // inverse transform gives the grid values directly.
  std::vector<Complex> state_, previous_state_;
  std::vector<Complex> nonlinear_, previous_nonlinear_;   // rho and sigma rows only
  std::vector<Complex> sbdf2_inverse_;                    // (3 - 2 dt L)^{-1} per mode
  std::unique_ptr<Workspace> work_;
};

}  // namespace ActiveGrain::Continuum
