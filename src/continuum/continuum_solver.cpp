#include "continuum_solver.h"

#include <fftw3.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace ActiveGrain::Continuum {

namespace {

using Complex = std::complex<double>;
constexpr Complex I{0.0, 1.0};
constexpr double TWO_PI = 6.283185307179586476925286766559;

bool positive_finite(double v) { return std::isfinite(v) && v > 0.0; }

void require(bool ok, const std::string &message)
{
  if (!ok) throw std::invalid_argument(message);
}

// In-place inverse of the n x n row-major matrix m (Gauss-Jordan, partial pivoting).
void invert(int n, Complex *m)
{
  Complex work[4][8];
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < 2 * n; ++c) work[r][c] = c < n ? m[r * n + c] : Complex(c - n == r ? 1.0 : 0.0);
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::abs(work[r][col]) > std::abs(work[pivot][col])) pivot = r;
    if (std::abs(work[pivot][col]) == 0.0)
      throw std::runtime_error("dt: the implicit operator 3 - 2 dt L(k) is singular for this step; change dt");
    if (pivot != col)
      for (int c = 0; c < 2 * n; ++c) std::swap(work[pivot][c], work[col][c]);
    const Complex inv = 1.0 / work[col][col];
    for (int c = 0; c < 2 * n; ++c) work[col][c] *= inv;
    for (int r = 0; r < n; ++r) {
      if (r == col) continue;
      const Complex f = work[r][col];
      for (int c = 0; c < 2 * n; ++c) work[r][c] -= f * work[col][c];
    }
  }
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) m[r * n + c] = work[r][n + c];
}

}  // namespace

// FFTW plans (made once, FFTW_ESTIMATE: no planning time and the same plan, hence the same
// round-off, on every run) and the aligned buffers they run on.
struct Solver::Workspace {
  double *grid = nullptr;
  fftw_complex *spectrum = nullptr;
  fftw_plan forward = nullptr, backward = nullptr;
  // scratch of nonlinear_terms
  std::vector<double> delta_rho, delta_sigma, polarization, gradient_rho, gradient_sigma, excess_diffusivity,
      product;
  std::vector<Complex> mode_scratch;

  Workspace(const Grid &g, int num_modes)
  {
    const int n = g.num_points();
    grid = fftw_alloc_real(n);
    spectrum = fftw_alloc_complex(num_modes);
    const int dims[2] = {g.dim == 2 ? g.ny : g.nx, g.nx};   // row-major, x fastest
    const int *shape = g.dim == 2 ? dims : dims + 1;
    if (grid && spectrum) {
      forward = fftw_plan_dft_r2c(g.dim, shape, grid, spectrum, FFTW_ESTIMATE);
      backward = fftw_plan_dft_c2r(g.dim, shape, spectrum, grid, FFTW_ESTIMATE);
    }
    if (!forward || !backward) {
      release();
      throw std::runtime_error("continuum: no memory for the FFTW buffers or plans");
    }
    delta_rho.resize(n);
    delta_sigma.resize(n);
    polarization.resize(n);
    gradient_rho.resize(n);
    gradient_sigma.resize(n);
    excess_diffusivity.resize(n);
    product.resize(n);
    mode_scratch.resize(num_modes);
  }
  ~Workspace() { release(); }

  void release()
  {
    if (forward) fftw_destroy_plan(forward);
    if (backward) fftw_destroy_plan(backward);
    fftw_free(grid);
    fftw_free(spectrum);
    forward = backward = nullptr;
    grid = nullptr;
    spectrum = nullptr;
  }
};

/* ---------------------------------------------------------------------- */

Solver::Solver(const Grid &grid, const ModelParameters &p, double dt) : grid_(grid), params_(p), dt_(dt)
{
  require(grid.dim == 1 || grid.dim == 2, "dim: must be 1 or 2");
  require(grid.nx >= 4, "nx: needs at least 4 points");
  require(grid.dim == 1 || grid.ny >= 4, "ny: needs at least 4 points in 2D");
  require(positive_finite(grid.lx), "lx: must be positive");
  require(grid.dim == 1 || positive_finite(grid.ly), "ly: must be positive");
  if (grid_.dim == 1) grid_.ny = 1;
  require(positive_finite(dt), "dt: must be positive");
  for (double v : {p.D_rho, p.D_sigma, p.D_rho_sigma, p.D_sigma_rho, p.alpha, p.u0, p.A, p.B, p.a, p.K, p.tau,
                   p.rho_close})
    require(std::isfinite(v), "parameters: all must be finite");
  require(p.rho_close >= 0.0, "rho_close: must not be negative (0: constant D_rho)");
  require(p.a > 0.0, "a: must be positive (the isotropic phase; P has no cubic term to saturate it)");
  require(p.K >= 0.0, "K: must not be negative");
  require(p.tau >= 0.0, "tau: must not be negative (0 slaves P to the gradients)");
  const double trace = p.D_rho + p.D_sigma;
  const double det = p.D_rho * p.D_sigma - p.D_rho_sigma * p.D_sigma_rho;
  require(trace > 0.0 && det > 0.0,
          "D_rho, D_sigma, D_rho_sigma, D_sigma_rho: the diffusivity matrix needs eigenvalues of positive "
          "real part (trace > 0, determinant > 0); otherwise the growth rate stays positive as k -> "
          "infinity and the problem is ill-posed");

  num_fields_ = 2 + (p.tau > 0.0 ? grid_.dim : 0);
  num_modes_ = grid_.ny * (grid_.nx / 2 + 1);
  build_modes();
  work_ = std::make_unique<Workspace>(grid_, num_modes_);
  state_.assign(static_cast<size_t>(num_fields_) * num_modes_, 0.0);
  nonlinear_.assign(2 * static_cast<size_t>(num_modes_), 0.0);
}

Solver::~Solver() = default;

/* ---------------------------------------------------------------------- */

void Solver::build_modes()
{
  const int nxh = grid_.nx / 2 + 1;
  kx_.resize(num_modes_);
  ky_.resize(num_modes_);
  kept_.resize(num_modes_);
  for (int j = 0; j < grid_.ny; ++j) {
    const int my = j <= grid_.ny / 2 ? j : j - grid_.ny;
    for (int i = 0; i < nxh; ++i) {
      const int m = j * nxh + i;
      kx_[m] = TWO_PI * i / grid_.lx;
      ky_[m] = grid_.dim == 2 ? TWO_PI * my / grid_.ly : 0.0;
      // 2/3 rule: a product of kept modes reaches |m| < 2n/3, whose aliases (shifted by n) stay
      // outside the kept band; this also drops the Nyquist modes.
      kept_[m] = 3 * i < grid_.nx && 3 * std::abs(my) < grid_.ny;
    }
  }
}

void Solver::linear_operator(int m, Complex *L) const
{
  const ModelParameters &p = params_;
  const double kx = kx_[m], ky = ky_[m], k2 = kx * kx + ky * ky;
  const double c[2] = {p.alpha * rho0_, p.u0 * sigma0_};   // rho0 alpha, sigma0 u0
  const double D[2][2] = {{D_implicit_, p.D_rho_sigma}, {p.D_sigma_rho, p.D_sigma}};
  const int n = num_fields_;
  for (int r = 0; r < 2; ++r)
    for (int col = 0; col < 2; ++col) L[r * n + col] = -D[r][col] * k2;
  if (!relaxed_polarization()) {
    // - c_r div P with P = i k (A rho + B sigma) / (a + K k^2)
    const double response = k2 / (p.a + p.K * k2);
    for (int r = 0; r < 2; ++r) {
      L[r * n + 0] += c[r] * p.A * response;
      L[r * n + 1] += c[r] * p.B * response;
    }
    return;
  }
  const double k[2] = {kx, ky};
  for (int d = 0; d < grid_.dim; ++d) {
    const int row = 2 + d;
    for (int r = 0; r < 2; ++r) L[r * n + row] = -c[r] * I * k[d];
    L[row * n + 0] = I * k[d] * p.A / p.tau;
    L[row * n + 1] = I * k[d] * p.B / p.tau;
    for (int col = 2; col < n; ++col) L[row * n + col] = col == row ? -(p.a + p.K * k2) / p.tau : 0.0;
  }
}

void Solver::factorise(double c0, double c1, std::vector<Complex> &out) const
{
  const int n = num_fields_, n2 = n * n;
  out.resize(static_cast<size_t>(num_modes_) * n2);
  for (int m = 0; m < num_modes_; ++m) {
    Complex *M = out.data() + static_cast<size_t>(m) * n2;
    linear_operator(m, M);
    for (int e = 0; e < n2; ++e) M[e] *= -c1 * dt_;
    for (int d = 0; d < n; ++d) M[d * n + d] += c0;
    invert(n, M);
  }
}

/* ---------------------------------------------------------------------- */

void Solver::to_grid(const Complex *spectrum, double *values) const
{
  // c2r overwrites its input: transform a copy
  std::copy(spectrum, spectrum + num_modes_, reinterpret_cast<Complex *>(work_->spectrum));
  fftw_execute(work_->backward);
  std::copy(work_->grid, work_->grid + grid_.num_points(), values);
}

void Solver::from_grid(const double *values, Complex *spectrum) const
{
  std::copy(values, values + grid_.num_points(), work_->grid);
  fftw_execute(work_->forward);
  const double scale = 1.0 / grid_.num_points();
  const Complex *s = reinterpret_cast<const Complex *>(work_->spectrum);
  for (int m = 0; m < num_modes_; ++m) spectrum[m] = kept_[m] ? s[m] * scale : 0.0;
}

void Solver::slaved_polarization(const Complex *rho_hat, const Complex *sigma_hat, int component,
                                 Complex *out) const
{
  const ModelParameters &p = params_;
  for (int m = 0; m < num_modes_; ++m) {
    const double k = component == 0 ? kx_[m] : ky_[m];
    const double k2 = kx_[m] * kx_[m] + ky_[m] * ky_[m];
    out[m] = I * k * (p.A * rho_hat[m] + p.B * sigma_hat[m]) / (p.a + p.K * k2);
  }
}

void Solver::nonlinear_terms(const std::vector<Complex> &state, std::vector<Complex> &out)
{
  Workspace &w = *work_;
  const int n = grid_.num_points();
  const Complex *rho_hat = state.data(), *sigma_hat = state.data() + num_modes_;
  Complex *scratch = w.mode_scratch.data();

  // deviations from the means on the grid
  std::copy(rho_hat, rho_hat + num_modes_, scratch);
  scratch[0] = 0.0;
  to_grid(scratch, w.delta_rho.data());
  std::copy(sigma_hat, sigma_hat + num_modes_, scratch);
  scratch[0] = 0.0;
  to_grid(scratch, w.delta_sigma.data());

  // close packing: the bead diffusivity beyond the implicit one, point by point
  const bool packing = params_.rho_close > 0.0;
  if (packing) {
    max_bead_diffusivity_ = 0.0;
    for (int x = 0; x < n; ++x) {
      const double rho = rho0_ + w.delta_rho[x];
      if (!(rho < params_.rho_close))
        throw StateNotFinite("rho reached rho_close at t = " + std::to_string(time_) +
                             ": the bead stiffness diverges there; a smaller dt resolves the approach");
      const double D = bead_diffusivity(rho);
      max_bead_diffusivity_ = std::max(max_bead_diffusivity_, D);
      w.excess_diffusivity[x] = D - D_implicit_;
    }
  }

  std::fill(out.begin(), out.end(), 0.0);
  Complex *out_rho = out.data(), *out_sigma = out.data() + num_modes_;
  const bool proportional = params_.proportional_cross_diffusion;
  for (int d = 0; d < grid_.dim; ++d) {
    const std::vector<double> &k = d == 0 ? kx_ : ky_;
    if (relaxed_polarization())
      to_grid(state.data() + static_cast<size_t>(2 + d) * num_modes_, w.polarization.data());
    else {
      slaved_polarization(rho_hat, sigma_hat, d, scratch);
      to_grid(scratch, w.polarization.data());
    }
    if (proportional || packing) {
      for (int m = 0; m < num_modes_; ++m) scratch[m] = I * k[m] * rho_hat[m];
      to_grid(scratch, w.gradient_rho.data());
    }
    if (proportional) {
      for (int m = 0; m < num_modes_; ++m) scratch[m] = I * k[m] * sigma_hat[m];
      to_grid(scratch, w.gradient_sigma.data());
    }
    // the nonlinear part of each current, component d:
    // beads  delta rho (alpha P - D_rho_sigma grad sigma / rho0) - (D_rho(rho) - D_implicit) grad rho
    // rods   delta sigma (u0 P - D_sigma_rho grad rho / sigma0)
    for (int x = 0; x < n; ++x)
      w.product[x] = w.delta_rho[x] * (params_.alpha * w.polarization[x] -
                                       (proportional ? params_.D_rho_sigma / rho0_ * w.gradient_sigma[x] : 0.0)) -
                     (packing ? w.excess_diffusivity[x] * w.gradient_rho[x] : 0.0);
    from_grid(w.product.data(), scratch);
    for (int m = 0; m < num_modes_; ++m) out_rho[m] -= I * k[m] * scratch[m];
    for (int x = 0; x < n; ++x)
      w.product[x] = w.delta_sigma[x] * (params_.u0 * w.polarization[x] -
                                         (proportional ? params_.D_sigma_rho / sigma0_ * w.gradient_rho[x] : 0.0));
    from_grid(w.product.data(), scratch);
    for (int m = 0; m < num_modes_; ++m) out_sigma[m] -= I * k[m] * scratch[m];
  }
}

double Solver::bead_diffusivity(double rho) const
{
  if (params_.rho_close == 0.0) return params_.D_rho;
  // dPi/drho / T of Henderson's Pi = rho T (1 + eta^2/8) / (1 - eta)^2, eta = rho / rho_close
  auto stiffness = [](double eta) {
    const double gap = 1.0 - eta;
    return (1.0 + eta * eta / 8.0) / (gap * gap) + eta * eta / 4.0 / (gap * gap) +
           2.0 * eta * (1.0 + eta * eta / 8.0) / (gap * gap * gap);
  };
  return params_.D_rho * stiffness(rho / params_.rho_close) / stiffness(rho0_ / params_.rho_close);
}

/* ---------------------------------------------------------------------- */

void Solver::set_state(const double *rho, const double *sigma, const double *P)
{
  if (!rho || !sigma) throw std::invalid_argument("rho, sigma: both fields are needed");
  if (relaxed_polarization() && !P)
    throw std::invalid_argument("P: needed when P relaxes (tau > 0)");
  if (!relaxed_polarization() && P)
    throw std::invalid_argument("P: must be null when P is slaved (tau = 0); it follows from rho and sigma");
  has_state_ = false;   // until the new one is complete
  const int n = grid_.num_points();
  for (const double *f : {rho, sigma})
    for (int x = 0; x < n; ++x)
      if (!std::isfinite(f[x])) throw std::invalid_argument("rho, sigma: values must be finite");
  from_grid(rho, state_.data());
  from_grid(sigma, state_.data() + num_modes_);
  for (int d = 0; relaxed_polarization() && d < grid_.dim; ++d) {
    for (int x = 0; x < n; ++x)
      if (!std::isfinite(P[static_cast<size_t>(d) * n + x])) throw std::invalid_argument("P: values must be finite");
    from_grid(P + static_cast<size_t>(d) * n, state_.data() + static_cast<size_t>(2 + d) * num_modes_);
  }
  rho0_ = state_[0].real();
  sigma0_ = state_[num_modes_].real();
  if (params_.proportional_cross_diffusion && !(rho0_ > 0.0 && sigma0_ > 0.0))
    throw std::invalid_argument("rho, sigma: proportional cross-diffusion needs positive mean densities");
  if (params_.rho_close > 0.0 && !(rho0_ > 0.0 && rho0_ < params_.rho_close))
    throw std::invalid_argument("rho: its mean must lie between 0 and rho_close");
  D_implicit_ = params_.D_rho;
  factorise(3.0, 2.0, sbdf2_inverse_);
  time_ = 0.0;
  steps_taken_ = 0;
  restart_ = true;
  has_state_ = true;
}

void Solver::get_state(double *rho, double *sigma, double *P) const
{
  if (!has_state_) throw std::logic_error("no state yet: call set_state first");
  const int n = grid_.num_points();
  if (rho) to_grid(state_.data(), rho);
  if (sigma) to_grid(state_.data() + num_modes_, sigma);
  if (!P) return;
  std::vector<Complex> component(num_modes_);
  for (int d = 0; d < grid_.dim; ++d) {
    if (relaxed_polarization())
      to_grid(state_.data() + static_cast<size_t>(2 + d) * num_modes_, P + static_cast<size_t>(d) * n);
    else {
      slaved_polarization(state_.data(), state_.data() + num_modes_, d, component.data());
      to_grid(component.data(), P + static_cast<size_t>(d) * n);
    }
  }
}

/* ---------------------------------------------------------------------- */

void Solver::step(int steps)
{
  if (!has_state_) throw std::logic_error("no state yet: call set_state first");
  if (steps < 0) throw std::invalid_argument("steps: must not be negative");
  const int n = num_fields_, n2 = n * n;
  std::vector<Complex> rhs(n);
  std::vector<Complex> euler_inverse;
  for (int s = 0; s < steps; ++s) {
    nonlinear_terms(state_, nonlinear_);
    if (max_bead_diffusivity_ > D_implicit_) {
      // the explicit remainder must stay a correction: a new split, a new L, a restart
      D_implicit_ = 1.5 * max_bead_diffusivity_;
      factorise(3.0, 2.0, sbdf2_inverse_);
      restart_ = true;
      nonlinear_terms(state_, nonlinear_);
    }
    const bool first = restart_;
    if (first) factorise(1.0, 1.0, euler_inverse);
    const std::vector<Complex> &inverse = first ? euler_inverse : sbdf2_inverse_;
    std::vector<Complex> next(state_.size());
    for (int m = 0; m < num_modes_; ++m) {
      if (!kept_[m]) continue;
      for (int f = 0; f < n; ++f) {
        const size_t i = static_cast<size_t>(f) * num_modes_ + m;
        if (first)
          rhs[f] = state_[i] + (f < 2 ? dt_ * nonlinear_[i] : 0.0);
        else
          rhs[f] = 4.0 * state_[i] - previous_state_[i] +
                   (f < 2 ? 2.0 * dt_ * (2.0 * nonlinear_[i] - previous_nonlinear_[i]) : 0.0);
      }
      const Complex *M = inverse.data() + static_cast<size_t>(m) * n2;
      for (int f = 0; f < n; ++f) {
        Complex v = 0.0;
        for (int g = 0; g < n; ++g) v += M[f * n + g] * rhs[g];
        next[static_cast<size_t>(f) * num_modes_ + m] = v;
      }
    }
    previous_state_.swap(state_);
    state_.swap(next);
    previous_nonlinear_.swap(nonlinear_);
    if (nonlinear_.size() != previous_nonlinear_.size()) nonlinear_.resize(previous_nonlinear_.size());
    ++steps_taken_;
    restart_ = false;
    time_ = steps_taken_ * dt_;
    check_finite();
  }
}

void Solver::check_finite() const
{
  double sum = 0.0;
  for (const Complex &v : state_) sum += std::norm(v);
  if (!std::isfinite(sum))
    throw StateNotFinite("the state is no longer finite at t = " + std::to_string(time_) +
                             ": the explicit terms alpha div(delta rho P), u0 div(delta sigma P) need a "
                             "smaller dt");
}

}  // namespace ActiveGrain::Continuum
