/* ----------------------------------------------------------------------
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

   fix saltdem/fault: the hanging wall of a basement normal fault.  The
   group (the hanging-wall wall discs) moves rigidly down-dip at a given
   rate until a target displacement, then stops, or ends the run.  Reports
   displacement, heave and throw.
------------------------------------------------------------------------- */

#include "fix_saltdem_fault.h"

#include "error.h"

#include <cmath>

using namespace LAMMPS_NS;

FixSaltdemFault::FixSaltdemFault(LAMMPS *lmp, int narg, char **arg) :
    FixSaltdemMotion(lmp, narg, arg), dip(0.0)
{
  has_toward = 1;
  usage = fmt::format("fix ID group {} dip D rate V target T [toward right|left] "
                      "[at_target stop|end] [taper Z0 Z1]",
                      style);
  parse(narg, arg);
  if (dip == 0.0) error->all(FLERR, "Fix {}: dip is required; usage: {}", style, usage);

  // the hanging wall of a fault dipping toward +x (right) moves down and right
  const double a = dip * M_PI / 180.0;
  blocks.push_back(translation(-1, sense * cos(a), -sin(a)));
  size_vector = 3;
}

int FixSaltdemFault::parse_keyword(const std::string &kw, const std::string &val)
{
  if (kw == "dip")
    dip = angle_arg(kw, val);
  else
    return 0;
  return 1;
}

/* 1 displacement along the fault, 2 heave (horizontal), 3 throw (vertical) */

double FixSaltdemFault::compute_vector(int n)
{
  if (n == 0) return disp;
  if (n == 1) return disp * fabs(blocks[0].vel[0]);
  return disp * fabs(blocks[0].vel[1]);
}
