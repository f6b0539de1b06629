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

   Internal fix SALTDEM_DENSITY: the continuity density of the fluid
   particles of pair style saltdem/viscous (see the header).  The pair style
   computes d rho / dt in its force pass (the pair's term of the continuity
   equation, SaltDEM::viscous_fluid_force) into drho; this fix adds
   dt d rho / dt to rho after the force pass of each step of a run, as
   LAMMPS's SPH package integrates its density in a fix.
------------------------------------------------------------------------- */

#include "fix_saltdem_density.h"

#include "pair_saltdem_viscous.h"
#include "saltdem_check.h"
#include "saltdem_contact_viscous.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemDensity::FixSaltdemDensity(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair(nullptr), rho(nullptr), drho(nullptr), restored(0)
{
  if (narg != 3) error->all(FLERR, "Illegal internal fix {} command", style);
  restart_global = 1;
  restart_peratom = 1;
  create_attribute = 1;
  peratom_flag = 1;
  size_peratom_cols = 0;
  peratom_freq = 1;
  comm_reverse = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nmax; i++) rho[i] = drho[i] = 0.0;
}

FixSaltdemDensity::~FixSaltdemDensity()
{
  if (copymode) return;
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(rho);
  memory->destroy(drho);
}

int FixSaltdemDensity::setmask()
{
  // setup_pre_force() is called for fixes with PRE_FORCE (runs) or MIN_PRE_FORCE
  // (minimizations) only; pre_force() itself does nothing
  return PRE_FORCE | MIN_PRE_FORCE | POST_FORCE | FINAL_INTEGRATE;
}

/* the pair style's viscous sub-steps or implicit step (pair_style saltdem/viscous substeps
   N > 1 or implicit yes), once every force of the step is in: both carry the other forces as
   constant, so that a steady flow keeps its viscous stress (this fix is created at the first
   run, after the deck's gravity and other force fixes) */

void FixSaltdemDensity::setup(int)
{
  pair->apply_substeps();
}

void FixSaltdemDensity::post_force(int)
{
  pair->apply_substeps();
}

/* the implicit viscous step's iterations over the run */

void FixSaltdemDensity::post_run()
{
  pair->implicit_report();
}

void FixSaltdemDensity::init()
{
  if (!pair)
    error->all(FLERR, "Fix {} {} is internal to pair style saltdem/viscous, which is not defined",
               style, id);
  if (utils::strmatch(update->integrate_style, "^respa"))
    error->all(FLERR, "Pair style {} does not support run_style respa", pair->name_of());
  const int nt = atom->ntypes;
  if ((int) rho0.size() != nt + 1) {
    rho0.resize(nt + 1, 0.0);
    h0.resize(nt + 1, 0.0);
  }
}

/* before the setup's force pass: the reference densities that are missing, and the density of
   every fluid particle that has none */

void FixSaltdemDensity::setup_pre_force(int)
{
  measure();
}

void FixSaltdemDensity::measure()
{
  if (!pair->any_fluid_pair()) return;
  const int nt = atom->ntypes;
  const int nlocal = atom->nlocal;
  const int *type = atom->type;
  const int *fluid = pair->fluid_types();

  // a fluid type whose reference density is missing, or was measured with another kernel
  auto stale = [&](int t) {
    const double h = pair->fluid_h(t);
    return fluid[t] && (rho0[t] <= 0.0 || fabs(h0[t] - h) > 1e-12 * h);
  };
  bool need = false;
  for (int t = 1; t <= nt; t++)
    if (stale(t)) need = true;

  if (restored && comm->me == 0)
    for (int t = 1; t <= nt; t++)
      if (fluid[t] && !stale(t))
        utils::logmesg(lmp,
                       "pair {}: reference density of fluid type {} = {:.15g} (from the "
                       "restart file)\n",
                       pair->name_of(), t, rho0[t]);
  restored = 0;

  if (need) {
    // the mean kernel density sum_j m_j W_ij per type over the particles whose kernel is full
    // (over all of them where none is: a layer thinner than the kernel), drho as the work
    // array, and the continuity densities that atoms already carry (an earlier run, a restart
    // file)
    std::vector<double> interior(nlocal > 0 ? nlocal : 1);
    pair->kernel_density(drho, interior.data());
    std::vector<double> sum(6 * (nt + 1), 0.0), all(6 * (nt + 1));
    for (int i = 0; i < nlocal; i++) {
      double *st = &sum[6 * type[i]];
      st[0] += drho[i];
      st[1] += 1.0;
      if (rho[i] > 0.0) {
        st[2] += rho[i];
        st[3] += 1.0;
      }
      if (interior[i] > 0.0) {
        st[4] += drho[i];
        st[5] += 1.0;
      }
    }
    MPI_Allreduce(sum.data(), all.data(), 6 * (nt + 1), MPI_DOUBLE, MPI_SUM, world);
    for (int t = 1; t <= nt; t++)
      if (stale(t) && all[6 * t + 1] > 0.0) {
        const double *at = &all[6 * t];
        const double hold = h0[t];
        rho0[t] = (at[5] > 0.0) ? at[4] / at[5] : at[0] / at[1];
        h0[t] = pair->fluid_h(t);
        if (comm->me == 0)
          utils::logmesg(lmp,
                         "pair {}: reference density of fluid type {} = {:.15g}\n  the mean "
                         "kernel density of {:.0f} of its {:.0f} particles, those with a full "
                         "kernel (of all: {:.15g})\n",
                         pair->name_of(), t, rho0[t], at[5] > 0.0 ? at[5] : at[1], at[1],
                         at[0] / at[1]);
        if (at[3] > 0.0 && comm->me == 0) {
          const double carried = at[2] / at[3];
          error->warning(FLERR,
                         "Pair style {}: the reference density of fluid type {} was measured "
                         "again ({:.6g}; its kernel h is now {:.6g}, was {:.6g}) while its "
                         "atoms carry densities from an earlier run or a restart file: their "
                         "pressure is reset (mean now {:.3g}), and a fluid under load loses "
                         "the pressure that carried it. Keep h to keep the reference density",
                         pair->name_of(), t, rho0[t], h0[t], hold,
                         SaltDEM::eos_pressure(pair->fluid_K(t), carried, rho0[t]));
        }
      }
  }
  for (int i = 0; i < nlocal; i++)
    if (fluid[type[i]] && rho[i] <= 0.0) rho[i] = rho0[type[i]];
}

/* continuity: rho += dt d rho / dt for the owned fluid particles, once the force pass of the
   step has summed d rho / dt (with newton on, the ghosts' parts come home first) */

void FixSaltdemDensity::final_integrate()
{
  if (!pair->any_fluid_pair()) return;
  if (force->newton_pair) comm->reverse_comm(this);
  const int *type = atom->type;
  const int *fluid = pair->fluid_types();
  const int nlocal = atom->nlocal;
  const double dt = update->dt;
  for (int i = 0; i < nlocal; i++)
    if (fluid[type[i]]) {
      if (rho[i] <= 0.0) rho[i] = rho0[type[i]];    // (an atom created during the run)
      rho[i] += dt * drho[i];
    }
}

/* ---------------------------------------------------------------------- */

void FixSaltdemDensity::grow_arrays(int nmax)
{
  memory->grow(rho, nmax, "saltdem/density:rho");
  memory->grow(drho, nmax, "saltdem/density:drho");
  vector_atom = rho;
}

void FixSaltdemDensity::copy_arrays(int i, int j, int)
{
  rho[j] = rho[i];
}

void FixSaltdemDensity::set_arrays(int i)
{
  rho[i] = 0.0;
}

int FixSaltdemDensity::pack_exchange(int i, double *buf)
{
  buf[0] = rho[i];
  return 1;
}

int FixSaltdemDensity::unpack_exchange(int nlocal, double *buf)
{
  rho[nlocal] = buf[0];
  return 1;
}

int FixSaltdemDensity::pack_restart(int i, double *buf)
{
  // buf[0]: the number of values including itself (how other fixes skip them)
  buf[0] = 2;
  buf[1] = rho[i];
  return 2;
}

void FixSaltdemDensity::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  rho[nlocal] = extra[nlocal][m + 1];
}

int FixSaltdemDensity::size_restart(int)
{
  return 2;
}

int FixSaltdemDensity::maxsize_restart()
{
  return 2;
}

/* global restart: the SaltDEM mark, the layout version, the number of types, then rho0 and h
   per type */

void FixSaltdemDensity::write_restart(FILE *fp)
{
  const int nt = atom->ntypes;
  std::vector<double> list(3 + 2 * nt, 0.0);
  list[0] = SaltDEM::RESTART_MARK;
  list[1] = RESTART_VERSION;
  list[2] = nt;
  for (int t = 1; t <= nt && t < (int) rho0.size(); t++) {
    list[1 + 2 * t] = rho0[t];
    list[2 + 2 * t] = h0[t];
  }
  if (comm->me == 0) {
    const int size = (int) (list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixSaltdemDensity::restart(char *buf)
{
  auto list = (double *) buf;
  if (list[0] != SaltDEM::RESTART_MARK || list[1] != RESTART_VERSION)
    error->all(FLERR,
               "Fix {}: the restart file holds the salt's densities in another layout (mark {}, "
               "version {}; this version reads {:.0f}, {}); continue with the SaltDEM version "
               "that wrote it, or start again from a data file",
               style, list[0], list[1], SaltDEM::RESTART_MARK, RESTART_VERSION);
  const int nt = static_cast<int>(list[2]);
  if (nt != atom->ntypes)
    error->all(FLERR,
               "Fix {}: the restart file holds reference densities of {} atom types, the "
               "system has {}",
               style, nt, atom->ntypes);
  rho0.assign(nt + 1, 0.0);
  h0.assign(nt + 1, 0.0);
  for (int t = 1; t <= nt; t++) {
    rho0[t] = list[1 + 2 * t];
    h0[t] = list[2 + 2 * t];
  }
  restored = 1;
}

int FixSaltdemDensity::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = drho[first + i];
  return n;
}

void FixSaltdemDensity::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int i = 0; i < n; i++) drho[list[i]] += buf[i];
}

double FixSaltdemDensity::memory_usage()
{
  return 2.0 * atom->nmax * sizeof(double);
}
