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

   fix saltdem/nve: velocity-Verlet for discs (2D, I = m r^2/2) and spheres
   (3D, I = 2 m r^2/5) with an optional inertia factor S.  The integrator
   divides forces and torques by S*m and S*I while gravity and all contact
   forces keep their true values: inertia is scaled, weight is not.  In a
   quasi-static viscous flow (Re << 1) this leaves the flow unchanged and
   lets an explicit dashpot of viscosity eta run at S times the time step
   (see pair saltdem/viscous).  It also stops the run with a clear message
   as soon as a velocity is no longer finite.
------------------------------------------------------------------------- */

#include "fix_saltdem_nve.h"

#include "saltdem_check.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "output.h"
#include "thermo.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemNVE::FixSaltdemNVE(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), inertia(1.0), check_every(100)
{
  time_integrate = 1;
  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("fix {} {}", style, arg[iarg]), error);
    if (strcmp(arg[iarg], "inertia") == 0) {
      inertia = SaltDEM::numeric(FLERR, arg[iarg + 1], fmt::format("Fix {}: inertia", style), lmp);
      if (inertia < 1.0)
        error->all(FLERR, "Fix {}: inertia {} must be >= 1 (1 = true inertia)", style, inertia);
    } else if (strcmp(arg[iarg], "check") == 0) {
      check_every = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (check_every < 0) error->all(FLERR, "Fix {}: check {} must be >= 0", style, check_every);
    } else
      error->all(FLERR, "Fix {}: unknown keyword '{}' (expected: inertia, check)", style,
                 arg[iarg]);
    iarg += 2;
  }
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "Fix {} requires atom style sphere (radius, rmass, omega, torque)", style);
}

int FixSaltdemNVE::setmask()
{
  return INITIAL_INTEGRATE | FINAL_INTEGRATE;
}

void FixSaltdemNVE::init()
{
  reset_dt();
  inertia_factor = (domain->dimension == 2) ? 0.5 : 0.4;
  if (group->count(igroup) == 0)
    error->all(FLERR,
               "Fix {} {}: group {} has no atoms, nothing would be integrated; check "
               "the group definition (or unfix {})",
               style, id, group->names[igroup], id);

  // a disc without radius or mass has no finite inertia: name it now, not as a NaN later
  bigint nbad = 0;
  tagint first = MAXTAGINT;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) &&
        !(atom->radius[i] > 0.0 && atom->rmass[i] > 0.0 && std::isfinite(atom->radius[i]) &&
          std::isfinite(atom->rmass[i]))) {
      nbad++;
      first = MIN(first, atom->tag[i]);
    }
  bigint nbadall;
  tagint firstall;
  MPI_Allreduce(&nbad, &nbadall, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  MPI_Allreduce(&first, &firstall, 1, MPI_LMP_TAGINT, MPI_MIN, world);
  if (nbadall)
    error->all(FLERR,
               "Fix {} {}: {} atom(s) of group {} have a radius or mass that is not "
               "> 0 (the first is atom {}); give every integrated disc a diameter and a mass "
               "('set ... diameter', 'set ... density/disc') before the run",
               style, id, nbadall, group->names[igroup], firstall);
}

void FixSaltdemNVE::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
}

/* velocity-Verlet: half-kick of v and omega (forces and torques over S m
   and S I), then (initial) the drift of x.  DIM 2: only x, y and the spin
   about z move, so the z parts stay at the zero LAMMPS creates 2D atoms with
   (what fix enforce2d would enforce for these atoms, at no extra pass).
   Every atom on its own: a range of them gives the numbers of the whole loop. */

template <int DIM, bool DRIFT> void FixSaltdemNVE::integrate(int ifrom, int ito)
{
  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **omega = atom->omega, **torque = atom->torque;
  const double *rmass = atom->rmass, *radius = atom->radius;
  const int *mask = atom->mask;
  const double dtfs = dtf / inertia;
  const double dtir = dtfs / inertia_factor;
  for (int i = ifrom; i < ito; i++) {
    if (!(mask[i] & groupbit)) continue;
    const double dtfm = dtfs / rmass[i];
    const double dtirotate = dtir / (rmass[i] * radius[i] * radius[i]);
    for (int k = 0; k < DIM; k++) v[i][k] += dtfm * f[i][k];
    if (DIM == 3) {
      omega[i][0] += dtirotate * torque[i][0];
      omega[i][1] += dtirotate * torque[i][1];
    }
    omega[i][2] += dtirotate * torque[i][2];
    if (DRIFT)
      for (int k = 0; k < DIM; k++) x[i][k] += dtv * v[i][k];
  }
}

void FixSaltdemNVE::integrate_range(int ifrom, int ito, bool drift)
{
  if (domain->dimension == 2) {
    if (drift)
      integrate<2, true>(ifrom, ito);
    else
      integrate<2, false>(ifrom, ito);
  } else {
    if (drift)
      integrate<3, true>(ifrom, ito);
    else
      integrate<3, false>(ifrom, ito);
  }
}

void FixSaltdemNVE::integrate_all(bool drift)
{
  integrate_range(0, atom->nlocal, drift);
}

void FixSaltdemNVE::initial_integrate(int)
{
  integrate_all(true);
}

void FixSaltdemNVE::final_integrate()
{
  integrate_all(false);
  if (check_every && update->ntimestep % check_every == 0) check_finite();
}

/* a NaN or Inf never passes silently: name the atom, its type and the step; nor does the
   loss of atoms through a non-periodic boundary */

void FixSaltdemNVE::check_finite()
{
  double **x = atom->x, **v = atom->v;
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    if (!std::isfinite(v[i][0] + v[i][1] + v[i][2] + x[i][0] + x[i][1] + x[i][2]))
      error->one(FLERR,
                 "Fix {}: atom {} (type {}) has a non-finite position or velocity at "
                 "step {}: the run is numerically unstable. Reduce the timestep (pair styles "
                 "saltdem/* report their stable limit) or raise the inertia of viscous discs",
                 style, atom->tag[i], atom->type[i], update->ntimestep);
  }

  // LAMMPS deletes an atom that leaves through a non-periodic boundary and by default reports
  // it only at the next thermo output, possibly many steps (and dump frames) later
  if (output->thermo && output->thermo->lostflag == Thermo::ERROR) {
    bigint n = atom->nlocal, ntotal;
    MPI_Allreduce(&n, &ntotal, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    // LAMMPS also drops an atom that jumps past the neighbouring sub-domains in one step
    if (ntotal != atom->natoms && domain->nonperiodic == 0)
      error->all(FLERR,
                 "Fix {}: {} atom(s) lost by step {} (original {}, current {}) in a "
                 "periodic box: they jumped farther than a sub-domain in one step, a numerical "
                 "blow-up. Reduce the timestep (pair styles saltdem/* report their stable "
                 "limit) or find the force that is not checked (e.g. another fix)",
                 style, atom->natoms - ntotal, update->ntimestep, atom->natoms, ntotal);
    if (ntotal != atom->natoms)
      error->all(FLERR,
                 "Fix {}: {} atom(s) lost by step {} (original {}, current {}): discs "
                 "left the box through a non-periodic boundary (or, after a numerical blow-up, "
                 "jumped past a sub-domain). Enclose the scene with wall discs, enlarge the box, "
                 "make that boundary shrink-wrapped ('boundary ... m'), or accept losses with "
                 "'thermo_modify lost ignore'",
                 style, atom->natoms - ntotal, update->ntimestep, atom->natoms, ntotal);
  }
}

void *FixSaltdemNVE::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "inertia") == 0) return (void *) &inertia;
  return nullptr;
}
