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

   Prescribed rigid motion of blocks of wall discs (basement blocks, end
   walls), shared by fix saltdem/fault, saltdem/keystone and saltdem/tiltwall.
   Every step the blocks are translated by rate*dt times their unit velocity
   until the drive displacement reaches the target; the last step is
   shortened so that it lands on the target exactly.  The discs carry the
   block velocity, so viscous and frictional contacts see moving, no-slip
   walls, and answer extract("prescribed") so that pair styles treat them as
   walls of unbounded mass.  The displacement goes to restart files.
------------------------------------------------------------------------- */

#include "fix_saltdem_motion.h"

#include "saltdem_check.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "timer.h"
#include "update.h"

#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;
using namespace FixConst;

FixSaltdemMotion::FixSaltdemMotion(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), rate(0.0), target(0.0), end_run(0), ended(0), disp(0.0), sense(1),
    has_toward(0), warned(0), tapered(0), taper_z{0.0, 0.0}
{
  time_integrate = 1;
  vector_flag = 1;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
}

void FixSaltdemMotion::parse(int narg, char **arg)
{
  for (int iarg = 3; iarg < narg;) {
    if (strcmp(arg[iarg], "taper") == 0) {
      if (iarg + 3 > narg)
        utils::missing_cmd_args(FLERR, fmt::format("fix {} taper", style), error);
      taper_z[0] = number_arg("taper z0", arg[iarg + 1]);
      taper_z[1] = number_arg("taper z1", arg[iarg + 2]);
      tapered = 1;
      iarg += 3;
      continue;
    }
    const int taken = (iarg + 1 < narg && parse_common(arg[iarg], arg[iarg + 1]))
        ? 2
        : parse_args(iarg, narg, arg);
    if (taken == 0)
      error->all(FLERR, "Fix {}: unknown keyword '{}'; usage: {}", style, arg[iarg], usage);
    iarg += taken;
  }
  if (rate <= 0.0)
    error->all(FLERR, "Fix {}: rate = {} must be > 0 (m/s); usage: {}", style, rate, usage);
  if (target <= 0.0)
    error->all(FLERR, "Fix {}: target = {} must be > 0 (m); usage: {}", style, target, usage);
  if (tapered && domain->dimension != 3)
    error->all(FLERR,
               "Fix {}: taper scales the motion along z (strike), a 3D option; this deck is 2D",
               style);
  if (tapered && taper_z[0] == taper_z[1])
    error->all(FLERR,
               "Fix {}: taper z0 = z1 = {}: give the z where the motion is whole and the "
               "z where it has died out",
               style, taper_z[0]);
}

int FixSaltdemMotion::parse_common(const std::string &kw, const std::string &val)
{
  if (kw == "rate")
    rate = number_arg("rate", val.c_str());
  else if (kw == "target")
    target = number_arg("target", val.c_str());
  else if (kw == "at_target") {
    if (val == "stop")
      end_run = 0;
    else if (val == "end")
      end_run = 1;
    else
      error->all(FLERR, "Fix {}: at_target '{}' must be stop or end", style, val);
  } else if (kw == "toward" && has_toward) {
    if (val == "right")
      sense = 1;
    else if (val == "left")
      sense = -1;
    else
      error->all(FLERR, "Fix {}: toward '{}' must be right or left", style, val);
  } else
    return 0;
  return 1;
}

int FixSaltdemMotion::parse_args(int iarg, int narg, char **arg)
{
  if (iarg + 2 > narg)
    utils::missing_cmd_args(FLERR, fmt::format("fix {} {}", style, arg[iarg]), error);
  return parse_keyword(arg[iarg], arg[iarg + 1]) ? 2 : 0;
}

double FixSaltdemMotion::number_arg(const std::string &what, const char *val)
{
  return SaltDEM::numeric(FLERR, val, fmt::format("Fix {}: {}", style, what), lmp);
}

FixSaltdemMotion::Block FixSaltdemMotion::translation(int igroup, double vx, double vy)
{
  return {igroup, {vx, vy, 0.0}, 0.0, {0.0, 0.0}, 0.0, std::numeric_limits<double>::infinity(), -1};
}

void FixSaltdemMotion::link_phases()
{
  const int n = blocks.size();
  for (int k = 0; k < n; k++) {
    blocks[k].next = -1;
    for (int j = k + 1; j < n && blocks[k].igroup >= 0; j++)
      if (blocks[j].igroup == blocks[k].igroup) {
        blocks[k].next = j;
        break;
      }
  }
}

void FixSaltdemMotion::carry(int k, double d, const double x0[2], double x[2], double &turn) const
{
  x[0] = x0[0];
  x[1] = x0[1];
  turn = 0.0;
  for (; k >= 0; k = blocks[k].next) {
    const Block &b = blocks[k];
    const double a = active(b, d), c = cos(b.omega * a), s = sin(b.omega * a);
    const double dx = x[0] - b.pivot[0], dy = x[1] - b.pivot[1];
    double p[2];
    pivot_at(b, d, p);
    x[0] = p[0] + c * dx - s * dy;
    x[1] = p[1] + s * dx + c * dy;
    turn += b.omega * a;
  }
}

double FixSaltdemMotion::active(const Block &b, double d)
{
  return MAX(MIN(d, b.to) - b.from, 0.0);
}

void FixSaltdemMotion::pivot_at(const Block &b, double d, double p[2])
{
  const double a = active(b, d);
  p[0] = b.pivot[0] + a * b.vel[0];
  p[1] = b.pivot[1] + a * b.vel[1];
}

double FixSaltdemMotion::angle_arg(const std::string &kw, const std::string &val)
{
  const double a = number_arg(kw, val.c_str());
  if (a <= 0.0 || a >= 90.0)
    error->all(FLERR, "Fix {}: {} = {} must be in (0, 90) degrees; usage: {}", style, kw, a, usage);
  return a;
}

int FixSaltdemMotion::group_arg(const std::string &kw, const std::string &val)
{
  const int g = group->find(val);
  if (g < 0) error->all(FLERR, "Fix {}: {} group '{}' does not exist", style, kw, val);
  return g;
}

int FixSaltdemMotion::setmask()
{
  return INITIAL_INTEGRATE;
}

void FixSaltdemMotion::init()
{
  link_phases();
  if (group->count(igroup) == 0)
    error->all(FLERR, "Fix {} {}: group {} has no atoms", style, id, group->names[igroup]);
  for (const auto &b : blocks)
    if (b.igroup >= 0 && group->count(b.igroup) == 0)
      error->all(FLERR, "Fix {} {}: block group {} has no atoms", style, id,
                 group->names[b.igroup]);

  if (tapered && domain->zperiodic)
    error->all(FLERR,
               "Fix {} {}: taper in a box periodic in z: the moving walls would meet walls of "
               "another throw across the z boundary; make z non-periodic (boundary ... f) with "
               "end walls",
               style, id);
  for (const auto &b : blocks)
    if (tapered && b.omega != 0.0)
      error->all(FLERR,
                 "Fix {} {}: taper scales translations along strike; a block that turns "
                 "(rotate, tilt) cannot be tapered",
                 style, id);
  check_travel();

  // the step of the drive, here since the time step may change after the fix is defined
  const double step = rate * update->dt;
  if (!std::isfinite(step) || step > target)
    error->all(FLERR,
               "Fix {} {}: one time step moves the blocks by rate x dt = {} x {} = {} m, beyond "
               "the target {} m: the whole motion would happen in a single jump. Lower the rate "
               "or the time step",
               style, id, rate, update->dt, step, target);

  // the walls jump through discs when a step moves a block by a good part of the smallest
  // radius of the scene (the fastest block: the right block of a keystone moves at 2 cos D)
  double speed = 0.0;
  for (const auto &b : blocks) speed = MAX(speed, block_speed(b));
  double rmin = DBL_MAX, rminall;
  if (atom->radius_flag)
    for (int i = 0; i < atom->nlocal; i++)
      if (atom->radius[i] > 0.0) rmin = MIN(rmin, atom->radius[i]);
  MPI_Allreduce(&rmin, &rminall, 1, MPI_DOUBLE, MPI_MIN, world);
  if (!warned && rminall < DBL_MAX && speed * step > JUMP_FRACTION * rminall) {
    warned = 1;
    if (comm->me == 0)
      error->warning(FLERR,
                     "Fix {} {}: one time step moves a block by {:.4g} m (rate x dt = {:.4g} x "
                     "{:.4g} at {:.3g} x the rate), more than {} of the smallest disc radius "
                     "{:.4g} m: the walls jump through discs. Lower the rate or the time step",
                     style, id, speed * step, rate, update->dt, speed, JUMP_FRACTION, rminall);
  }
}

/* before the drive starts: every disc of the blocks stays in the box (its non-periodic
   directions) over the whole motion, checked at the phases' ends and at the target (a block
   turns by less than a half turn per phase) */

void FixSaltdemMotion::check_travel()
{
  if (disp > 0.0) return;
  std::vector<double> ds = {target};
  for (const auto &b : blocks) {
    ds.push_back(MIN(b.from, target));
    ds.push_back(MIN(b.to, target));
  }
  double **x = atom->x;
  const double *lo = domain->boxlo, *hi = domain->boxhi;
  double worst = 0.0, where[2] = {0.0, 0.0};
  for (int i = 0; i < atom->nlocal; i++) {
    const int k = block_of(i);
    if (k < 0) continue;
    for (double d : ds) {
      double xe[2], turn;
      carry(k, d, x[i], xe, turn);
      for (int dim = 0; dim < 2; dim++) {
        if (domain->periodicity[dim]) continue;
        const double out = MAX(lo[dim] - xe[dim], xe[dim] - hi[dim]);
        if (out > worst) {
          worst = out;
          where[0] = xe[0];
          where[1] = xe[1];
        }
      }
    }
  }
  struct {
    double out;
    int rank;
  } mine = {worst, comm->me}, all;
  MPI_Allreduce(&mine, &all, 1, MPI_DOUBLE_INT, MPI_MAXLOC, world);
  if (all.out <= 0.0) return;
  MPI_Bcast(where, 2, MPI_DOUBLE, all.rank, world);
  error->all(FLERR,
             "Fix {} {}: the motion to the target {} m takes wall discs out of the box (to "
             "({:.6g}, {:.6g}), {:.4g} outside [{:.6g}, {:.6g}] x [{:.6g}, {:.6g}]); enlarge the "
             "box (change_box) or lower the target",
             style, id, target, where[0], where[1], all.out, lo[0], hi[0], lo[1], hi[1]);
}

/* the block's fastest disc per unit of drive rate: its translation plus its turn times the
   largest distance of its discs from the pivot (where the pivot is now) */

double FixSaltdemMotion::block_speed(const Block &b)
{
  double speed = sqrt(b.vel[0] * b.vel[0] + b.vel[1] * b.vel[1] + b.vel[2] * b.vel[2]);
  if (b.omega == 0.0) return speed;
  double p[2];
  pivot_at(b, disp, p);
  double r2 = 0.0, r2all;
  double **x = atom->x;
  const int k = &b - blocks.data();
  for (int i = 0; i < atom->nlocal; i++)
    if (in_chain(block_of(i), k)) {
      const double dx = x[i][0] - p[0], dy = x[i][1] - p[1];
      r2 = MAX(r2, dx * dx + dy * dy);
    }
  MPI_Allreduce(&r2, &r2all, 1, MPI_DOUBLE, MPI_MAX, world);
  return speed + fabs(b.omega) * sqrt(r2all);
}

/* the first phase of local atom i's block, -1 if it is not in the fix group */

int FixSaltdemMotion::block_of(int i) const
{
  const int m = atom->mask[i];
  if (!(m & groupbit)) return -1;
  const int n = blocks.size();
  for (int k = 0; k < n; k++)
    if (blocks[k].igroup < 0 || (m & group->bitmask[blocks[k].igroup])) return k;
  return -1;
}

/* the discs take the velocity of their block's phase at the present drive displacement:
   translation plus turn about the pivot, and the phase's spin; rate 0 (stopped) or no phase
   whose window holds the drive leaves them at rest */

void FixSaltdemMotion::set_velocity(double speed)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  for (int i = 0; i < atom->nlocal; i++) {
    const int first = block_of(i);
    if (first < 0) continue;
    int k = first;
    while (k >= 0 && !(disp >= blocks[k].from && disp < blocks[k].to)) k = blocks[k].next;
    // no phase holds the drive: at rest (the first phase's velocity times 0)
    const Block *b = &blocks[k >= 0 ? k : first];
    const double s = (k >= 0 ? speed : 0.0) * along(x[i][2]);
    for (int j = 0; j < 3; j++) v[i][j] = s * b->vel[j];
    if (b->omega != 0.0) {
      double p[2];
      pivot_at(*b, disp, p);
      const double dx = x[i][0] - p[0], dy = x[i][1] - p[1];
      v[i][0] -= s * b->omega * dy;
      v[i][1] += s * b->omega * dx;
    }
    if (omega) {
      omega[i][0] = omega[i][1] = 0.0;
      omega[i][2] = s * b->omega;
    }
  }
}

void FixSaltdemMotion::setup(int)
{
  set_velocity(disp < target ? rate : 0.0);
}

/* each block moves by the part of this step's drive that falls in its window: a turn about
   its pivot where the step starts, then the translation (the exact rigid motion at constant
   velocity and spin) */

void FixSaltdemMotion::initial_integrate(int)
{
  const double step = MIN(rate * update->dt, target - disp);
  if (step <= 0.0) {
    set_velocity(0.0);
    if (end_run) end_this_run();
    return;
  }
  const int nb = blocks.size();
  phase_steps.resize(nb);
  for (int k = 0; k < nb; k++) {
    const Block &b = blocks[k];
    PhaseStep &ps = phase_steps[k];
    // a step inside the window moves by the step itself, bit for bit
    ps.ds = (disp >= b.from && disp + step <= b.to) ? step
                                                    : active(b, disp + step) - active(b, disp);
    ps.c = cos(b.omega * ps.ds);
    ps.s = sin(b.omega * ps.ds);
    pivot_at(b, disp, ps.p);
  }
  double **x = atom->x;
  for (int i = 0; i < atom->nlocal; i++) {
    const double f = along(x[i][2]);
    for (int k = block_of(i); k >= 0; k = blocks[k].next) {
      const PhaseStep &ps = phase_steps[k];
      if (ps.ds == 0.0) continue;
      const Block &b = blocks[k];
      if (b.omega != 0.0) {
        const double dx = x[i][0] - ps.p[0], dy = x[i][1] - ps.p[1];
        x[i][0] = ps.p[0] + ps.c * dx - ps.s * dy;
        x[i][1] = ps.p[1] + ps.s * dx + ps.c * dy;
      }
      for (int j = 0; j < 3; j++) x[i][j] += f * ps.ds * b.vel[j];
    }
  }
  disp += step;
  set_velocity(disp < target ? rate : 0.0);
  if (disp >= target) {
    if (comm->me == 0)
      utils::logmesg(lmp, "fix {} {}: target displacement {} m reached at step {}\n", style, id,
                     target, update->ntimestep);
    if (end_run) end_this_run();
  }
}

/* 'at_target end' stops the run through the timer, as a time limit would; the timeout is
   cleared after the run so that later run commands of the deck still run (as fix halt does) */

void FixSaltdemMotion::end_this_run()
{
  ended = 1;
  timer->force_timeout();
}

void FixSaltdemMotion::post_run()
{
  if (ended) timer->reset_timeout();
  ended = 0;
}

/* the motion is prescribed: pair styles treat the discs as walls */

void *FixSaltdemMotion::extract(const char *str, int &dim)
{
  dim = 0;
  if (strcmp(str, "prescribed") == 0) return (void *) &rate;
  return nullptr;
}

/* restart: the SaltDEM mark, the layout version, the drive displacement */

void FixSaltdemMotion::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    const double list[3] = {SaltDEM::RESTART_MARK, RESTART_VERSION, disp};
    int size = 3 * sizeof(double);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 3, fp);
  }
}

void FixSaltdemMotion::restart(char *buf)
{
  double list[3];
  memcpy(list, buf, sizeof(double));
  if (list[0] != SaltDEM::RESTART_MARK)
    error->all(FLERR,
               "Fix {} {}: the restart file was written by another SaltDEM version (its "
               "data of this fix are not marked); continue with the version that wrote it, or "
               "define the fix under another ID to start its motion from 0",
               style, id);
  memcpy(list, buf, sizeof(list));
  if (list[1] != RESTART_VERSION)
    error->all(FLERR,
               "Fix {} {}: the restart file holds this fix's data in layout version {}, "
               "this version reads layout {}",
               style, id, list[1], RESTART_VERSION);
  disp = list[2];
}
