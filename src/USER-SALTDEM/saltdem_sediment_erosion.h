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

   The erosion of fix saltdem/sediment: the discs of a group whose centre lies above the
   erosion level are deleted.  Called where new atoms may be made (pre_exchange, the ghosts
   cleared), as LAMMPS's own deleting fixes do.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_EROSION_H
#define LMP_SALTDEM_SEDIMENT_EROSION_H

namespace LAMMPS_NS {
class LAMMPS;

namespace SaltDEM {

  // deletes the owned discs of groupbit above their level (level[i] per atom, or lconst where
  // level is null) along up; n and area: the discs deleted on all ranks
  void sediment_erode(LAMMPS *lmp, int groupbit, const double *up, const double *level,
                      double lconst, double &n, double &area);

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
