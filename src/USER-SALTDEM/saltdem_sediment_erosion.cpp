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

   The erosion of fix saltdem/sediment (see the header).
------------------------------------------------------------------------- */

#include "saltdem_sediment_erosion.h"

#include "atom.h"
#include "atom_vec.h"
#include "lammps.h"
#include "math_const.h"

#include <vector>

using namespace LAMMPS_NS;
using MathConst::MY_PI;

void SaltDEM::sediment_erode(LAMMPS *lmp, int groupbit, const double *up, const double *level,
                             double lconst, double &n, double &area)
{
  Atom *atom = lmp->atom;
  AtomVec *avec = atom->avec;
  double **x = atom->x;
  double *radius = atom->radius;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  std::vector<char> gone(nlocal, 0);
  double loc[2] = {0.0, 0.0}, all[2];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double u = up[0] * x[i][0] + up[1] * x[i][1];
    if (u > (level ? level[i] : lconst)) {
      gone[i] = 1;
      loc[0] += 1.0;
      loc[1] += MY_PI * radius[i] * radius[i];
    }
  }
  // the last disc takes the place of a deleted one
  int i = 0;
  while (i < nlocal) {
    if (gone[i]) {
      avec->copy(nlocal - 1, i, 1);
      gone[i] = gone[nlocal - 1];
      nlocal--;
    } else
      i++;
  }
  atom->nlocal = nlocal;
  MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_SUM, lmp->world);
  atom->natoms -= (bigint) all[0];
  n = all[0];
  area = all[1];
}
