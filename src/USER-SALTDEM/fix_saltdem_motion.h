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

   FixSaltdemMotion: the shared machinery of the prescribed-motion fixes
   (saltdem/fault, saltdem/keystone, saltdem/tiltwall).  Not a style.
------------------------------------------------------------------------- */

#ifndef LMP_FIX_SALTDEM_MOTION_H
#define LMP_FIX_SALTDEM_MOTION_H

#include "fix.h"

namespace LAMMPS_NS {

class FixSaltdemMotion : public Fix {
 public:
  FixSaltdemMotion(class LAMMPS *, int, char **);
  int setmask() override;
  void init() override;
  void setup(int) override;
  void initial_integrate(int) override;
  void post_run() override;
  void *extract(const char *, int &) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 protected:
  // Rigid blocks of wall discs, in phases.  An atom of the fix group belongs to the block
  // of the first phase whose group holds it; a phase with group -1 takes the rest of the
  // fix group.  Per unit of drive displacement inside its window [from, to], a phase
  // translates its block by vel and turns it by omega (radians, counterclockwise) about its
  // pivot (where it is at the window's start), which moves with the translation.  Phases of
  // one block (the same group) follow each other in disjoint windows, in order.
  struct Block {
    int igroup;
    double vel[3];
    double omega;
    double pivot[2];
    double from, to;
    int next;    // the block's next phase, -1: none (set by link_phases())
  };
  std::vector<Block> blocks;
  // a block that translates by (vx, vy) per unit of drive over the whole motion
  static Block translation(int igroup, double vx, double vy);
  // the drive displacement phase b has moved by at drive displacement d
  static double active(const Block &b, double d);
  // where phase b's pivot is at drive displacement d
  static void pivot_at(const Block &b, double d, double p[2]);
  void link_phases();
  // where the point x0 (at drive 0) of the block whose first phase is k is at drive d, and
  // by how much it has turned (radians)
  void carry(int k, double d, const double x0[2], double x[2], double &turn) const;

  double rate;       // drive rate (m/s): the displacement the fix reports grows at this rate
  double target;     // drive displacement at which the blocks stop (m)
  int end_run;       // 1: end the run when the target is reached
  int ended;         // 1: this fix ended the current run (post_run lets the next one go)
  double disp;       // drive displacement so far (m), kept in restart files
  int sense;         // toward right|left: +1 the motion goes toward +x, -1 toward -x
  int has_toward;    // 1: the fix takes the keyword 'toward right|left' (set before parse())
  int warned;        // the warning that a step moves a block by much of a disc radius was given
  // taper z0 z1 (3D): a disc's motion is scaled by 1 at z0 falling linearly to 0 at z1 (held
  // beyond both): a throw that dies out along strike
  int tapered;
  double taper_z[2];
  double along(double z) const
  {
    if (!tapered) return 1.0;
    const double f = (taper_z[1] - z) / (taper_z[1] - taper_z[0]);
    return f < 0.0 ? 0.0 : (f > 1.0 ? 1.0 : f);
  }
  // a step that moves a block by more than this fraction of the smallest disc radius warns
  static constexpr double JUMP_FRACTION = 0.1;
  static constexpr double RESTART_VERSION = 1.0;    // layout of the restart data
  std::string usage;

  // parse the keywords shared by all motion fixes (rate, target, at_target, and toward where
  // has_toward is set) and call parse_args() for the others; then check rate and target
  void parse(int narg, char **arg);
  int parse_common(const std::string &kw, const std::string &val);    // 1: taken
  // the fix's own keywords at arg[iarg]: the number of arguments taken (0: unknown); by
  // default a keyword-value pair handed to parse_keyword()
  virtual int parse_args(int iarg, int narg, char **arg);
  virtual int parse_keyword(const std::string &, const std::string &) { return 0; }
  double number_arg(const std::string &what, const char *val);
  double angle_arg(const std::string &kw, const std::string &val);    // (0,90) degrees
  int group_arg(const std::string &kw, const std::string &val);

 private:
  void set_velocity(double speed);
  // per phase, this step's part of the drive, its turn (cos, sin) and its pivot where the
  // step starts (kept between steps to spare the allocation)
  struct PhaseStep {
    double ds, c, s, p[2];
  };
  std::vector<PhaseStep> phase_steps;
  void check_travel();                   // the blocks stay in the box to the target
  double block_speed(const Block &b);    // fastest disc of the block per unit of drive rate
 protected:
  int block_of(int i) const;               // the first phase of local atom i's block (-1: none)
  bool in_chain(int first, int k) const    // phase k is one of the phases from first on
  {
    for (; first >= 0; first = blocks[first].next)
      if (first == k) return true;
    return false;
  }
  void end_this_run();
};

}    // namespace LAMMPS_NS

#endif
