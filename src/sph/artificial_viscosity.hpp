#pragma once
// Monaghan's (1992, ARA&A 30:543) artificial viscosity, shared by WCSPH and the compressible solver:
//   Pi_ij = (-alpha c_bar mu_ij + beta mu_ij^2) / rho_bar,   mu_ij = h v_ij . r_ij / (r_ij^2 + epsilon h^2),
// for approaching pairs (v_ij . r_ij < 0; the callers test that first, so that sound speeds are only
// evaluated where needed). c_bar, rho_bar and h are the pair means the scheme uses.
namespace sph {

inline double monaghan_viscosity(double alpha, double beta, double epsilon, double h, double c_bar, double rho_bar,
                                 double vr, double r) {
  const double mu = h * vr / (r * r + epsilon * h * h);
  return (-alpha * c_bar * mu + beta * mu * mu) / rho_bar;
}

}  // namespace sph
