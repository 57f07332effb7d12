/* Plain C interface to the continuum solver (continuum_solver.h), for Python's ctypes and any
 * other caller. Every function that can fail returns an AG_CONTINUUM_* code and leaves a message
 * for ag_continuum_last_error() (per thread) that begins with the offending parameter's name.
 * Solvers must be created and destroyed from one thread at a time (FFTW's planner is not
 * thread-safe); each solver may then step in its own thread. */
#ifndef ACTIVEGRAIN_CONTINUUM_H
#define ACTIVEGRAIN_CONTINUUM_H

#ifdef __cplusplus
extern "C" {
#endif

/* Raised whenever ag_continuum_config changes layout; callers check it before use. */
#define AG_CONTINUUM_ABI_VERSION 1

enum ag_continuum_status {
  AG_CONTINUUM_OK = 0,
  AG_CONTINUUM_BAD_ARGUMENT = 1, /* a parameter or field is invalid: the message names it */
  AG_CONTINUUM_NOT_FINITE = 2,   /* the state stopped being finite while stepping (dt too large) */
  AG_CONTINUUM_FAILURE = 3       /* anything else (out of memory, ...) */
};

typedef struct ag_continuum_config {
  int dim;          /* 1 or 2 */
  int nx, ny;       /* grid points (ny ignored in 1D) */
  double lx, ly;    /* periodic box lengths */
  double dt;        /* time step */
  double D_rho, D_sigma, D_rho_sigma, D_sigma_rho;
  double alpha, u0, A, B, a, K;
  double tau;       /* 0: P slaved, (a - K lap) P = A grad rho + B grad sigma; > 0: relaxes */
  double rho_close; /* 0: constant D_rho; > 0: D_rho scaled by Henderson's hard-disk stiffness at
                       area fraction rho/rho_close, D_rho itself at the mean */
  int proportional_cross_diffusion; /* 0: D_rho_sigma grad sigma (the paper); 1: times rho/rho0
                                       (and D_sigma_rho grad rho times sigma/sigma0) */
} ag_continuum_config;

typedef struct ag_continuum ag_continuum;

int ag_continuum_abi_version(void);
const char *ag_continuum_last_error(void);

int ag_continuum_create(const ag_continuum_config *config, ag_continuum **out);
void ag_continuum_destroy(ag_continuum *solver);

/* Fields on the grid, row-major [ny][nx], x fastest; P is dim such arrays one after another.
 * set_state: P must be NULL when tau = 0; resets the time to 0. get_state: any output may be
 * NULL; P is the slaved polarization when tau = 0. */
int ag_continuum_set_state(ag_continuum *solver, const double *rho, const double *sigma, const double *P);
int ag_continuum_get_state(const ag_continuum *solver, double *rho, double *sigma, double *P);
int ag_continuum_step(ag_continuum *solver, int steps);
int ag_continuum_time(const ag_continuum *solver, double *time);

#ifdef __cplusplus
}
#endif

#endif
