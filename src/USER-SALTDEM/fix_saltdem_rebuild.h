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
------------------------------------------------------------------------- */

#ifdef FIX_CLASS
// clang-format off
FixStyle(SALTDEM_REBUILD,FixSaltdemRebuild);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_REBUILD_H
#define LMP_FIX_SALTDEM_REBUILD_H

#include "fix.h"

namespace LAMMPS_NS {

/* Internal fix of the SaltDEM pair styles with history (not for input
   scripts).  A size-based neighbour list holds pairs with r < ri + rj +
   skin and is rebuilt once an atom has moved skin/2; a law that still acts
   at a gap `range` beyond contact would then miss pairs that close in from
   just outside the list.  This fix forces the rebuild as soon as an atom
   has moved (skin - range)/2, which keeps every interacting pair listed. */

class FixSaltdemRebuild : public Fix {
 public:
  FixSaltdemRebuild(class LAMMPS *, int, char **);
  int setmask() override;
  void post_integrate() override;

  double range;    // largest interaction range beyond contact, set by the pair style
};

}    // namespace LAMMPS_NS

#endif
#endif
