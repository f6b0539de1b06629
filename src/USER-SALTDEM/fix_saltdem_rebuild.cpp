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
------------------------------------------------------------------------- */

#include "fix_saltdem_rebuild.h"

#include "atom.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemRebuild::FixSaltdemRebuild(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), range(0.0)
{
  force_reneighbor = 1;
  next_reneighbor = -1;
}

int FixSaltdemRebuild::setmask()
{
  return POST_INTEGRATE;
}

/* runs after the atoms moved and before Neighbor::decide() of this step */

void FixSaltdemRebuild::post_integrate()
{
  double **xhold = neighbor->get_xhold();
  if (range <= 0.0 || !xhold) return;    // without 'check yes' LAMMPS keeps no xhold
  const double trigger = 0.5 * (neighbor->skin - range);
  const double triggersq = trigger * trigger;
  double **x = atom->x;
  int flag = 0;
  for (int i = 0; i < atom->nlocal; i++) {
    const double dx = x[i][0] - xhold[i][0];
    const double dy = x[i][1] - xhold[i][1];
    const double dz = x[i][2] - xhold[i][2];
    if (dx * dx + dy * dy + dz * dz > triggersq) {
      flag = 1;
      break;
    }
  }
  int any;
  MPI_Allreduce(&flag, &any, 1, MPI_INT, MPI_MAX, world);
  if (any) next_reneighbor = update->ntimestep;
}
