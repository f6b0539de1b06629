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

   The bound on every coefficient and setting of the SaltDEM styles: a value
   must be finite and, unless it is 0, of a magnitude in [1e-100, 1e100].
   Products of a few such values with the scene's masses, lengths and time
   step (stiffness x mass, calibration x viscosity, rate x dt, ...) stay
   finite and non-zero; a value beyond the bound is not a physical one in
   any unit system LAMMPS offers and is refused where it is given.  A
   derived quantity that is still not finite is refused by the style that
   derives it, naming its inputs.  Not a style.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_CHECK_H
#define LMP_SALTDEM_CHECK_H

#include "error.h"
#include "lammps.h"
#include "utils.h"

#include <cmath>
#include <string>

namespace LAMMPS_NS {
namespace SaltDEM {

  constexpr double MAX_VALUE = 1e100;    // largest magnitude of a coefficient
  // the first value of a SaltDEM style's restart data, followed by the style's layout version
  // (pair styles: PairSaltdem::RESTART_MARK, the same value)
  constexpr double RESTART_MARK = -20261214.0;
  constexpr double MIN_VALUE = 1e-100;    // smallest magnitude of a non-zero coefficient

  inline bool in_bounds(double v)
  {
    const double a = std::fabs(v);
    return std::isfinite(v) && (a == 0.0 || (a >= MIN_VALUE && a <= MAX_VALUE));
  }

  /* v must be in bounds; `what` names it with its style, e.g. "Pair style saltdem/viscous: eta" */
  inline double check_bounds(const char *file, int line, double v, const std::string &what,
                             LAMMPS_NS::LAMMPS *lmp)
  {
    if (!in_bounds(v))
      lmp->error->all(
          file, line,
          "{} = {} is not a usable value: SaltDEM coefficients must be finite and 0 or "
          "of a magnitude in [{:g}, {:g}] (its products with the scene's masses, lengths "
          "and time step would overflow or vanish); give it in the units of the deck",
          what, v, MIN_VALUE, MAX_VALUE);
    return v;
  }

  /* utils::numeric, then check_bounds */
  inline double numeric(const char *file, int line, const char *str, const std::string &what,
                        LAMMPS_NS::LAMMPS *lmp)
  {
    return check_bounds(file, line, LAMMPS_NS::utils::numeric(file, line, str, false, lmp), what,
                        lmp);
  }

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
