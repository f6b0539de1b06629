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

   fix saltdem/keystone: a keystone graben between two opposing basement
   normal faults of the same dip.  The left block is static (integrated by
   no fix); the keystone moves down-dip parallel to the left fault,
   (cos D, -sin D) per unit displacement; the right block moves horizontally
   at (2 cos D, 0), which makes the keystone's motion relative to it
   (-cos D, -sin D): down-dip on the right fault, by the same amount.  The
   graben stays symmetric.  The fix group holds the keystone and the right
   block; the keyword 'keystone' names the keystone's group.
------------------------------------------------------------------------- */

#include "fix_saltdem_keystone.h"

#include "atom.h"
#include "error.h"
#include "group.h"

#include <cmath>

using namespace LAMMPS_NS;

FixSaltdemKeystone::FixSaltdemKeystone(LAMMPS *lmp, int narg, char **arg) :
    FixSaltdemMotion(lmp, narg, arg), dip(0.0), ikeystone(-1)
{
  usage = fmt::format("fix ID group {} dip D keystone GROUP rate V target T "
                      "[at_target stop|end] [taper Z0 Z1]",
                      style);
  parse(narg, arg);
  if (dip == 0.0) error->all(FLERR, "Fix {}: dip is required; usage: {}", style, usage);
  if (ikeystone < 0)
    error->all(FLERR, "Fix {}: keystone GROUP is required; usage: {}", style, usage);

  const double a = dip * M_PI / 180.0;
  blocks.push_back(translation(ikeystone, cos(a), -sin(a)));
  blocks.push_back(translation(-1, 2.0 * cos(a), 0.0));
  size_vector = 5;
}

int FixSaltdemKeystone::parse_keyword(const std::string &kw, const std::string &val)
{
  if (kw == "dip")
    dip = angle_arg(kw, val);
  else if (kw == "keystone")
    ikeystone = group_arg(kw, val);
  else
    return 0;
  return 1;
}

/* the keystone must lie inside the fix group, and the right block must not be empty */

void FixSaltdemKeystone::init()
{
  FixSaltdemMotion::init();
  const int kbit = group->bitmask[ikeystone];
  int *mask = atom->mask;
  bigint outside = 0, right = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    if ((mask[i] & kbit) && !(mask[i] & groupbit)) outside++;
    if ((mask[i] & groupbit) && !(mask[i] & kbit)) right++;
  }
  bigint all[2], mine[2] = {outside, right};
  MPI_Allreduce(mine, all, 2, MPI_LMP_BIGINT, MPI_SUM, world);
  if (all[0] > 0)
    error->all(FLERR,
               "Fix {} {}: {} atoms of keystone group {} are not in the fix group {}; the "
               "fix group holds the keystone and the right block",
               style, id, all[0], group->names[ikeystone], group->names[igroup]);
  if (all[1] == 0)
    error->all(FLERR,
               "Fix {} {}: the right block (fix group {} minus keystone group {}) has no "
               "atoms",
               style, id, group->names[igroup], group->names[ikeystone]);
}

/* 1 left-fault displacement, 2 right-fault displacement (equal by construction),
   3 throw (keystone subsidence), 4 heave of each fault, 5 extension (right block) */

double FixSaltdemKeystone::compute_vector(int n)
{
  const double c = blocks[0].vel[0], s = -blocks[0].vel[1];
  if (n == 0) return disp;
  if (n == 1) {
    const double dx = (blocks[0].vel[0] - blocks[1].vel[0]) * disp, dy = -s * disp;
    return sqrt(dx * dx + dy * dy);
  }
  if (n == 2) return disp * s;
  if (n == 3) return disp * c;
  return disp * blocks[1].vel[0];
}
