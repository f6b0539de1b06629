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

   The contact math of the package, written once.  Every pair style, its
   OpenMP variant and any wall interaction call these inline functions:
   the geometry and kinematics of a disc/sphere contact (Contact), the
   frictional-cohesive cover law (cohesive_force) and the viscous salt laws
   (viscous_fluid_force, viscous_contact_force).  Nothing here depends on
   LAMMPS classes.

   Sign conventions: n points from j to i; the force returned acts on i
   (j receives its negative); torques are returned separately for i and j
   because the lever arms differ.

   Template parameters: DIM = 2 for discs in the xy plane, where the z parts
   of positions, velocities and forces and the x, y parts of angular
   velocities and torques are zero (LAMMPS creates 2D atoms at z = 0 and fix
   enforce2d keeps them there): those parts are neither read nor written,
   which drops only exact zeros from the 3D arithmetic, so both give the
   same numbers.  EVFLAG = 0 skips the energy (evdwl is left unset).
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_CONTACT_H
#define LMP_SALTDEM_CONTACT_H

#include <cmath>

namespace LAMMPS_NS {
namespace SaltDEM {

  /* Geometry and kinematics of one pair: computed once, read by the laws. */
  struct Contact {
    double n[3];      // unit normal, from j to i
    double r;         // centre distance
    double delta;     // overlap r_i + r_j - r (> 0 when touching, < 0 is a gap)
    double li, lj;    // lever arms from the centres to the contact point
    double vr[3];     // relative velocity of the centres v_i - v_j
    double vn;        // normal relative velocity (v_i - v_j).n, < 0 approaching
    double vt[3];     // tangential relative velocity at the contact point
    double wr[3];     // relative angular velocity w_i - w_j
    double meff;      // reduced mass m_i m_j / (m_i + m_j)
    double reff;      // reduced radius r_i r_j / (r_i + r_j)
  };

  /* Fill c for discs/spheres i and j.  r > 0 is required (callers skip r == 0).
   want_reff = false leaves c.reff unset (only rolling resistance reads it). */
  template <int DIM = 3>
  inline void contact_kinematics(const double *xi, const double *xj, const double *vi,
                                 const double *vj, const double *wi, const double *wj, double radi,
                                 double radj, double mi, double mj, double r, Contact &c,
                                 bool want_reff = true)
  {
    const double rinv = 1.0 / r;
    c.n[0] = (xi[0] - xj[0]) * rinv;
    c.n[1] = (xi[1] - xj[1]) * rinv;
    c.n[2] = (DIM == 3) ? (xi[2] - xj[2]) * rinv : 0.0;
    c.r = r;
    c.delta = radi + radj - r;
    // the contact point sits at the middle of the overlap (or gap)
    c.li = radi - 0.5 * c.delta;
    c.lj = radj - 0.5 * c.delta;

    const double vr0 = vi[0] - vj[0], vr1 = vi[1] - vj[1];
    c.vr[0] = vr0;
    c.vr[1] = vr1;
    if (DIM == 3) {
      const double vr2 = vi[2] - vj[2];
      c.vr[2] = vr2;
      c.vn = vr0 * c.n[0] + vr1 * c.n[1] + vr2 * c.n[2];
      // rotation adds -(li w_i + lj w_j) x n at the contact point
      const double w0 = c.li * wi[0] + c.lj * wj[0];
      const double w1 = c.li * wi[1] + c.lj * wj[1];
      const double w2 = c.li * wi[2] + c.lj * wj[2];
      c.vt[0] = vr0 - c.vn * c.n[0] - (w1 * c.n[2] - w2 * c.n[1]);
      c.vt[1] = vr1 - c.vn * c.n[1] - (w2 * c.n[0] - w0 * c.n[2]);
      c.vt[2] = vr2 - c.vn * c.n[2] - (w0 * c.n[1] - w1 * c.n[0]);
      c.wr[0] = wi[0] - wj[0];
      c.wr[1] = wi[1] - wj[1];
      c.wr[2] = wi[2] - wj[2];
    } else {
      c.vr[2] = 0.0;
      c.vn = vr0 * c.n[0] + vr1 * c.n[1];
      // the 3D expressions with n[2] = w0 = w1 = 0
      const double w2 = c.li * wi[2] + c.lj * wj[2];
      c.vt[0] = vr0 - c.vn * c.n[0] + w2 * c.n[1];
      c.vt[1] = vr1 - c.vn * c.n[1] - w2 * c.n[0];
      c.vt[2] = 0.0;
      c.wr[0] = c.wr[1] = 0.0;
      c.wr[2] = wi[2] - wj[2];
    }

    c.meff = (mi > 0.0 && mj > 0.0) ? mi * mj / (mi + mj) : (mi > 0.0 ? mi : mj);
    if (want_reff) c.reff = radi * radj / (radi + radj);
  }

  /* A tangential force at the contact point both pushes a disc (sphere) and turns it: per unit
   1/m its compliance is 1/m + l^2/I = 3/m for a disc (I = m r^2/2, l = r) and 3.5/m for a
   sphere (I = 2 m r^2/5).  A tangential spring or dashpot therefore acts on the mass m over
   this factor, which sets its stable time step. */
  inline double rotation_factor(int dimension)
  {
    return (dimension == 2) ? 3.0 : 3.5;
  }

  /* Keep a 3D history vector in the tangent plane as the contact rotates, with
   its length unchanged (frame-indifferent spring). */
  inline void rotate_into_plane(double *h, const double *n)
  {
    const double hn = h[0] * n[0] + h[1] * n[1] + h[2] * n[2];
    if (hn == 0.0) return;
    const double before = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    h[0] -= hn * n[0];
    h[1] -= hn * n[1];
    h[2] -= hn * n[2];
    const double after = h[0] * h[0] + h[1] * h[1] + h[2] * h[2];
    if (after > 0.0) {
      const double s = std::sqrt(before / after);
      h[0] *= s;
      h[1] *= s;
      h[2] *= s;
    }
  }

  /* Torque contributions of a tangential force ft applied at the contact:
   ti = -li (n x ft), tj = -lj (n x ft). */
  template <int DIM = 3>
  inline void contact_torques(const Contact &c, const double *ft, double *ti, double *tj)
  {
    if (DIM == 2) {    // only the z parts: n x ft = (0, 0, n0 ft1 - n1 ft0)
      const double nx2 = c.n[0] * ft[1] - c.n[1] * ft[0];
      ti[0] = ti[1] = tj[0] = tj[1] = 0.0;
      ti[2] = -c.li * nx2;
      tj[2] = -c.lj * nx2;
      return;
    }
    const double nx0 = c.n[1] * ft[2] - c.n[2] * ft[1];
    const double nx1 = c.n[2] * ft[0] - c.n[0] * ft[2];
    const double nx2 = c.n[0] * ft[1] - c.n[1] * ft[0];
    ti[0] = -c.li * nx0;
    ti[1] = -c.li * nx1;
    ti[2] = -c.li * nx2;
    tj[0] = -c.lj * nx0;
    tj[1] = -c.lj * nx1;
    tj[2] = -c.lj * nx2;
  }

  /* ----------------------------------------------------------------------
   Frictional-cohesive cover law (pair saltdem/cohesive)
------------------------------------------------------------------------- */

  struct CohesiveParams {
    double kn;        // normal stiffness (force/length)
    double kt;        // tangential stiffness (force/length)
    double mu;        // contact friction coefficient
    double coh;       // contact cohesion (force)
    double tens;      // tensile strength (force): peak of the attraction
    double range;     // gap at which the attraction has softened to zero (length)
    double zeta_n;    // normal damping ratio (fraction of critical)
    double zeta_t;    // tangential damping ratio
    double kr;        // rolling stiffness (force/length on the rolling displacement); 0: none
    double mur;       // rolling friction coefficient: |fr| <= mur * Fn
    double cn, ct;    // derived (cohesive_derive): damping per sqrt(reduced mass), 2 zeta sqrt(k)
  };

  /* the derived members of p, from the others.  ftm2v: the unit system's force x time / mass
   to velocity (LAMMPS's force->ftm2v; 1 in SI): a critical dashpot is 2 sqrt(k m / ftm2v) */
  inline void cohesive_derive(CohesiveParams &p, double ftm2v)
  {
    p.cn = 2.0 * p.zeta_n * std::sqrt(p.kn / ftm2v);
    p.ct = 2.0 * p.zeta_t * std::sqrt(p.kt / ftm2v);
  }

  /* Elastic + cohesive normal force (positive = repulsive) at overlap delta.
   Touching: kn*delta.  In a gap g = -delta the attraction rises elastically
   (slope kn) to the tensile strength at g_p = tens/kn, then softens linearly
   to zero at g = range.  It is a function of the gap only: reversible, no
   bond, re-forms on every new contact. */
  inline double cohesive_normal(const CohesiveParams &p, double delta)
  {
    if (delta >= 0.0) return p.kn * delta;
    const double g = -delta;
    if (g >= p.range) return 0.0;
    const double gp = p.tens / p.kn;
    if (g <= gp) return -p.kn * g;
    return -p.tens * (p.range - g) / (p.range - gp);
  }

  /* Potential energy of cohesive_normal, zero at and beyond the range. */
  inline double cohesive_normal_energy(const CohesiveParams &p, double delta)
  {
    const double gp = p.tens / p.kn;
    const double e_range = 0.5 * p.tens * p.range;    // work to pull apart from touching
    if (delta >= 0.0) return 0.5 * p.kn * delta * delta - e_range;
    const double g = -delta;
    if (g >= p.range) return 0.0;
    if (g <= gp) return 0.5 * p.kn * g * g - e_range;
    const double a = p.range - g;
    return -0.5 * p.tens * a * a / (p.range - gp);
  }

  /* The cover law.  hist: 3 tangential (+3 rolling) values, kept while the
   discs touch.  f: force on i.  ti, tj: torques on i and j.  advance: move
   the history on (false during setup, as in LAMMPS's granular styles).
   evdwl: elastic energy stored in the contact (EVFLAG only).  Returns true
   while the discs touch (delta > 0); in the cohesive gap only the normal
   force acts (ti, tj are then left unset).

   Tangential: a spring with the Mohr-Coulomb limit c + mu Fn (Fn elastic,
   compressive here); sliding caps the force and resets the spring to it.
   The spring first follows this step's sliding, as in gran/hooke/history.
   Rolling resistance: an elastic-plastic spring (stiffness kr) on the
   rolling displacement, rate reff (w_i - w_j) x n (Wang et al. 2015),
   limited by mur * Fn; the resisting torque is reff n x fr.  Both limits are
   compared squared (fmax, frmax >= 0: cohesion >= 0 and a compressive
   elastic force): a square root only for a sliding or rolling contact.

   DIM 2: both displacements lie along the tangent t = (-n1, n0) and are kept
   as signed lengths along it (hist[0], hist[3]; hist[1,2,4,5] stay 0): they
   turn with the contact by construction.  DIM 3: vectors, turned into the
   new tangent plane with their lengths kept (rotate_into_plane).  The two
   give the same forces. */
  template <int EVFLAG>
  inline void cohesive_tangent_2d(const CohesiveParams &p, const Contact &c, double *hist,
                                  bool rolling, double dt, bool advance, double gt, double fn_el,
                                  double *f, double *ti, double *tj, double &evdwl)
  {
    const double t0 = -c.n[1], t1 = c.n[0];
    const double vt = c.vt[0] * t0 + c.vt[1] * t1;
    double &xi = hist[0];
    if (advance) xi += vt * dt;
    double ft = -p.kt * xi - gt * vt;
    const double fmax = p.coh + p.mu * fn_el;
    if (ft * ft > fmax * fmax) {
      ft = std::copysign(fmax, ft);
      if (p.kt > 0.0) xi = -(ft + gt * vt) / p.kt;
    }
    if (EVFLAG) evdwl += 0.5 * p.kt * xi * xi;
    f[0] += ft * t0;
    f[1] += ft * t1;
    ti[0] = ti[1] = tj[0] = tj[1] = 0.0;
    ti[2] = -c.li * ft;    // -l (n x ft)_z
    tj[2] = -c.lj * ft;

    if (rolling && p.kr > 0.0) {
      double &psi = hist[3];
      if (advance) psi += c.reff * c.wr[2] * dt;
      double fr = -p.kr * psi;
      const double frmax = p.mur * fn_el;
      if (fr * fr > frmax * frmax) {
        fr = std::copysign(frmax, fr);
        psi = -fr / p.kr;
      }
      if (EVFLAG) evdwl += 0.5 * p.kr * psi * psi;
      ti[2] += c.reff * fr;
      tj[2] -= c.reff * fr;
    }
  }

  template <int EVFLAG>
  inline void cohesive_tangent_3d(const CohesiveParams &p, const Contact &c, double *hist,
                                  bool rolling, double dt, bool advance, double gt, double fn_el,
                                  double *f, double *ti, double *tj, double &evdwl)
  {
    double *xi = hist;
    rotate_into_plane(xi, c.n);
    if (advance)
      for (int k = 0; k < 3; k++) xi[k] += c.vt[k] * dt;
    double ft[3];
    for (int k = 0; k < 3; k++) ft[k] = -p.kt * xi[k] - gt * c.vt[k];
    const double fmax = p.coh + p.mu * fn_el;
    const double ft2 = ft[0] * ft[0] + ft[1] * ft[1] + ft[2] * ft[2];
    if (ft2 > fmax * fmax) {
      const double s = fmax / std::sqrt(ft2);
      for (int k = 0; k < 3; k++) {
        ft[k] *= s;
        if (p.kt > 0.0) xi[k] = -(ft[k] + gt * c.vt[k]) / p.kt;
      }
    }
    if (EVFLAG) evdwl += 0.5 * p.kt * (xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
    for (int k = 0; k < 3; k++) f[k] += ft[k];
    contact_torques<3>(c, ft, ti, tj);

    if (rolling && p.kr > 0.0) {
      double *psi = hist + 3;
      rotate_into_plane(psi, c.n);
      const double vr[3] = {c.reff * (c.wr[1] * c.n[2] - c.wr[2] * c.n[1]),
                            c.reff * (c.wr[2] * c.n[0] - c.wr[0] * c.n[2]),
                            c.reff * (c.wr[0] * c.n[1] - c.wr[1] * c.n[0])};
      if (advance)
        for (int k = 0; k < 3; k++) psi[k] += vr[k] * dt;
      double fr[3];
      for (int k = 0; k < 3; k++) fr[k] = -p.kr * psi[k];
      const double frmax = p.mur * fn_el;
      const double fr2 = fr[0] * fr[0] + fr[1] * fr[1] + fr[2] * fr[2];
      if (fr2 > frmax * frmax) {
        const double s = frmax / std::sqrt(fr2);
        for (int k = 0; k < 3; k++) {
          fr[k] *= s;
          psi[k] = -fr[k] / p.kr;
        }
      }
      if (EVFLAG) evdwl += 0.5 * p.kr * (psi[0] * psi[0] + psi[1] * psi[1] + psi[2] * psi[2]);
      const double tr[3] = {c.reff * (c.n[1] * fr[2] - c.n[2] * fr[1]),
                            c.reff * (c.n[2] * fr[0] - c.n[0] * fr[2]),
                            c.reff * (c.n[0] * fr[1] - c.n[1] * fr[0])};
      for (int k = 0; k < 3; k++) {
        ti[k] += tr[k];
        tj[k] -= tr[k];
      }
    }
  }

  template <int DIM = 3, int EVFLAG = 1>
  inline bool cohesive_force(const CohesiveParams &p, const Contact &c, double *hist, bool rolling,
                             double dt, bool advance, double *f, double *ti, double *tj,
                             double &evdwl)
  {
    // normal: elastic/cohesive + viscous damping (critical ratio zeta_n)
    const double fn_el = cohesive_normal(p, c.delta);
    const double sqm = std::sqrt(c.meff);
    const double fn = fn_el - p.cn * sqm * c.vn;
    if (EVFLAG) evdwl = cohesive_normal_energy(p, c.delta);
    for (int k = 0; k < DIM; k++) f[k] = fn * c.n[k];
    if (c.delta <= 0.0) return false;
    const double gt = p.ct * sqm;
    if (DIM == 2)
      cohesive_tangent_2d<EVFLAG>(p, c, hist, rolling, dt, advance, gt, fn_el, f, ti, tj, evdwl);
    else
      cohesive_tangent_3d<EVFLAG>(p, c, hist, rolling, dt, advance, gt, fn_el, f, ti, tj, evdwl);
    return true;
  }

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
   PairSaltdemViscous::pair_weights), where fi, fj say whether each carries a pressure (its own
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
   (docs/validation.md 4.4).  a is capped at NOSLIP_MAX (the fluid crowding the surface: a
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
