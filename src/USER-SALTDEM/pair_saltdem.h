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
#include "domain.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

#include <cmath>
#include <string>
#include <vector>

namespace LAMMPS_NS {

class PairSaltdem : public Pair {
 public:
  PairSaltdem(class LAMMPS *, const char *style_name, const char *history_id);
  ~PairSaltdem() override;

  void init_style() override;
  double init_one(int, int) override;
  void setup() override;
  void write_restart(FILE *) override;
  void read_restart(FILE *) override;
  void write_restart_settings(FILE *) override;
  void read_restart_settings(FILE *) override;
  void transfer_history(double *, double *, int, int) override;
  double memory_usage() override;
  virtual void pre_loop() {}    // per-step work before the pair loop (all threads joined)
  // a per-atom sum the law feeds while the forces are computed (see loop()): the array
  // thread tid of nthreads adds into (nullptr: the law has none), and what to do with the
  // sums once every thread has finished
  virtual double *loop_sum(int /*tid*/, int /*nthreads*/) { return nullptr; }
  virtual void post_loop(int /*nthreads*/) {}
  // the largest stable time step for the present atoms, coefficients and integrators, and
  // what sets it.  Nothing limits it (no integrated atoms of its types, no coefficients):
  // `why` is left empty and the return is 0.  A limit that is not a finite positive number
  // (a coefficient or mass out of range) is returned as it is, with its reason.  cached: the
  // smallest inertial masses of the last call (no loop over the atoms, no communication;
  // for the re-check during a run, when a coefficient changed)
  double stable_limit(std::string &why, bool cached = false);
  const char *name_of() const { return name; }
  // the coefficients of every type pair this style computes, mixed and derived as init_one()
  // makes them: for saltdem/timestep, which needs the stable limit before a run's init
  void init_coeffs();

  // the stable limit of every SaltDEM pair style present (the pair style, or the SaltDEM
  // sub-styles of pair hybrid, in their order), and the smallest of them (pair nullptr: nothing
  // limits the time step).  A limit that is not a finite positive number stops the run with an
  // error naming the style and what sets it (`who`: the command asking, for that message).
  // Used by the styles' time step check and by saltdem/timestep.
  struct Limit {
    PairSaltdem *pair;
    double dt;
    std::string why;
  };
  static std::vector<PairSaltdem *> saltdem_styles(class LAMMPS *lmp);
  static Limit smallest_limit(class LAMMPS *lmp, const std::string &who,
                              std::vector<Limit> *each = nullptr, bool cached = false);

  // what a law returns: the discs touch (history kept), the law made torques
  enum { LAW_TOUCH = 1, LAW_TORQUE = 2 };

  // the per-atom arrays a law reads, fetched once per pair loop (LAMMPS
  // allocates per-atom 2D arrays contiguously: rows of 3)
  struct Atoms {
    const double (*x)[3], (*v)[3], (*omega)[3];
    const double *radius, *rmass;
  };

  // the pair loop over [ifrom, ito) of the neighbour list, written once for
  // the serial and the threaded styles.  The derived style's inline law
  //   template <int DIM, int EVFLAG> int law(const Atoms &, int i, int j, int itype,
  //     int jtype, double r, double *hist, bool advance, double *f, double *ti,
  //     double *tj, double &evdwl, double &q)
  // computes the kinematics it needs, fills the force on i (and torques on i
  // and j if it returns LAW_TORQUE) and returns LAW_* flags (Derived::HISTORY:
  // whether hist is used, a compile-time constant).  A law with a
  // per-atom pair sum (Derived::PAIR_SUM, e.g. the continuity density of the
  // fluid) sets q, symmetric under i <-> j: sum[i] += m_j q, sum[j] += m_i q
  // (sum: loop_sum(), so the sum costs no second pass).  tally() receives
  // (i, j, evdwl, fx, fy, fz, delx, dely, delz).  DIM 2: discs in the xy
  // plane (z parts are zero and are not touched, see saltdem_contact.h).
  template <class Derived, int EVFLAG, int DIM, class Tally>
  void loop(Derived *self, int ifrom, int ito, double **f, double **torque, double *sum,
            Tally &&tally);

  // loop() for the run's energy/virial flag and dimension
  template <class Derived, class Tally>
  void dispatch_loop(Derived *self, int ifrom, int ito, double **f, double **torque,
                     double *sum, Tally &&tally)
  {
    if (domain->dimension == 2) {
      if (evflag)
        loop<Derived, 1, 2>(self, ifrom, ito, f, torque, sum, tally);
      else
        loop<Derived, 0, 2>(self, ifrom, ito, f, torque, sum, tally);
    } else {
      if (evflag)
        loop<Derived, 1, 3>(self, ifrom, ito, f, torque, sum, tally);
      else
        loop<Derived, 0, 3>(self, ifrom, ito, f, torque, sum, tally);
    }
  }

  // the slice [b[t], b[t+1]) of the neighbour list for thread t of n: about the same
  // number of pairs each (the atoms of a style's list are often bunched in one part of
  // it, e.g. the salt of a scene), re-split after each neighbour list build
  const int *thread_bounds(int nthreads);

  // the serial compute() of a derived style: pre_loop(), the loop over all pairs, post_loop()
  template <class Derived> void compute_serial(Derived *self, int eflag, int vflag)
  {
    recheck_timestep();
    ev_init(eflag, vflag);
    pre_loop();
    auto tally = [this](int i, int j, double e, double fx, double fy, double fz, double dx,
                        double dy, double dz) {
      ev_tally_xyz(i, j, atom->nlocal, force->newton_pair, e, 0.0, fx, fy, fz, dx, dy, dz);
    };
    dispatch_loop(self, 0, list->inum, atom->f, atom->torque, loop_sum(0, 1), tally);
    post_loop(1);
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
  std::vector<int> tbounds;    // thread_bounds(): the slices, and the list they were made for
  bigint tbounds_built;
  int tbounds_inum;

  virtual void allocate();
  virtual void allocate_params(int n) = 0;
  virtual void *pair_params(int i, int j) = 0;    // (plain-old-data: copied to j,i)
  virtual size_t params_size() const = 0;
  virtual void mix(int i, int j) = 0;             // fill params[i][j] from i,i and j,j
  // the derived members of params[i][j] (i <= j) from the coefficients given (init_one)
  virtual void derive(int, int) {}
  virtual double range(int i, int j) const = 0;   // interaction range beyond contact
  virtual double range_abs(int, int) const { return 0.0; }    // range between centres
  // the stable limits of type pair i,j (i <= j, coefficients derived by init_one()) for the
  // smallest inertial mass m of its integrated atoms and the smallest inertial mass per disc
  // (sphere) volume mv, each passed to consider_limit(lim, best, why, reason)
  virtual void pair_limit(int i, int j, double m, double mv, double &best, std::string &why) = 0;
  // type pair i,j is computed by this style: set by its pair_coeff, or mixed from I,I and J,J
  // of this style where no other sub-style of pair hybrid was given it
  bool owns(int i, int j) const;
  // the coefficients of type pair i <= j: mixed if not set, derived, copied to j,i
  void init_coeff(int i, int j);
  // the pair_coeff loop: each(i, j) for every I,J of the ranges with i <= j, which are then set
  template <class Each> void assign_coeffs(int ilo, int ihi, int jlo, int jhi, Each &&each)
  {
    int count = 0;
    for (int i = ilo; i <= ihi; i++)
      for (int j = MAX(jlo, i); j <= jhi; j++) {
        each(i, j);
        setflag[i][j] = 1;
        count++;
      }
    if (count == 0) no_coeffs_set();
  }
  void no_coeffs_set();    // the error of a pair_coeff whose I,J ranges are empty
  // springs and dashpots of two types in series (the mixing rule of stiffnesses)
  static double mix_series(double x, double y) { return (x + y > 0.0) ? 2.0 * x * y / (x + y) : 0.0; }
  // per type: the smallest inertial mass (DBL_MAX: walls only, -1: no atoms) and the smallest
  // inertial mass per disc (sphere) volume of its integrated atoms
  void min_inertial_mass(double *mmin, double *mvmin);
  double inertia_scale(int i);
  // Self-describing restart.  A style's settings begin with RESTART_MARK (negative: the files
  // before the mark began with a positive setting; the files of 2026-11-23 and 2026-12-07 with
  // other marks: their raw coefficient structs are not read), then its own layout version
  // (restart_version(), counted up when its fields change), its settings by name and value,
  // and the names of its coefficients; then (not under pair hybrid, which writes settings
  // only) the coefficients of every type pair set, field by field.  Derived values are not
  // written: init_one() computes them again.  A file of another mark, version or field list
  // stops read_restart with a message naming both.
  static constexpr double RESTART_MARK = -20261214.0;    // SaltDEM::RESTART_MARK (saltdem_check.h)
  virtual int restart_version() const = 0;
  virtual std::vector<std::string> setting_names() const = 0;
  virtual void pack_settings(double *) const = 0;      // in the order of setting_names()
  virtual void unpack_settings(const double *) = 0;
  virtual std::vector<std::string> coeff_names() const = 0;
  virtual void pack_coeffs(int i, int j, double *) const = 0;    // coeff_names() of I,J
  virtual void unpack_coeffs(int i, int j, const double *) = 0;
  int ncoeff_read;    // the number of coefficients per type pair of the file being read
  void read_names(FILE *fp, const std::vector<std::string> &want, const char *what);
  void check_types(int narg, char **arg, int nmin, const char *usage, int &ilo, int &ihi,
                   int &jlo, int &jhi);

  // the time step check: the smallest limit of all SaltDEM pair styles present (the message
  // names the style and the parameter that set it, and the limits of the others); `when`
  // prefixes the message (a re-check during a run).  Returns the limits of every style.
  std::vector<Limit> check_timestep(const std::string &when);
  // a coefficient the limit depends on changed during a run (e.g. fix adapt, through
  // extract() and reinit(), which calls init_one()): the next compute() checks again
  bool recheck;
  std::string recheck_what;    // what changed, for the message
  void recheck_timestep();
  // called on every SaltDEM style once its limit has been checked (it records the values
  // checked, against which a change during the run is detected)
  virtual void limits_checked() { recheck = false; }
  // keep the smaller limit: best/why hold the smallest so far (why empty: none yet); a limit
  // that is not a finite positive number is kept in preference (the check stops on it)
  template <class Reason> static void consider_limit(double lim, double &best, std::string &why,
                                                     Reason &&reason)
  {
    auto bad = [](double v) { return !(v > 0.0) || !std::isfinite(v); };
    if (!why.empty() && bad(best)) return;
    if (why.empty() || bad(lim) || lim < best) {
      best = lim;
      why = reason();
    }
  }
  std::vector<double> mmin_cache, mv_cache;    // min_inertial_mass() of the last full stable_limit()
};

template <class Derived, int EVFLAG, int DIM, class Tally>
void PairSaltdem::loop(Derived *self, int ifrom, int ito, double **f, double **torque,
                       double *sum, Tally &&tally)
{
  using row = const double (*)[3];
  const Atoms a = {atom->x ? (row) atom->x[0] : nullptr, atom->v ? (row) atom->v[0] : nullptr,
                   atom->omega ? (row) atom->omega[0] : nullptr, atom->radius, atom->rmass};
  const auto x = a.x;
  const double *radius = atom->radius;
  const double *rmass = atom->rmass;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int newton_pair = force->newton_pair;
  const bool advance = (update->setupflag == 0);    // history is not advanced in setup
  // a law without history (Derived::HISTORY false): nhist is the constant 0, and the history
  // bookkeeping compiles away
  const int nhist = Derived::HISTORY ? size_history : 0;

  const int *ilist = list->ilist;
  const int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  int **firsttouch = nhist ? fix_history->firstflag : nullptr;
  double **firsthist = nhist ? fix_history->firstvalue : nullptr;

  double fij[3], ti[3], tj[3];

  for (int ii = ifrom; ii < ito; ii++) {
    const int i = ilist[ii];
    const int itype = type[i];
    const double radi = radius[i];
    const double xi0 = x[i][0], xi1 = x[i][1], xi2 = (DIM == 3) ? x[i][2] : 0.0;
    const double *extra_i = extra[itype];
    const double *reach_i = reach_abs[itype];
    const int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    int *touch = nhist ? firsttouch[i] : nullptr;
    double *allhist = nhist ? firsthist[i] : nullptr;
    const double mi = rmass[i];
    // what i receives is summed here and added once after its neighbours: in memory, each
    // pair would wait for the previous pair's store to f[i]
    double fi0 = 0.0, fi1 = 0.0, fi2 = 0.0, ti0 = 0.0, ti1 = 0.0, ti2 = 0.0, sumi = 0.0;

    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const int jtype = type[j];
      const double delx = xi0 - x[j][0];
      const double dely = xi1 - x[j][1];
      const double delz = (DIM == 3) ? xi2 - x[j][2] : 0.0;
      const double rsq = (DIM == 3) ? delx * delx + dely * dely + delz * delz
                                    : delx * delx + dely * dely;
      const double reach = MAX(radi + radius[j] + extra_i[jtype], reach_i[jtype]);
      double *hist = nhist ? &allhist[nhist * jj] : nullptr;

      // out of reach: a pair that is not flagged touching has a zero history
      // already (FixNeighHistory zeroes new pairs, this loop ended ones)
      if (rsq >= reach * reach || rsq == 0.0) {
        if (nhist && touch[jj]) {
          touch[jj] = 0;
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        }
        continue;
      }
      double evdwl = 0.0, q = 0.0;
      const int flags = self->template law<DIM, EVFLAG>(a, i, j, itype, jtype, std::sqrt(rsq),
                                                        hist, advance, fij, ti, tj, evdwl, q);
      if (Derived::PAIR_SUM) {
        sumi += rmass[j] * q;
        if (newton_pair || j < nlocal) sum[j] += mi * q;
      }
      if (nhist) {
        if (flags & LAW_TOUCH)
          touch[jj] = 1;
        else if (touch[jj]) {
          touch[jj] = 0;
          for (int k = 0; k < nhist; k++) hist[k] = 0.0;
        }
      }

      fi0 += fij[0];
      fi1 += fij[1];
      if (DIM == 3) fi2 += fij[2];
      if (flags & LAW_TORQUE) {
        if (DIM == 3) {
          ti0 += ti[0];
          ti1 += ti[1];
        }
        ti2 += ti[2];
      }
      if (newton_pair || j < nlocal) {
        f[j][0] -= fij[0];
        f[j][1] -= fij[1];
        if (DIM == 3) f[j][2] -= fij[2];
        if (flags & LAW_TORQUE) {
          if (DIM == 3) {
            torque[j][0] += tj[0];
            torque[j][1] += tj[1];
          }
          torque[j][2] += tj[2];
        }
      }
      if (EVFLAG) tally(i, j, evdwl, fij[0], fij[1], (DIM == 3) ? fij[2] : 0.0, delx, dely, delz);
    }
    f[i][0] += fi0;
    f[i][1] += fi1;
    if (DIM == 3) {
      f[i][2] += fi2;
      torque[i][0] += ti0;
      torque[i][1] += ti1;
    }
    torque[i][2] += ti2;
    if (Derived::PAIR_SUM) sum[i] += sumi;
  }
}

}    // namespace LAMMPS_NS

#endif
