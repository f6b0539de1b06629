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
FixStyle(saltdem/blocks,FixSaltdemBlocks);
// clang-format on
#else

#ifndef LMP_FIX_SALTDEM_BLOCKS_H
#define LMP_FIX_SALTDEM_BLOCKS_H

#include "fix_saltdem_motion.h"

namespace LAMMPS_NS {

class FixSaltdemBlocks : public FixSaltdemMotion {
 public:
  FixSaltdemBlocks(class LAMMPS *, int, char **);
  void init() override;
  double compute_vector(int) override;
  double compute_array(int, int) override;

 protected:
  std::vector<int> firsts;    // the first phase of each block, in the order given
  int parse_args(int, int, char **) override;
  int parse_block(int, int, char **);
};

}    // namespace LAMMPS_NS

#endif
#endif
