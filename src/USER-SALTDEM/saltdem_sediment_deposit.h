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

   The deposition of fix saltdem/sediment: the new discs of one interval.  Every rank gathers
   the discs near the surface (SaltDEM::SedimentPockets decides which), places the same new
   discs in their pockets with the same radii, and creates those in its sub-domain at rest.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_DEPOSIT_H
#define LMP_SALTDEM_SEDIMENT_DEPOSIT_H

#include "pointers.h"
#include "saltdem_sediment_random.h"

namespace LAMMPS_NS {

class SaltdemSedimentDeposit : protected Pointers {
 public:
  SaltdemSedimentDeposit(class LAMMPS *, class Fix *);

  int ntype;                        // type of the new discs
  double rmin, rmax;                // their radius law ...
  int paper;                        // ... uniform, or the paper's power law p(r) ~ r^-Q
  double density;                   // mass per area (2D: m = density pi r^2)
  double tol;                       // accepted overlap, fraction of the smaller radius
  bigint maxper;                    // most discs in one interval
  std::vector<int> groups;          // the new discs join these groups and the fix's
  int epoch_index, epoch_offset;    // their epoch goes to this per-atom integer (-1: none)
  SaltDEM::SedimentRandom rng;

  // after a deposition: the area of its discs, whether it ran out of room, the largest atom
  // ID before it (the new discs follow)
  double area;
  int roomless;
  tagint maxtag;

  void check_fit();
  // the discs of one interval below the base level, up to the area target in rate mode;
  // returns their number
  bigint deposit(const class SaltdemSedimentLevels &, double level, bool rate, double target,
                 int epoch);

 private:
  class Fix *fix;
  void create(double *coord, double r, tagint id, int mask, int epoch);
};

}    // namespace LAMMPS_NS

#endif
