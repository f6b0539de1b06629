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

   The frictional-cohesive cover law of pair saltdem/cohesive, written once.
   The conventions (signs, DIM, EVFLAG) are those of saltdem_contact.h.
   Nothing here depends on LAMMPS classes.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_CONTACT_COHESIVE_H
#define LMP_SALTDEM_CONTACT_COHESIVE_H

#include "saltdem_contact.h"

#include <cmath>

namespace LAMMPS_NS {
namespace SaltDEM {

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

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
