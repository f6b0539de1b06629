/* ----------------------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   fix saltdem/fault: the hanging wall of a basement normal fault.  The
   group (the hanging-wall wall discs) moves rigidly down-dip at a given
   rate until a target displacement, then stops, or ends the run.  The
   discs carry the fault velocity, so viscous and frictional contacts see a
   moving, no-slip boundary.  Reports displacement, heave and throw.
------------------------------------------------------------------------- */

#include "fix_saltdem_fault.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "timer.h"
#include "update.h"

#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemFault::FixSaltdemFault(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), dip(0.0), rate(0.0), target(0.0), end_run(0), disp(0.0)
{
  const char *usage = "fix ID group saltdem/fault dip D rate V target T [toward right|left] "
                      "[at_target stop|end]";
  int sense = 1;
  int iarg = 3;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("fix saltdem/fault {}", arg[iarg]), error);
    const std::string kw = arg[iarg], val = arg[iarg + 1];
    if (kw == "dip") dip = utils::numeric(FLERR, val, false, lmp);
    else if (kw == "rate") rate = utils::numeric(FLERR, val, false, lmp);
    else if (kw == "target") target = utils::numeric(FLERR, val, false, lmp);
    else if (kw == "toward") {
      if (val == "right") sense = 1;
      else if (val == "left") sense = -1;
      else error->all(FLERR, "Fix saltdem/fault: toward '{}' must be right or left", val);
    } else if (kw == "at_target") {
      if (val == "stop") end_run = 0;
      else if (val == "end") end_run = 1;
      else error->all(FLERR, "Fix saltdem/fault: at_target '{}' must be stop or end", val);
    } else
      error->all(FLERR, "Fix saltdem/fault: unknown keyword '{}'; usage: {}", kw, usage);
    iarg += 2;
  }
  if (dip <= 0.0 || dip >= 90.0)
    error->all(FLERR, "Fix saltdem/fault: dip = {} must be in (0, 90) degrees; usage: {}", dip, usage);
  if (rate <= 0.0) error->all(FLERR, "Fix saltdem/fault: rate = {} must be > 0 (m/s); usage: {}", rate, usage);
  if (target <= 0.0) error->all(FLERR, "Fix saltdem/fault: target = {} must be > 0 (m); usage: {}", target, usage);
  if (domain->dimension != 2) error->all(FLERR, "Fix saltdem/fault requires dimension 2");

  // the hanging wall of a fault dipping toward +x (right) moves down and right
  const double a = dip * M_PI / 180.0;
  dir[0] = sense * cos(a);
  dir[1] = -sin(a);
  dir[2] = 0.0;

  time_integrate = 1;
  vector_flag = 1;
  size_vector = 3;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
}

int FixSaltdemFault::setmask()
{
  return INITIAL_INTEGRATE;
}

void FixSaltdemFault::init()
{
  if (group->count(igroup) == 0)
    error->all(FLERR, "Fix saltdem/fault {}: group {} has no atoms", id, group->names[igroup]);
}

/* the discs carry the velocity of the block (contacts see a moving wall) */

void FixSaltdemFault::set_velocity(double speed)
{
  double **v = atom->v, **omega = atom->omega;
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit) {
      for (int k = 0; k < 3; k++) v[i][k] = speed * dir[k];
      if (omega) omega[i][0] = omega[i][1] = omega[i][2] = 0.0;
    }
}

void FixSaltdemFault::setup(int)
{
  set_velocity(disp < target ? rate : 0.0);
}

void FixSaltdemFault::initial_integrate(int)
{
  const double step = MIN(rate * update->dt, target - disp);
  if (step <= 0.0) {
    set_velocity(0.0);
    if (end_run) timer->force_timeout();
    return;
  }
  double **x = atom->x;
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++)
    if (mask[i] & groupbit)
      for (int k = 0; k < 3; k++) x[i][k] += step * dir[k];
  disp += step;
  set_velocity(disp < target ? rate : 0.0);
  if (disp >= target && comm->me == 0)
    utils::logmesg(lmp, "fix saltdem/fault {}: target displacement {} m reached at step {}\n", id,
                   target, update->ntimestep);
  if (disp >= target && end_run) timer->force_timeout();
}

/* 1 displacement along the fault, 2 heave (horizontal), 3 throw (vertical) */

double FixSaltdemFault::compute_vector(int n)
{
  if (n == 0) return disp;
  if (n == 1) return disp * fabs(dir[0]);
  return disp * fabs(dir[1]);
}

/* the motion is prescribed: pair styles treat the discs as walls */

void *FixSaltdemFault::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "prescribed") == 0) return (void *) &rate;
  return nullptr;
}

void FixSaltdemFault::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    int size = sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(&disp, sizeof(double), 1, fp);
  }
}

void FixSaltdemFault::restart(char *buf)
{
  memcpy(&disp, buf, sizeof(double));
}
