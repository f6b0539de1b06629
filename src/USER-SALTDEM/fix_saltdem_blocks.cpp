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

   fix saltdem/blocks: any number of rigid basement blocks, each with its
   own kinematics per unit of drive displacement (a translation, a slip
   along a fault of given dip, a turn about a pivot, or a translation and a
   turn) inside its own window of the drive.  The general form of
   saltdem/fault, saltdem/keystone and saltdem/tiltwall.
------------------------------------------------------------------------- */

#include "fix_saltdem_blocks.h"

#include "atom.h"
#include "error.h"
#include "group.h"

#include <cmath>
#include <cstring>
#include <limits>

using namespace LAMMPS_NS;

static constexpr double DEG = M_PI / 180.0;

FixSaltdemBlocks::FixSaltdemBlocks(LAMMPS *lmp, int narg, char **arg) :
    FixSaltdemMotion(lmp, narg, arg)
{
  usage = fmt::format(
      "fix ID group {} rate V target T [at_target stop|end] [taper Z0 Z1] block GROUP [move VX VY] "
      "[slip DIP right|left] [rotate PX PY W] [scale F] [from D0] [to D1] [block ...]",
      style);
  parse(narg, arg);
  if (blocks.empty()) error->all(FLERR, "Fix {}: no block given; usage: {}", style, usage);
  for (auto &b : blocks) {
    if (b.to == std::numeric_limits<double>::infinity()) b.to = target;
    if (b.to > target)
      error->all(FLERR,
                 "Fix {}: block {} moves to drive displacement {} m, beyond the target {} m; "
                 "lower its 'to' or raise the target",
                 style, group->names[b.igroup], b.to, target);
    if (b.from >= b.to)
      error->all(FLERR,
                 "Fix {}: block {} starts at drive displacement {} m, not before the target {} m",
                 style, group->names[b.igroup], b.from, target);
  }
  // a block given again is a later phase of its motion: after the previous one, in order
  link_phases();
  const int n = blocks.size();
  std::vector<bool> later(n, false);    // a phase some earlier phase of its block leads to
  for (int k = 0; k < n; k++) {
    const int j = blocks[k].next;
    if (j >= 0) later[j] = true;
    if (j >= 0 && blocks[j].from < blocks[k].to)
      error->all(FLERR,
                 "Fix {}: block {} is given again with a window (from {} to {}) that starts "
                 "before its previous one ends ({} to {}); give a block's phases in order, "
                 "each from where the previous one ends or later",
                 style, group->names[blocks[k].igroup], blocks[j].from, blocks[j].to,
                 blocks[k].from, blocks[k].to);
    if (!later[k]) firsts.push_back(k);
  }
  vector_flag = 1;
  size_vector = 1;
  array_flag = 1;
  size_array_rows = firsts.size();
  size_array_cols = 5;
  extarray = 0;
}

int FixSaltdemBlocks::parse_args(int iarg, int narg, char **arg)
{
  if (strcmp(arg[iarg], "block") == 0) return parse_block(iarg, narg, arg);
  return 0;
}

/* block GROUP and its keywords, up to the next 'block' or a keyword of the fix */

int FixSaltdemBlocks::parse_block(int iarg, int narg, char **arg)
{
  if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, fmt::format("fix {} block", style), error);
  const std::string name = arg[iarg + 1];
  Block b = translation(group_arg("block", name), 0.0, 0.0);
  double scale = 1.0;
  int kinematics = 0, n = iarg + 2;
  auto need = [&](int k, const char *kw) {
    if (n + k >= narg)
      error->all(FLERR, "Fix {}: block {}: '{}' needs {} values; usage: {}", style, name, kw, k,
                 usage);
  };
  auto value = [&](const char *what) {
    return number_arg(fmt::format("block {} {}", name, what), arg[++n]);
  };
  while (n < narg) {
    const std::string kw = arg[n];
    if (kw == "block" || kw == "rate" || kw == "target" || kw == "at_target") break;
    if (kw == "move") {
      need(2, "move");
      b.vel[0] += value("move VX");
      b.vel[1] += value("move VY");
      kinematics = 1;
    } else if (kw == "slip") {
      need(2, "slip");
      const double dip = value("slip DIP");
      if (dip <= 0.0 || dip >= 90.0)
        error->all(FLERR, "Fix {}: block {}: slip dip {} must be in (0, 90) degrees", style, name,
                   dip);
      const std::string side = arg[++n];
      if (side != "right" && side != "left")
        error->all(FLERR, "Fix {}: block {}: slip {} '{}': the fault must dip toward right or left",
                   style, name, dip, side);
      // the hanging wall of a fault dipping toward +x moves down and right
      const double a = dip * M_PI / 180.0;    // as fix saltdem/fault: the same bits
      b.vel[0] += (side == "right" ? 1.0 : -1.0) * cos(a);
      b.vel[1] -= sin(a);
      kinematics = 1;
    } else if (kw == "rotate") {
      need(3, "rotate");
      b.pivot[0] = value("rotate PX");
      b.pivot[1] = value("rotate PY");
      b.omega = value("rotate W") * DEG;
      kinematics = 1;
    } else if (kw == "scale") {
      need(1, "scale");
      scale = value("scale");
    } else if (kw == "from") {
      need(1, "from");
      b.from = value("from");
    } else if (kw == "to") {
      need(1, "to");
      b.to = value("to");
    } else
      error->all(FLERR, "Fix {}: block {}: unknown keyword '{}'; usage: {}", style, name, kw,
                 usage);
    n++;
  }
  if (!kinematics)
    error->all(FLERR,
               "Fix {}: block {} has no kinematics: give move VX VY, slip DIP right|left or "
               "rotate PX PY W",
               style, name);
  if (b.from < 0.0 || b.from >= b.to)
    error->all(FLERR, "Fix {}: block {}: from {} to {} must satisfy 0 <= from < to (m of drive)",
               style, name, b.from, b.to);
  for (int k = 0; k < 2; k++) b.vel[k] *= scale;
  b.omega *= scale;
  if (b.vel[0] == 0.0 && b.vel[1] == 0.0 && b.omega == 0.0)
    error->all(FLERR,
               "Fix {}: block {} does not move (zero velocity and turn); leave a static block "
               "out of the fix",
               style, name);
  blocks.push_back(b);
  return n - iarg;
}

/* every atom of the fix group lies in exactly one block */

void FixSaltdemBlocks::init()
{
  FixSaltdemMotion::init();
  const int nb = firsts.size();
  bigint none = 0;
  std::vector<bigint> both(nb * nb, 0), all(nb * nb + 1);
  int *mask = atom->mask;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    int first = -1;
    for (int k = 0; k < nb; k++)
      if (mask[i] & group->bitmask[blocks[firsts[k]].igroup]) {
        if (first < 0)
          first = k;
        else
          both[first * nb + k]++;
      }
    if (first < 0) none++;
  }
  both.push_back(none);
  MPI_Allreduce(both.data(), all.data(), nb * nb + 1, MPI_LMP_BIGINT, MPI_SUM, world);
  auto name = [&](int k) {
    return group->names[blocks[firsts[k]].igroup];
  };
  for (int j = 0; j < nb; j++)
    for (int k = 0; k < nb; k++)
      if (all[j * nb + k] > 0)
        error->all(FLERR,
                   "Fix {} {}: blocks {} and {} overlap ({} atoms in both); each wall disc "
                   "belongs to one block",
                   style, id, name(j), name(k), all[j * nb + k]);
  if (all[nb * nb] > 0)
    error->all(FLERR,
               "Fix {} {}: {} atoms of the fix group {} are in no block; give them a block or "
               "leave them out of the group",
               style, id, all[nb * nb], group->names[igroup]);
  for (int k = 0; k < nb; k++) {
    const int bit = group->bitmask[blocks[firsts[k]].igroup];
    bigint out = 0, outall;
    for (int i = 0; i < atom->nlocal; i++)
      if ((mask[i] & bit) && !(mask[i] & groupbit)) out++;
    MPI_Allreduce(&out, &outall, 1, MPI_LMP_BIGINT, MPI_SUM, world);
    if (outall > 0)
      error->all(FLERR,
                 "Fix {} {}: {} atoms of block {} are not in the fix group {}; the fix group "
                 "holds every block",
                 style, id, outall, name(k), group->names[igroup]);
  }
}

/* 1 drive displacement */

double FixSaltdemBlocks::compute_vector(int)
{
  return disp;
}

/* per block: 1 displacement of its reference point (the pivot of its first phase; any disc
   of a block that never turns), 2 heave (x), 3 throw (down), 4 turn (degrees,
   counterclockwise), 5 progress (0-1: the part of its windows done) */

double FixSaltdemBlocks::compute_array(int i, int j)
{
  const int first = firsts[i];
  double x[2], turn;
  const double *x0 = blocks[first].pivot;    // the reference point at drive 0
  carry(first, disp, x0, x, turn);
  const double dx = x[0] - x0[0], dy = x[1] - x0[1];
  if (j == 0) return sqrt(dx * dx + dy * dy);
  if (j == 1) return dx;
  if (j == 2) return -dy;
  if (j == 3) return turn / DEG;
  double done = 0.0, length = 0.0;
  for (int k = first; k >= 0; k = blocks[k].next) {
    done += active(blocks[k], disp);
    length += blocks[k].to - blocks[k].from;
  }
  return done / length;
}
