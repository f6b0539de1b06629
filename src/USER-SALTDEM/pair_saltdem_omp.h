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

   PairSaltdemOMP: what the OpenMP variants of the SaltDEM pair styles share (not a style):
   the ThrOMP machinery and the split of the neighbour list between the threads.  Each thread
   runs the style's own pair loop (PairSaltdem::loop, the code of the serial style) over its
   slice of the list into thread-private force and torque arrays, which ThrOMP reduces.
   Built with the OPENMP package only.
------------------------------------------------------------------------- */

#ifndef LMP_PAIR_SALTDEM_OMP_H
#define LMP_PAIR_SALTDEM_OMP_H

#include "thr_omp.h"

namespace LAMMPS_NS {

class PairSaltdemOMP : public ThrOMP {
 public:
  PairSaltdemOMP(class LAMMPS *lmp) : ThrOMP(lmp, THR_PAIR), tbounds_built(-1), tbounds_inum(-1) {}

 protected:
  // the slice [b[t], b[t+1]) of the neighbour list (ilist, numneigh, inum) for thread t of
  // n: about the same number of pairs each (the atoms of a style's list are often bunched in
  // one part of it, e.g. the salt of a scene), made again after each neighbour list build
  // (lastcall: Neighbor::lastcall)
  const int *thread_bounds(const int *ilist, const int *numneigh, int inum, bigint lastcall,
                           int nthreads)
  {
    if ((int) tbounds.size() != nthreads + 1 || tbounds_built != lastcall || tbounds_inum != inum) {
      tbounds.assign(nthreads + 1, inum);
      tbounds[0] = 0;
      bigint total = 0;
      for (int ii = 0; ii < inum; ii++) total += numneigh[ilist[ii]] + 1;
      bigint sum = 0;
      int t = 1;
      for (int ii = 0; ii < inum && t < nthreads; ii++) {
        sum += numneigh[ilist[ii]] + 1;
        while (t < nthreads && sum * nthreads >= total * t) tbounds[t++] = ii + 1;
      }
      tbounds_built = lastcall;
      tbounds_inum = inum;
    }
    return tbounds.data();
  }

 private:
  std::vector<int> tbounds;    // the slices, and the list they were made for
  bigint tbounds_built;
  int tbounds_inum;
};

}    // namespace LAMMPS_NS

#endif
