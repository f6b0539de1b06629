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

   Internal fix SALTDEM_PLASTIC: the plastic stress of the frictional-viscous fluid particles
   of pair style saltdem/viscous (see the header and saltdem_plastic.h).
------------------------------------------------------------------------- */

#include "fix_saltdem_plastic.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_contact_viscous.h"
#include "saltdem_plastic.h"

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;
using namespace FixConst;
using SaltDEM::NSYM;

FixSaltdemPlastic::FixSaltdemPlastic(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), tau(nullptr), dtau(nullptr), ystress(nullptr), out(nullptr),
    nout(0)
{
  if (narg != 3) error->all(FLERR, "Illegal internal fix {} command", style);
  restart_peratom = 1;
  create_attribute = 1;
  peratom_flag = 1;
  nout = (domain->dimension == 2 ? 3 : 6) + 1;
  size_peratom_cols = nout;
  peratom_freq = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nmax; i++) set_arrays(i);
}

FixSaltdemPlastic::~FixSaltdemPlastic()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(tau);
  memory->destroy(dtau);
  memory->destroy(ystress);
  memory->destroy(out);
}

int FixSaltdemPlastic::setmask()
{
  return FINAL_INTEGRATE | END_OF_STEP;
}

void FixSaltdemPlastic::init()
{
  if (!pair)
    error->all(FLERR, "Fix {} {} is internal to pair style saltdem/viscous, which is not defined",
               style, id);
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Pair style {} does not support run_style respa", pair->name_of());
}

/* tau += dt d tau / dt for the owned particles, then radially back onto the yield surface of
   the strength of the same force pass (the stress of a step is that of the step before, as
   the pressure is of the density before) */

void FixSaltdemPlastic::final_integrate()
{
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  const int dim = domain->dimension;
  for (int i = 0; i < nlocal; i++) {
    double *t = tau[i];
    for (int k = 0; k < NSYM; k++) t[k] += dt * dtau[i][k];
    if (dim == 2)
      SaltDEM::plastic_return<2>(ystress[i], t);
    else
      SaltDEM::plastic_return<3>(ystress[i], t);
  }
}

/* the per-atom output of the step: the stress and how close to yield it is */

void FixSaltdemPlastic::end_of_step()
{
  const int nlocal = atom->nlocal;
  const int dim = domain->dimension;
  for (int i = 0; i < nlocal; i++) {
    for (int k = 0; k < nout - 1; k++) out[i][k] = tau[i][k];
    const double J = (dim == 2) ? SaltDEM::plastic_norm<2>(tau[i])
                                : SaltDEM::plastic_norm<3>(tau[i]);
    out[i][nout - 1] = (ystress[i] > 0.0) ? J / ystress[i] : 0.0;
  }
}

/* ---------------------------------------------------------------------- */

void FixSaltdemPlastic::grow_arrays(int nmax)
{
  memory->grow(tau, nmax, NSYM, "saltdem/plastic:tau");
  memory->grow(dtau, nmax, NSYM, "saltdem/plastic:dtau");
  memory->grow(ystress, nmax, "saltdem/plastic:ystress");
  memory->grow(out, nmax, nout, "saltdem/plastic:out");
  array_atom = out;
}

void FixSaltdemPlastic::copy_arrays(int i, int j, int)
{
  for (int k = 0; k < NSYM; k++) tau[j][k] = tau[i][k];
}

void FixSaltdemPlastic::set_arrays(int i)
{
  for (int k = 0; k < NSYM; k++) tau[i][k] = dtau[i][k] = 0.0;
  ystress[i] = 0.0;
  for (int k = 0; k < nout; k++) out[i][k] = 0.0;
}

int FixSaltdemPlastic::pack_exchange(int i, double *buf)
{
  for (int k = 0; k < NSYM; k++) buf[k] = tau[i][k];
  return NSYM;
}

int FixSaltdemPlastic::unpack_exchange(int nlocal, double *buf)
{
  for (int k = 0; k < NSYM; k++) tau[nlocal][k] = buf[k];
  return NSYM;
}

int FixSaltdemPlastic::pack_restart(int i, double *buf)
{
  // buf[0]: the number of values including itself (how other fixes skip them)
  buf[0] = NSYM + 1;
  for (int k = 0; k < NSYM; k++) buf[k + 1] = tau[i][k];
  return NSYM + 1;
}

void FixSaltdemPlastic::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  for (int k = 0; k < NSYM; k++) tau[nlocal][k] = extra[nlocal][m + 1 + k];
}

int FixSaltdemPlastic::size_restart(int)
{
  return NSYM + 1;
}

int FixSaltdemPlastic::maxsize_restart()
{
  return NSYM + 1;
}

double FixSaltdemPlastic::memory_usage()
{
  return (double) atom->nmax * (2 * NSYM + 1 + nout) * sizeof(double);
}
