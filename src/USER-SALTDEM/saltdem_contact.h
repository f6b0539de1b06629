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

   The contact math of the package, written once: here the geometry and
   kinematics of a disc/sphere contact (Contact) that every law reads; the
   frictional-cohesive cover law (cohesive_force) is in
   saltdem_contact_cohesive.h, the viscous salt laws (viscous_fluid_force,
   viscous_contact_force) and their SPH pieces in saltdem_contact_viscous.h.
   Every pair style, its OpenMP variant and any wall interaction call these
   inline functions.  Nothing here depends on LAMMPS classes.

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

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
