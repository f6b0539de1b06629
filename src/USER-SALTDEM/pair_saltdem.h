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

   PairSaltdem: what every SaltDEM contact pair style shares - per type
   pair coefficients of one parameter struct, the size-based neighbour
   list (with shear history where the law has one), cutoffs from the
   largest radius per type, restart of the coefficients, the stable time
   step check, and the one pair loop.  A derived style supplies its
   parameter struct and its law as a policy the loop is handed (its law
   header); the loop is defined in saltdem_pair_loop.h, which, as the law
   headers, only the .cpp files include.
   The OpenMP variants (pair_saltdem_omp.h and the *_omp styles, built with
   the OPENMP package only) run the same loop per thread.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_SALTDEM_H
#define LMP_PAIR_SALTDEM_H

#include "pair.h"

namespace LAMMPS_NS {

class PairSaltdem : public Pair {
 public:
  // the viscous sub-steps per time step of a style that has them (saltdem/timestep ...
  // substeps N); false: the style has none
  virtual bool set_substeps(int) { return false; }
  // its implicit viscosity on or off (saltdem/timestep ... implicit yes|no); false: it has none
  virtual bool set_implicit(bool, double = -1.0, int = -1) { return false; }
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
  // a per-atom sum the law feeds while the forces are computed (see loop()): the array,
  // zeroed for the owned and ghost atoms, that the serial loop adds into (nullptr: the law
  // has none; the OpenMP variant of such a style sums per thread)
  virtual double *loop_sum() { return nullptr; }
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

  // the SaltDEM pair styles present whose style name matches `style` (a pattern, as
  // Force::pair_match: "saltdem/" for all, "saltdem/viscous" for the salt's, /omp included):
  // the pair style, or those sub-styles of pair hybrid in their order.  The one walk over the
  // sub-styles: every style and fix that looks for SaltDEM styles uses it
  static std::vector<PairSaltdem *> saltdem_styles(class LAMMPS *lmp,
                                                   const std::string &style = "saltdem/");

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

  // the pair loop over [ifrom, ito) of the neighbour list, written once for the serial and
  // the threaded styles, with the law a policy it is handed (each style's law header, e.g.
  // saltdem_cohesive_law.h): a struct with
  //   static constexpr bool HISTORY, PAIR_SUM;
  //   template <int DIM, int EVFLAG> int force(const Atoms &, int i, int j, int itype,
  //     int jtype, double r, double *hist, bool advance, double *f, double *ti,
  //     double *tj, double &evdwl, double *q) const
  // inlined into the loop.  force() computes the kinematics it needs, fills the force on i
  // (and torques on i and j if it returns LAW_TORQUE) and returns LAW_* flags (HISTORY:
  // whether hist is used).  A law with a per-atom pair sum (PAIR_SUM, e.g. the continuity
  // density of the fluid) sets i's and j's terms of it, q[0] and q[1]: sum[i] += q[0],
  // sum[j] += q[1] (sum: loop_sum(), so the sum costs no second pass).  tally() receives
  // (i, j, evdwl, fx, fy, fz, delx, dely, delz).  DIM 2: discs in the xy plane (z parts are
  // zero and are not touched, see saltdem_contact.h).
  template <class Law, int EVFLAG, int DIM, class Tally>
  void loop(const Law &law, int ifrom, int ito, double **f, double **torque, double *sum,
            Tally &&tally);

  // loop() for the run's energy/virial flag and dimension
  template <class Law, class Tally>
  void dispatch_loop(const Law &law, int ifrom, int ito, double **f, double **torque, double *sum,
                     Tally &&tally);

  // the serial compute() of a style: pre_loop(), the loop over all pairs
  template <class Law> void compute_serial(const Law &law, int eflag, int vflag);

  // (the three templates are defined in saltdem_pair_loop.h, which only the .cpp files of
  // the styles include)

 protected:
  const char *name;             // style name for messages (force->pair_style may be hybrid)
  const char *hist_id;          // id stem of the FixNeighHistory (nullptr: law has no history)
  int history, size_history;    // values kept per touching pair
  class FixNeighHistory *fix_history;
  class FixSaltdemRebuild *fix_rebuild;    // keeps pairs within the range listed
  std::string rebuild_id() const { return fmt::format("SALTDEM_REBUILD{}", instance_me); }
  double *transfer_factor;    // sign of each history value when (i,j) -> (j,i)
  double *onerad, *maxrad;    // largest radius per type (local, global)
  double **extra;             // interaction range beyond contact per type pair
  double **reach_abs;         // interaction range between centres, whatever the radii
  double dtfactor;            // stable dt = dtfactor * sqrt(m/k) (elastic)
  // dtfactor: default, and the largest accepted (the measured limit between cover discs is
  // 0.77 sqrt(m/k); docs/performance.md, "Measured stability limits")
  static constexpr double DTFACTOR_DEFAULT = 0.6, DTFACTOR_MAX = 0.75;
  // the elastic limit's factor: dtfactor, twice it for a pair with a wall (a type without
  // integrated atoms: the disc has one free side; measured >= 7.6x the disc-disc bound)
  double elastic_factor(bool wall) const { return wall ? 2.0 * dtfactor : dtfactor; }

  virtual void allocate();
  virtual void allocate_params(int n) = 0;
  virtual void *pair_params(int i, int j) = 0;    // (plain-old-data: copied to j,i)
  virtual size_t params_size() const = 0;
  virtual void mix(int i, int j) = 0;    // fill params[i][j] from i,i and j,j
  // the derived members of params[i][j] (i <= j) from the coefficients given (init_one)
  virtual void derive(int, int) {}
  virtual double range(int i, int j) const = 0;               // interaction range beyond contact
  virtual double range_abs(int, int) const { return 0.0; }    // range between centres
  // the stable limits of type pair i,j (i <= j, coefficients derived by init_one()) for the
  // smallest inertial mass m of its integrated atoms and the smallest inertial mass per disc
  // (sphere) volume mv, each passed to consider_limit(lim, best, why, reason); wall: one of
  // the types has no integrated atoms
  virtual void pair_limit(int i, int j, double m, double mv, bool wall, double &best,
                          std::string &why) = 0;
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
  static double mix_series(double x, double y)
  {
    return (x + y > 0.0) ? 2.0 * x * y / (x + y) : 0.0;
  }
  // per type: the smallest inertial mass (DBL_MAX: walls only, -1: no atoms) and the smallest
  // inertial mass per disc (sphere) volume of its integrated atoms
  void min_inertial_mass(double *mmin, double *mvmin);
  // the time-integrating fixes of the present fix list: group bit and inertia factor
  using Integrators = std::vector<std::pair<int, double>>;
  Integrators find_integrators();
  // the inertia factor of an atom of group mask mask (-1: a wall, no integrator or prescribed)
  static double inertia_scale(int mask, const Integrators &integrators);
  // the inertia factor a time-integrating fix gives its atoms: S of a SaltDEM integrator, 1
  // of another, -1 when it prescribes their motion (fix move, extract("prescribed"))
  static double fix_inertia_scale(class Fix *ifix);
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
  // the layouts a style reads, in order: its own and older ones that a released version wrote
  // (its setting_names() and unpack_settings() then follow layout_read, the version of the
  // file being read; 0 outside read_restart)
  virtual std::vector<int> restart_versions_read() const { return {restart_version()}; }
  int layout_read;
  virtual std::vector<std::string> setting_names() const = 0;
  virtual void pack_settings(double *) const = 0;    // in the order of setting_names()
  virtual void unpack_settings(const double *) = 0;
  virtual std::vector<std::string> coeff_names() const = 0;
  virtual void pack_coeffs(int i, int j, double *) const = 0;    // coeff_names() of I,J
  virtual void unpack_coeffs(int i, int j, const double *) = 0;
  int ncoeff_read;    // the number of coefficients per type pair of the file being read
  void read_names(FILE *fp, const std::vector<std::string> &want, const char *what);
  void check_types(int narg, char **arg, int nmin, const char *usage, int &ilo, int &ihi, int &jlo,
                   int &jhi);

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
  template <class Reason>
  static void consider_limit(double lim, double &best, std::string &why, Reason &&reason);
  std::vector<double> mmin_cache,
      mv_cache;    // min_inertial_mass() of the last full stable_limit()
};

}    // namespace LAMMPS_NS

#endif
