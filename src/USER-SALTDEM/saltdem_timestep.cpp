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

   saltdem/timestep F [substeps N] [implicit yes|no [tolerance T] [maxiter N]]: sets the time
   step to F times the smallest stable limit of the SaltDEM pair styles (alone or in pair
   hybrid) for the present atoms, coefficients and integrators - the limit their run-time check
   enforces - so that a deck states its margin instead of a number that is right for one
   resolution only.  substeps N and implicit yes|no (with its solver's tolerance and maxiter)
   first set the viscous sub-steps or implicit viscosity of pair saltdem/viscous (also of a
   style read from a restart file).
------------------------------------------------------------------------- */

#include "saltdem_timestep.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "pair_saltdem.h"
#include "saltdem_check.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

void SaltdemTimestep::command(int narg, char **arg)
{
  const char *usage = "saltdem/timestep F [substeps N] [implicit yes|no [tolerance T] [maxiter N]]";
  if (narg < 1 || narg % 2 == 0)
    error->all(FLERR, "Illegal saltdem/timestep command: usage: {}", usage);
  if (domain->box_exist == 0)
    error->all(FLERR, "saltdem/timestep command before simulation box is defined");
  const double frac = SaltDEM::numeric(FLERR, arg[0], "saltdem/timestep: fraction F", lmp);
  if (!(frac > 0.0 && frac <= 1.0))
    error->all(FLERR, "saltdem/timestep: fraction {} of the stable limit must be in (0, 1]", frac);

  // the smallest limit over every SaltDEM pair style present (alone or the sub-styles of a
  // hybrid): the same as the styles' own check at each run; a limit that is not a finite
  // positive number (zero or infinite: a coefficient or mass out of range) stops here
  const auto styles = PairSaltdem::saltdem_styles(lmp);
  if (styles.empty())
    error->all(FLERR,
               "saltdem/timestep needs a SaltDEM pair style (saltdem/cohesive, "
               "saltdem/viscous; alone or in pair_style hybrid) with its coefficients set");
  // substeps N: the viscous sub-steps of every style that has them (saltdem/viscous), which
  // raise its viscous limit N-fold; implicit yes: its implicit viscosity, which has no limit
  // (implicit first: a style that turns it off may then take sub-steps)
  int nsub = -1, implicit = -1, maxiter = -1;
  double tol = -1.0;
  for (int iarg = 1; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg], "substeps") == 0)
      nsub = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
    else if (strcmp(arg[iarg], "tolerance") == 0) {
      tol = SaltDEM::numeric(FLERR, arg[iarg + 1], "saltdem/timestep: tolerance", lmp);
      if (!(tol > 0.0 && tol < 1.0))
        error->all(FLERR, "saltdem/timestep: tolerance {} must be in (0, 1)", tol);
    } else if (strcmp(arg[iarg], "maxiter") == 0) {
      maxiter = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxiter < 1 || maxiter > 100000)
        error->all(FLERR, "saltdem/timestep: maxiter {} must be in [1, 100000]", maxiter);
    } else if (strcmp(arg[iarg], "implicit") == 0) {
      if (strcmp(arg[iarg + 1], "yes") != 0 && strcmp(arg[iarg + 1], "no") != 0)
        error->all(FLERR, "saltdem/timestep: implicit '{}' must be yes or no", arg[iarg + 1]);
      implicit = strcmp(arg[iarg + 1], "yes") == 0;
    } else
      error->all(FLERR, "saltdem/timestep: unknown keyword '{}'; usage: {}", arg[iarg], usage);
  }
  if ((tol > 0.0 || maxiter > 0) && implicit != 1)
    error->all(FLERR,
               "saltdem/timestep: tolerance and maxiter are options of implicit yes; add it "
               "(usage: {})",
               usage);
  if (implicit >= 0) {
    bool any = false;
    for (auto pair : styles) any = pair->set_implicit(implicit == 1, tol, maxiter) || any;
    if (!any)
      error->all(FLERR,
                 "saltdem/timestep: implicit given, but no pair style has an implicit viscosity "
                 "(saltdem/viscous)");
  }
  if (nsub >= 0) {
    bool any = false;
    for (auto pair : styles) any = pair->set_substeps(nsub) || any;
    if (!any)
      error->all(FLERR,
                 "saltdem/timestep: substeps {} given, but no pair style has viscous sub-steps "
                 "(saltdem/viscous)",
                 nsub);
  }
  // the coefficients of every type pair as the run's init_one() will make them (mixed,
  // derived): the limit is computed from those
  for (auto pair : styles) pair->init_coeffs();
  const auto lim = PairSaltdem::smallest_limit(lmp, "saltdem/timestep: ");
  if (!lim.pair)
    error->all(FLERR,
               "saltdem/timestep: no stable limit applies (no integrated particles "
               "interact through a SaltDEM pair style yet, or its coefficients are not set): set "
               "the time step with 'timestep'");
  const double best = lim.dt;
  const std::string &why = lim.why;
  const std::string style = lim.pair->name_of();

  const double dt = frac * best;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "saltdem/timestep: timestep {:.6g} = {} of the stable limit {:.6g} of "
                   "pair style {} ({})\n",
                   dt, frac, best, style, why);
  input->one(fmt::format("timestep {:.17g}", dt));
}
