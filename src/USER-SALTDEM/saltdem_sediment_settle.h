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

   The damped settling of fix saltdem/sediment: the discs of an interval feel a drag
   -gamma v (and -gamma r^2 omega) for a number of steps, so that they come to rest in their
   pockets rather than bounce off.  The discs are known by their range of atom IDs, which the
   restart file keeps.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_SETTLE_H
#define LMP_SALTDEM_SEDIMENT_SETTLE_H

#include "pointers.h"

namespace LAMMPS_NS {

class SaltdemSedimentSettle : protected Pointers {
 public:
  SaltdemSedimentSettle(class LAMMPS *);
  int steps;       // settling lasts this many steps ...
  double gamma;    // ... with this drag

  void add(tagint lo, tagint hi);    // the discs with IDs lo to hi, deposited at this step
  void apply();                      // the drag on the forces of this step
  void pack(std::vector<double> &) const;
  int unpack(const double *);    // returns the number of values read

 private:
  struct Span {
    tagint lo, hi;    // the IDs of the discs of one interval
    bigint end;       // the last step of their settling
  };
  std::vector<Span> spans;
};

}    // namespace LAMMPS_NS

#endif
