/* -*- c++ -*- ----------------------------------------------------------
   LAMMPS - Large-scale Atomic/Molecular Massively Parallel Simulator
   https://www.lammps.org/, Sandia National Laboratories
   LAMMPS development team: developers@lammps.org

   Copyright (2003) Sandia Corporation.  Under the terms of Contract
   DE-AC04-94AL85000 with Sandia Corporation, the U.S. Government retains
   certain rights in this software.  This software is distributed under
   the GNU General Public License.

   See the README file in the top-level LAMMPS directory.
------------------------------------------------------------------------- */

/* ----------------------------------------------------------------------
   Contributing authors: the SaltDEM developers (USER-SALTDEM package, SaltDEM
   repository: discrete-element salt tectonics)

   The frictional-viscous fluid (pair saltdem/viscous, fluid ... yield MU C): the deviatoric
   stress is the Morris viscosity's 2 eta D plus a plastic stress tau, pressure-dependent
   (Drucker-Prager in its shear form), carried per particle:
     d tau / dt = 2 G dev(D) + W tau - tau W      (Jaumann rate, W the spin)
     sqrt(J2(tau)) <= Y = C + MU max(P, 0)        (returned radially onto the yield surface)
   The elastic part G regularizes the rigid-plastic limit: below yield the fluid is an elastic
   solid of strain Y / G at most, at yield tau = Y along D, so a steady shear carries
   C + MU P + eta rate (Bingham for MU = 0) and a fluid without load is Newtonian.  Being
   elastic, its stable step is that of a sound speed with K + 4G/3, not of a viscosity
   Y / rate that grows without bound where the fluid barely moves.  The velocity gradient is
   the corrected SPH gradient, exact for linear fields: grad v_i = G_i S_i^-1 with
   G_i = sum_j mu_ij w_ij (v_i - v_j) (x_i - x_j)^T and the kernel moment S_i of the pressure
   matrices.  Symmetric tensors use the layout of the pressure matrices (xx yy xy in 2D,
   xx yy zz xy xz yz in 3D).  Nothing here depends on LAMMPS classes.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_PLASTIC_H
#define LMP_SALTDEM_PLASTIC_H

#include <cmath>

namespace LAMMPS_NS {
namespace SaltDEM {

  // per atom: the velocity-gradient sums over the fluid partners (0..NG) and over the boundary
  // partners (NG..2NG), row-major, G[a * DIM + b] = sum c dv_a d_b
  template <int DIM> struct PlasticLayout {
    static constexpr int NG = DIM * DIM, NVG = 2 * DIM * DIM;
  };
  constexpr int PLASTIC_NVG_MAX = PlasticLayout<3>::NVG;

  template <int DIM>
  inline void add_velocity_gradient(double c, const double *dv, const double *d, double *G)
  {
    for (int a = 0; a < DIM; a++)
      for (int b = 0; b < DIM; b++) G[a * DIM + b] += c * dv[a] * d[b];
  }

  // a symmetric tensor in the pressure matrices' layout as a full 3x3 matrix, and back
  template <int DIM> inline void sym_to_full(const double *s, double (*m)[3])
  {
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) m[a][b] = 0.0;
    if (DIM == 2) {
      m[0][0] = s[0];
      m[1][1] = s[1];
      m[0][1] = m[1][0] = s[2];
      return;
    }
    m[0][0] = s[0];
    m[1][1] = s[1];
    m[2][2] = s[2];
    m[0][1] = m[1][0] = s[3];
    m[0][2] = m[2][0] = s[4];
    m[1][2] = m[2][1] = s[5];
  }

  template <int DIM> inline void full_to_sym(const double (*m)[3], double *s)
  {
    if (DIM == 2) {
      s[0] = m[0][0];
      s[1] = m[1][1];
      s[2] = 0.5 * (m[0][1] + m[1][0]);
      return;
    }
    s[0] = m[0][0];
    s[1] = m[1][1];
    s[2] = m[2][2];
    s[3] = 0.5 * (m[0][1] + m[1][0]);
    s[4] = 0.5 * (m[0][2] + m[2][0]);
    s[5] = 0.5 * (m[1][2] + m[2][1]);
  }

  /* grad v = G S^-1 (gv row-major: gv[a * DIM + b] = d v_a / d x_b).  S must span every
   direction: det(S / rho) below det_min (a particle with neighbours on one side only) keeps
   the plain gradient G / rho, as the pressure matrices do */
  template <int DIM>
  inline void moment_inverse(const double *S, double rho, double det_min, double (*inv)[3])
  {
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) inv[a][b] = 0.0;
    double m[3][3];
    sym_to_full<DIM>(S, m);
    const double u = 1.0 / rho;
    double det;
    bool ok;
    if (DIM == 2) {
      det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
      ok = det * u * u >= det_min;
      if (ok) {
        inv[0][0] = m[1][1] / det;
        inv[1][1] = m[0][0] / det;
        inv[0][1] = inv[1][0] = -m[0][1] / det;
      }
    } else {
      const double c0 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
      const double c1 = m[0][2] * m[2][1] - m[0][1] * m[2][2];
      const double c2 = m[0][1] * m[1][2] - m[0][2] * m[1][1];
      det = m[0][0] * c0 + m[1][0] * c1 + m[2][0] * c2;
      ok = det * u * u * u >= det_min;
      if (ok) {
        inv[0][0] = c0 / det;
        inv[0][1] = c1 / det;
        inv[0][2] = c2 / det;
        inv[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / det;
        inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
        inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
        inv[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / det;
        inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
        inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
      }
    }
    if (!ok)
      for (int a = 0; a < DIM; a++) inv[a][a] = u;
  }

  template <int DIM>
  inline void velocity_gradient(const double *G, const double *S, double rho, double det_min,
                                double *gv)
  {
    double inv[3][3];
    moment_inverse<DIM>(S, rho, det_min, inv);
    for (int a = 0; a < DIM; a++)
      for (int b = 0; b < DIM; b++) {
        double s = 0.0;
        for (int k = 0; k < DIM; k++) s += G[a * DIM + k] * inv[k][b];
        gv[a * DIM + b] = s;
      }
  }

  /* the stress term of the pressure matrices, sym(tau (S / rho)^-1) (tau where S is
   degenerate): a particle's stress then has the virial tau V whatever its neighbours'
   arrangement, as its pressure has (saltdem_contact_viscous.h, pressure_matrix) */
  template <int DIM>
  inline void corrected_stress(const double *tau, const double *S, double rho, double det_min,
                               double *out)
  {
    double inv[3][3], t[3][3], r[3][3];
    moment_inverse<DIM>(S, rho, det_min, inv);
    sym_to_full<DIM>(tau, t);
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) {
        double x = 0.0;
        for (int k = 0; k < 3; k++) x += t[a][k] * inv[k][b];
        r[a][b] = x * rho;
      }
    full_to_sym<DIM>(r, out);
  }

  /* d tau / dt = 2 Gmod dev(D) + W tau - tau W from the velocity gradient gv */
  template <int DIM>
  inline void plastic_stress_rate(double Gmod, const double *gv, const double *tau, double *dtau)
  {
    double L[3][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
    for (int a = 0; a < DIM; a++)
      for (int b = 0; b < DIM; b++) L[a][b] = gv[a * DIM + b];
    double t[3][3], r[3][3];
    sym_to_full<DIM>(tau, t);
    double tr = 0.0;
    for (int a = 0; a < DIM; a++) tr += L[a][a];
    for (int a = 0; a < 3; a++)
      for (int b = 0; b < 3; b++) {
        const double D = 0.5 * (L[a][b] + L[b][a]) - ((a == b && a < DIM) ? tr / DIM : 0.0);
        double spin = 0.0;
        for (int k = 0; k < 3; k++) {
          const double Wak = 0.5 * (L[a][k] - L[k][a]), Wkb = 0.5 * (L[k][b] - L[b][k]);
          spin += Wak * t[k][b] - t[a][k] * Wkb;
        }
        r[a][b] = 2.0 * Gmod * D + spin;
      }
    full_to_sym<DIM>(r, dtau);
  }

  /* sqrt(J2) = sqrt(tau:tau / 2) of a deviator; in simple shear the shear stress */
  template <int DIM> inline double plastic_norm(const double *tau)
  {
    if (DIM == 2) return std::sqrt(0.5 * (tau[0] * tau[0] + tau[1] * tau[1]) + tau[2] * tau[2]);
    return std::sqrt(0.5 * (tau[0] * tau[0] + tau[1] * tau[1] + tau[2] * tau[2]) + tau[3] * tau[3] +
                     tau[4] * tau[4] + tau[5] * tau[5]);
  }

  /* the strength Y = C + MU max(P, 0) */
  inline double plastic_yield(double mu, double c, double P)
  {
    return c + mu * (P > 0.0 ? P : 0.0);
  }

  /* back onto the yield surface, radially, where sqrt(J2) exceeds Y */
  template <int DIM> inline void plastic_return(double Y, double *tau)
  {
    constexpr int n = (DIM == 2) ? 3 : 6;
    const double J = plastic_norm<DIM>(tau);
    if (J <= Y) return;
    const double f = (Y > 0.0) ? Y / J : 0.0;
    for (int k = 0; k < n; k++) tau[k] *= f;
  }

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
