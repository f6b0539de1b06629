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

   The radii of the new discs of fix saltdem/sediment: a splitmix64 generator and the radius
   law.  Every rank draws the same stream from the seed, so every rank places the same discs;
   the whole state is one 64-bit word, which the restart file keeps as two exact doubles.
   Another generator (LAMMPS's RanPark) would draw other radii and so change the deposits.
   Nothing here depends on LAMMPS classes (unit test: tests/unit/sediment_pockets_test.cpp).
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_RANDOM_H
#define LMP_SALTDEM_SEDIMENT_RANDOM_H

#include <cmath>
#include <cstdint>

namespace LAMMPS_NS {
namespace SaltDEM {

  // exponent of the paper's radius law p(r) ~ r^-Q (tools/pack.in, dist paper)
  constexpr double SEDIMENT_PAPER_Q = 1.7522293;

  class SedimentRandom {
   public:
    uint64_t state = 0;

    uint64_t next()
    {
      uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
      return z ^ (z >> 31);
    }

    // in [0, 1), the top 53 bits
    double uniform() { return (double) (next() >> 11) * (1.0 / 9007199254740992.0); }

    // uniform on [rmin, rmax], or the paper's law by inverting its distribution function
    double radius(double rmin, double rmax, bool paper)
    {
      const double u = uniform();
      if (!paper || rmax == rmin) return rmin + u * (rmax - rmin);
      const double e = 1.0 - SEDIMENT_PAPER_Q;
      const double a = pow(rmin, e), b = pow(rmax, e);
      const double r = pow(a + u * (b - a), 1.0 / e);
      const double lo = rmin > r ? rmin : r;    // in [rmin, rmax] despite round-off
      return rmax < lo ? rmax : lo;
    }
  };

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
