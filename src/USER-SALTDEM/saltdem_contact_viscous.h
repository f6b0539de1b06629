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

   The viscous salt laws of pair saltdem/viscous and their SPH pieces
   (kernel, equation of state, pressure matrices, boundary fill, no-slip
   offset), written once.  The conventions (signs, DIM, EVFLAG) are those of
   saltdem_contact.h.  Nothing here depends on LAMMPS classes.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_CONTACT_VISCOUS_H
#define LMP_SALTDEM_CONTACT_VISCOUS_H

#include "saltdem_contact.h"

#include <cmath>

namespace LAMMPS_NS {
namespace SaltDEM {

  /* ----------------------------------------------------------------------
   Viscous salt law (pair saltdem/viscous)

   Two forms, chosen per type pair:
   - FLUID (salt-salt): the Morris et al. (1997) SPH viscosity, a dashpot on
     the full relative velocity whose coefficient is a smooth kernel of the
     distance, summed over all neighbours within 2h, with particle volumes
     V = m/rho (rho: the per-atom continuity density of the style).  It
     discretises eta * laplacian(v) and is linear in the velocities:
     Newtonian by construction.  An SPH pressure P = K (rho/rho0 - 1)
     carries the load without granular friction; an optional elastic core
     kn acts between touching discs.
   - CONTACT (boundaries: salt-wall, cover-salt, cover-wall): elastic
     repulsion plus normal and tangential dashpots at the contact point,
     within a small gap; a stiff tangential dashpot makes the interface
     no-slip.
------------------------------------------------------------------------- */

  enum ViscousMode { VISCOUS_FLUID = 0, VISCOUS_CONTACT = 1 };

  /* the coefficients of one type pair; the viscosity eta itself is kept by the pair style
   (one per type pair, which fix adapt changes) and enters only through the derived dashpots */
  struct ViscousParams {
    int mode;         // VISCOUS_FLUID or VISCOUS_CONTACT
    double kn;        // elastic normal stiffness (force/length)
    double h;         // FLUID: smoothing length; the kernel reaches 2h
    double K;         // FLUID: bulk modulus of the equation of state P = K (rho/rho0 - 1)
    double cw;        // FLUID: |dW/dr| / r = cw (1 - r/2h)^3 (derived)
    double cW;        // FLUID: W(0), the kernel's normalisation (derived; wendland_c2_s)
    double ih2;       // FLUID: 1 / 2h (derived)
    double kfac;      // FLUID: 2 eta * kernel constant in the force pass (derived: eta,
                      // dimension, h; 0 when the viscosity is sub-stepped after it)
    double kvisc;     // FLUID: 2 eta * kernel constant (derived)
    double gap;       // CONTACT: the dashpots act up to this gap beyond contact (length)
    double ratio;     // CONTACT: tangential / normal dashpot coefficient
    double gn, gt;    // CONTACT: dashpot coefficients (derived: calibration * eta)
    double mu_y;      // FLUID: plastic strength C + mu_y max(P, 0) (saltdem_plastic.h); 0, 0:
    double coh_y;     // FLUID: none, a Newtonian fluid
    double G;         // FLUID: shear modulus of the plastic stress (its elastic part)
  };

  /* FLUID: the equation of state P = K (rho / rho0 - 1): a fluid at its reference density
   carries no pressure */
  inline double eos_pressure(double K, double rho, double rho0)
  {
    return K * (rho / rho0 - 1.0);
  }

  /* FLUID: the volume m / rho of a particle of mass m and density rho (0 without a density) */
  inline double particle_volume(double m, double rho)
  {
    return (rho > 0.0) ? m / rho : 0.0;
  }

  /* FLUID: the pressure term a = m P / rho^2 of a particle (eos_pressure written out in the
   order the scenes' trajectories were computed with); 0 without a reference density */
  inline double pressure_term(double m, double K, double rho, double rho0)
  {
    return (rho0 > 0.0) ? m * K * (rho / rho0 - 1.0) / (rho * rho) : 0.0;
  }

  /* FLUID: the pressure of a particle is carried by a symmetric matrix, stored as xx, yy, xy
   (2D) or xx, yy, zz, xy, xz, yz (3D): A_i = (m_i P_i / rho_i) S_i^-1 with the kernel's second
   moment S_i = sum_j mu_ij w_ij d_ij d_ij (w = |W'|/r, d = x_i - x_j, over the FLUID pairs
   of i, boundary partners included; mu_ij: j's mass counted as i's material, m_j for one
   density), i.e. m P / rho^2 times the kernel-gradient correction
   L_i = (S_i / rho_i)^-1 of Bonet & Lok (1999).  The pair force (mu_ij A_i + mu_ji A_j) grad W
   (their variational form) conserves linear momentum, and i's half of its pairs has the
   virial sum_j w mu_ij d (A_i d) = S_i A_i = V_i P_i I: a particle's pressure makes an isotropic
   stress whatever the arrangement of its neighbours.  Without L (the plain SPH gradient) that
   virial is P_i V_i S_i / rho_i, whose off-diagonal part under a sheared, loaded arrangement
   made a shear stress proportional to the pressure (a friction; docs/validation.md).
   Number of stored components per atom (both dimensions use the same stride): */
  constexpr int NSYM = 6;
  template <int DIM> constexpr int nsym()
  {
    return DIM == 2 ? 3 : 6;
  }

  /* the pressure matrix A of a particle from its scalar term a = m P / rho^2, density rho and
   moment S (overwritten with A).  The correction needs a moment that spans all directions: a
   particle with few neighbours on one side (det(S/rho) below DET_MIN, against 1 in a full
   kernel and 1/2 at a flat free surface) keeps the plain gradient, A = a I */
  constexpr double CORRECTION_DET_MIN = 0.1;
  template <int DIM> inline void pressure_matrix(double a, double rho, double *S)
  {
    const double u = 1.0 / rho;
    if (DIM == 2) {
      const double xx = S[0] * u, yy = S[1] * u, xy = S[2] * u;
      const double det = xx * yy - xy * xy;
      if (det < CORRECTION_DET_MIN) {
        S[0] = S[1] = a;
        S[2] = 0.0;
        return;
      }
      const double f = a / det;
      S[0] = f * yy;
      S[1] = f * xx;
      S[2] = -f * xy;
      return;
    }
    const double xx = S[0] * u, yy = S[1] * u, zz = S[2] * u;
    const double xy = S[3] * u, xz = S[4] * u, yz = S[5] * u;
    const double c0 = yy * zz - yz * yz, c1 = xz * yz - xy * zz, c2 = xy * yz - xz * yy;
    const double det = xx * c0 + xy * c1 + xz * c2;
    if (det < CORRECTION_DET_MIN) {
      S[0] = S[1] = S[2] = a;
      S[3] = S[4] = S[5] = 0.0;
      return;
    }
    const double f = a / det;
    S[0] = f * c0;
    S[1] = f * (xx * zz - xz * xz);
    S[2] = f * (xx * yy - xy * xy);
    S[3] = f * c1;
    S[4] = f * c2;
    S[5] = f * (xy * xz - xx * yz);
  }

  /* FLUID: the SPH pressure pair matrix pm = mj A_i + mi A_j from the pressure matrices of
   particles i and j (mj: the mass j counts with in i's sums, mu_ij, and mi = mu_ji; see
   SphFields::pair_weights), where fi, fj say whether each carries a pressure (its own
   pair is FLUID with K > 0).  The boundary rule: a particle that carries none (a wall, the
   cover, a fluid with K = 0) mirrors its partner's pressure and correction, so the fluid's
   pressure pushes on it as on more fluid; two such particles exert none. */
  template <int DIM>
  inline void pressure_pair(bool fi, bool fj, double mi, double mj, const double *Ai,
                            const double *Aj, double *pm)
  {
    constexpr int n = nsym<DIM>();
    if (fi && fj)
      for (int k = 0; k < n; k++) pm[k] = mj * Ai[k] + mi * Aj[k];
    else if (fi)
      for (int k = 0; k < n; k++) pm[k] = 2.0 * mj * Ai[k];
    else if (fj)
      for (int k = 0; k < n; k++) pm[k] = 2.0 * mi * Aj[k];
    else
      for (int k = 0; k < n; k++) pm[k] = 0.0;
  }

  /* the moment S += c d d (the layout of pressure_matrix) */
  template <int DIM> inline void add_moment(double c, const double *d, double *S)
  {
    S[0] += c * d[0] * d[0];
    S[1] += c * d[1] * d[1];
    if (DIM == 2) {
      S[2] += c * d[0] * d[1];
      return;
    }
    S[2] += c * d[2] * d[2];
    S[3] += c * d[0] * d[1];
    S[4] += c * d[0] * d[2];
    S[5] += c * d[1] * d[2];
  }

  /* FLUID at a boundary.  A boundary particle (a wall or cover disc: its own pair is not FLUID)
   stands, for a fluid particle i, for the part of i's kernel that the fluid leaves empty: with
   the fluid's kernel sum wf = sum_{fluid j} mu_ij W_ij (i included) and the boundary's
   wb = sum_{boundary j} mu_ij W_ij, the boundary partners of i count fill_i times their mass
   mu_ij and volume (mu_ij/rho_b, rho_b the reference density of i's fluid) in i's pairs, with
     fill_i = (1 - wf / rho_i) / (wb / rho_b)
   the empty fraction of the kernel over what the boundary fills of it, so that a fluid and its
   boundary together fill the kernel whatever the boundary's construction (one line of discs,
   a dense line, a thick band).  A band as thick as the kernel needs no fill (1); fill is kept
   in [1, fill_max] (a particle near a free surface that also sees a boundary would otherwise
   make the boundary stand for the empty space above the fluid as well); fill_max 1 turns it
   off. */
  inline double boundary_fill(double wf, double wb, double rho, double rhob, double fill_max)
  {
    if (!(wb > 0.0) || !(rho > 0.0) || fill_max <= 1.0) return 1.0;
    const double fill = (1.0 - wf / rho) * rhob / wb;
    return fill < 1.0 ? 1.0 : (fill > fill_max ? fill_max : fill);
  }

  /* FLUID: the reference density of a type is the mean kernel density of its particles whose
   kernel is full, those whose neighbours surround them: the kernel-weighted first moment
   |sum_j mu_ij w_ij d_ij| below INTERIOR_MAX of sum_j mu_ij w_ij |d_ij| (0 in a uniform
   neighbourhood; measured 0.03 +- 0.02 in the bulk of a disc pack, at most 0.11, and about 0.4
   at a free surface or a single line of wall discs, whose particles have kernel densities
   15-25 % below the bulk's) */
  constexpr double INTERIOR_MAX = 0.1;

  /* Wendland C2 kernel W(q = r/h) = A (1 - q/2)^4 (1 + 2q) on r < 2h, with
   A = 7/(4 pi h^2) in 2D and 21/(16 pi h^3) in 3D */
  inline double wendland_c2(int dimension, double h, double r)
  {
    const double q = r / h;
    if (q >= 2.0) return 0.0;
    const double s = 1.0 - 0.5 * q;
    const double a = (dimension == 2) ? 7.0 / (4.0 * M_PI * h * h)
                                      : 21.0 / (16.0 * M_PI * h * h * h);
    return a * s * s * s * s * (1.0 + 2.0 * q);
  }

  /* the same W from s = 1 - r/2h and W(0) = A (the pair loops have s already): 1 + 2q = 5 - 4s,
   no division */
  inline double wendland_c2_s(double W0, double s)
  {
    const double s2 = s * s;
    return W0 * s2 * s2 * (5.0 - 4.0 * s);
  }

  /* and its |dW/dr| / r = C (1 - r/2h)^3 with C = 35/(4 pi h^4) in 2D and
   105/(16 pi h^5) in 3D */
  inline double wendland_c2_grad_over_r(int dimension, double h)
  {
    return (dimension == 2) ? 35.0 / (4.0 * M_PI * h * h * h * h)
                            : 105.0 / (16.0 * M_PI * h * h * h * h * h);
  }

  /* FLUID, noslip surface: the velocity that a boundary particle (wall or cover disc of
   radius R and velocity vb) shows its fluid partners is the fluid's, extrapolated linearly
   through the particle's own surface, where the two move together (Morris et al. 1997, J
   Comput Phys 136:214; Adami et al. 2012, J Comput Phys 231:7057, with the wall's depth):
     v_eff = vb - a (u - vb),  a = R / dist,
   u = ws^-1 sum_f mu_f W_f v_f the fluid's kernel average about the particle, at its kernel
   centroid c / ws (c = sum_f mu_f W_f (x_f - x_b)), which lies dist = |c| / ws - R beyond the
   surface along c.  A linear shear flow then sees a continuous velocity across the surface;
   a plain static particle holds the fluid still at its centre, R below the surface
   (docs/salt-validation.md 4.4).  a is capped at NOSLIP_MAX (the fluid crowding the surface: a
   mirror velocity larger than the fluid's own); with no side to the fluid (dist <= 0: a disc
   inside the fluid) a ramps to 0.  Writes the offset o = v_eff - vb. */
  constexpr double NOSLIP_MAX = 1.0;
  template <int DIM>
  inline void noslip_offset(double ws, const double *c, const double *u, const double *vb, double R,
                            double *o)
  {
    for (int k = 0; k < 3; k++) o[k] = 0.0;
    if (!(ws > 0.0) || !(R > 0.0)) return;
    double c2 = 0.0;
    for (int k = 0; k < DIM; k++) c2 += c[k] * c[k];
    const double dist = std::sqrt(c2) / ws - R;
    if (!(dist > 0.0)) return;
    const double a = (dist * NOSLIP_MAX >= R) ? R / dist : NOSLIP_MAX * NOSLIP_MAX * dist / R;
    for (int k = 0; k < DIM; k++) o[k] = -a * (u[k] / ws - vb[k]);
  }

  /* FLUID: the Morris viscosity and the SPH pressure between particles of
   volumes voli, volj (m/rho) at d = x_i - x_j, r = |d|, relative velocity
   vr = v_i - v_j, radii summing to radsum; pm: the SPH pressure pair matrix
   mu_ij A_i + mu_ji A_j (pressure_pair); ov: what the viscosity adds to vr, the
   boundary partner's no-slip offset (o_i - o_j, noslip_offset; zeros for a plain
   pair).  No torque.  divw: v_ij . grad_i W_ij (of the particles' own velocities), the
   pair's term of the continuity equation d rho_i/dt = sum_j mu_ij v_ij . grad_i W_ij.
   Written on d rather than the unit normal: no division unless an elastic core acts.
   Returns true while the discs touch. */
  template <int DIM = 3, int EVFLAG = 1>
  inline bool viscous_fluid_force(const ViscousParams &p, const double *d, const double *vr,
                                  const double *ov, double r, double radsum, double voli,
                                  double volj, const double *pm, double *f, double &evdwl,
                                  double &divw)
  {
    const double delta = radsum - r;
    const bool touching = delta > 0.0;
    if (EVFLAG) evdwl = touching ? 0.5 * p.kn * delta * delta : 0.0;
    const double s = 1.0 - r * p.ih2;
    const double s3 = (s > 0.0) ? s * s * s : 0.0;
    const double g = p.kfac * voli * volj * s3;    // Morris viscosity
    // grad_i W = -cw s^3 d; pressure -pm grad_i W, repulsive for P > 0; the core kn delta d/r
    const double cws3 = p.cw * s3;
    const double a = (touching && p.kn > 0.0) ? p.kn * delta / r : 0.0;
    double pd[3];
    if (DIM == 2) {
      pd[0] = pm[0] * d[0] + pm[2] * d[1];
      pd[1] = pm[2] * d[0] + pm[1] * d[1];
    } else {
      pd[0] = pm[0] * d[0] + pm[3] * d[1] + pm[4] * d[2];
      pd[1] = pm[3] * d[0] + pm[1] * d[1] + pm[5] * d[2];
      pd[2] = pm[4] * d[0] + pm[5] * d[1] + pm[2] * d[2];
    }
    double vd = 0.0;
    for (int k = 0; k < DIM; k++) {
      f[k] = cws3 * pd[k] + a * d[k] - g * (vr[k] + ov[k]);
      vd += vr[k] * d[k];
    }
    divw = -cws3 * vd;
    return touching;
  }

  /* CONTACT: elastic repulsion and dashpots at the contact point (full
   contact_kinematics; reff is not read). */
  template <int DIM = 3, int EVFLAG = 1>
  inline bool viscous_contact_force(const ViscousParams &p, const Contact &c, double *f, double *ti,
                                    double *tj, double &evdwl)
  {
    const bool touching = c.delta > 0.0;
    const double fel = touching ? p.kn * c.delta : 0.0;
    if (EVFLAG) evdwl = touching ? 0.5 * p.kn * c.delta * c.delta : 0.0;
    const double fn = fel - p.gn * c.vn;
    double ft[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < DIM; k++) {
      ft[k] = -p.gt * c.vt[k];
      f[k] = fn * c.n[k] + ft[k];
    }
    contact_torques<DIM>(c, ft, ti, tj);
    return touching;
  }

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
