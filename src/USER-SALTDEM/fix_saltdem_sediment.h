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

   fix saltdem/sediment: syn-tectonic sedimentation and erosion
   (docs/fix_saltdem_sediment.rst).
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(saltdem/sediment,FixSaltdemSediment);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_SEDIMENT_H
#define LMP_FIX_SALTDEM_SEDIMENT_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemSediment : public Fix {
 public:
  FixSaltdemSediment(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void end_of_step() override;
  void pre_exchange() override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

  // a level: a constant, an equal-style variable, or (erosion only) an atom-style variable
  struct Level {
    enum { NONE, CONSTANT, EQUAL, ATOM };
    int kind = NONE;
    double value = 0.0;
    std::string name;    // variable name (without v_)
    int ivar = -1;
  };

 private:
  enum { MODE_NONE, MODE_FILL, MODE_RATE };
  enum { DRIVE_STEPS, DRIVE_VARIABLE, DRIVE_FIX };
  enum { DIST_UNIFORM, DIST_PAPER };

  int mode;             // none (erosion only), fill (to the base level) or rate
  double rate;          // rate mode: disc area per unit length and time (m^2 / (m s))
  int ntype;            // type of the new discs
  double rmin, rmax;    // radius law of the new discs
  int dist;             // uniform, or the paper's power law p(r) ~ r^-Q on [rmin, rmax]
  double density;       // mass per area of a new disc (2D: m = density pi r^2)
  double tol;           // accepted overlap with an existing disc, fraction of the smaller radius
  bigint maxper;        // most discs deposited in one interval

  // interval: every nsteps steps, or every 'every' of drive displacement
  int drive_kind;
  double every;
  bigint nsteps;
  std::string drive_name;    // variable name, or fix ID
  int drive_index;           // fix: 0 scalar, >= 1 vector element
  int drive_ivar;
  class Fix *drive_fix;

  Level base, erode;
  int erode_igroup, erode_groupbit;
  std::vector<int> extra_groups;    // the new discs join these groups (and the fix group)
  std::string epoch_name;           // per-atom integer (fix property/atom i_NAME) for the epoch
  int epoch_index, epoch_offset;
  int window_given;
  Level wlo, whi;     // the window's ends: constants or equal-style variables (a front)
  double xlo, xhi;    // deposition window along the 'along' axis (default: the box)
  double foreset;     // outside the window the base level falls by this per unit length
                      // (< 0: no deposit outside the window)
  double length;      // rate mode: length the rate is given per (default xhi - xlo)
  int length_given;
  double up[2], along[2];    // frame of gravity: up = -g / |g|, along = (up_y, -up_x)
  int settle_steps;          // damped settling of the new discs for this many steps ...
  double settle_gamma;       // ... with a drag -gamma v (and -gamma r^2 omega)
  uint64_t rng;              // state of the radius and tie generator (splitmix64)

  // state, written to restart files
  int epoch;            // deposition intervals so far
  double ndep, nero;    // discs deposited, eroded (counts, exact in a double)
  double adep, aero;    // their area
  double abyp;          // rate mode: area that found no room below the base level
  double carry;         // rate mode: requested minus deposited area of the last interval (<= 0)
  double t_last;        // rate mode: time of the last interval
  int t_last_set;
  double next_drive;    // drive displacement of the next interval
  int next_set;
  double last_level;            // base level at the last interval
  double last_n, last_area;     // deposited in the last interval
  double last_xlo, last_xhi;    // the window at the last interval
  struct Settle {
    tagint lo, hi;    // tags of the discs of one interval
    bigint end;       // last step of their settling
  };
  std::vector<Settle> settles;

  // decided at the end of a step (or at setup): deposit at the next step
  int pending;
  double drive_at_decision;

  std::string usage;

  void parse_level(Level &, const char *, const char *kw);
  void resolve_level(Level &, const char *kw);
  double level_value(Level &, const char *kw);
  void check_in_box(double level, const char *kw);
  void parse_window_end(Level &, const char *text);
  void update_window();
  double drive_value();
  void decide();
  bool has_cover_law(int itype);
  double now() const;
  void erosion(const std::vector<double> &lev, double lconst);
  void deposition(double level, double time);
  uint64_t next_random();
  double uniform();
  double draw_radius();
};

}    // namespace LAMMPS_NS

#endif
#endif
