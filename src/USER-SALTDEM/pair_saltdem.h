/* -*- c++ -*- ----------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   PairSaltdem: what every SaltDEM contact pair style shares - per type
   pair coefficients of one parameter struct, the size-based neighbour
   list (with shear history where the law has one), cutoffs from the
   largest radius per type, restart of the coefficients, the stable time
   step check, and the one pair loop.  A derived style supplies the law as
   an inline member `law()` and its parameter struct; its OpenMP variant
   reuses the same loop (saltdem_omp.h).
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_SALTDEM_H
#define LMP_PAIR_SALTDEM_H

#include "pair.h"
#include "saltdem_contact.h"

#include "atom.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>

namespace LAMMPS_NS {

class PairSaltdem : public Pair {
 public:
  PairSaltdem(class LAMMPS *, const char *style_name, const char *history_id);
  ~PairSaltdem() override;

  void init_style() override;
  double init_one(int, int) override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void transfer_history(double *, double *, int, int) override;
  double memory_usage() override;
  virtual void pre_loop() {}    // per-step work before the pair loop (all threads joined)

  // the pair loop over [ifrom, ito) of the neighbour list, written once for
  // the serial and the threaded styles: law() is the derived style's inline
  // force law (it fills force and torques, returns true while touching),
  // tally() receives (i, j, evdwl, fx, fy, fz, delx, dely, delz)
  template <class Derived, int EVFLAG, class Tally>
  void loop(Derived *self, int ifrom, int ito, double **f, double **torque, Tally &&tally);

  // the serial compute() of a derived style: pre_loop(), then the loop over all pairs
  template <class Derived> void compute_serial(Derived *self, int eflag, int vflag)
  {
    ev_init(eflag, vflag);
    pre_loop();
    auto tally = [this](int i, int j, double e, double fx, double fy, double fz, double dx,
                        double dy, double dz) {
      ev_tally_xyz(i, j, atom->nlocal, force->newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz);
    };
    if (evflag)
      loop<Derived, 1>(self, 0, list->inum, atom->f, atom->torque, tally);
    else
      loop<Derived, 0>(self, 0, list->inum, atom->f, atom->torque, tally);
  }

 protected:
  const char *name;            // style name for messages (force->pair_style may be hybrid)
  const char *hist_id;         // id stem of the FixNeighHistory (nullptr: law has no history)
  int history, size_history;   // values kept per touching pair
  class FixNeighHistory *fix_history;
  class FixSaltdemRebuild *fix_rebuild;    // keeps pairs within the range listed
  double *transfer_factor;     // sign of each history value when (i,j) -> (j,i)
  double *onerad, *maxrad;     // largest radius per type (local, global)
  double **extra;              // interaction range beyond contact per type pair
  double **reach_abs;          // interaction range between centres, whatever the radii
  double dtfactor;             // stable dt = dtfactor * sqrt(m/k) (elastic)

  virtual void allocate();
  virtual void allocate_params(int n) = 0;
  virtual void *pair_params(int i, int j) = 0;    // for restart (plain-old-data)
  virtual size_t params_size() const = 0;
  virtual void mix(int i, int j) = 0;             // fill params[i][j] from i,i and j,j
  virtual double range(int i, int j) const = 0;   // interaction range beyond contact
  virtual double range_abs(int, int) const { return 0.0; }    // range between centres
  // the largest stable dt given the smallest inertial mass per type (DBL_MAX:
  // walls only, -1: no atoms); returns 0 if nothing limits it
  virtual double stable_dt(const double *mmin, std::string &why) = 0;
  void min_inertial_mass(double *mmin);
  double inertia_scale(int i);
  void check_types(int narg, char **arg, int nmin, const char *usage, int &ilo, int &ihi,
                   int &jlo, int &jhi);
};

template <class Derived, int EVFLAG, class Tally>
void PairSaltdem::loop(Derived *self, int ifrom, int ito, double **f, double **torque,
                       Tally &&tally)
{
  double **x = atom->x;
  double **v = atom->v;
  double **omega = atom->omega;
  double *radius = atom->radius;
  double *rmass = atom->rmass;
  int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const bool advance = (update->setupflag == 0);    // history is not advanced in setup
  const int nhist = size_history;

  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  int **firsttouch = nhist ? fix_history->firstflag : nullptr;
  double **firsthist = nhist ? fix_history->firstvalue : nullptr;

  SaltDEM::Contact c;
  double fij[3], ti[3], tj[3];

  for (int ii = ifrom; ii < ito; ii++) {
    const int i = ilist[ii];
    const int itype = type[i];
    const double radi = radius[i];
    int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    int *touch = nhist ? firsttouch[i] : nullptr;
    double *allhist = nhist ? firsthist[i] : nullptr;

    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const int jtype = type[j];
      const double delx = x[i][0] - x[j][0];
      const double dely = x[i][1] - x[j][1];
      const double delz = x[i][2] - x[j][2];
      const double rsq = delx * delx + dely * dely + delz * delz;
      const double reach = MAX(radi + radius[j] + extra[itype][jtype], reach_abs[itype][jtype]);
      double *hist = nhist ? &allhist[nhist * jj] : nullptr;

      if (rsq >= reach * reach || rsq == 0.0) {
        if (nhist) {
          touch[jj] = 0;
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        }
        continue;
      }
      SaltDEM::contact_kinematics(x[i], x[j], v[i], v[j], omega[i], omega[j], radi, radius[j],
                                  rmass[i], rmass[j], std::sqrt(rsq), c);
      double evdwl = 0.0;
      const bool touching = self->law(i, j, itype, jtype, c, hist, advance, fij, ti, tj, evdwl);
      if (nhist) {
        touch[jj] = touching ? 1 : 0;
        if (!touching)
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
      }

      f[i][0] += fij[0];
      f[i][1] += fij[1];
      f[i][2] += fij[2];
      torque[i][0] += ti[0];
      torque[i][1] += ti[1];
      torque[i][2] += ti[2];
      if (newton_pair || j < nlocal) {
        f[j][0] -= fij[0];
        f[j][1] -= fij[1];
        f[j][2] -= fij[2];
        torque[j][0] += tj[0];
        torque[j][1] += tj[1];
        torque[j][2] += tj[2];
      }
      if (EVFLAG) tally(i, j, evdwl, fij[0], fij[1], fij[2], delx, dely, delz);
    }
  }
}

}    // namespace LAMMPS_NS

#endif
