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

   fix saltdem/sediment: syn-tectonic sedimentation and erosion.  Every N
   steps, or every given amount of drive displacement, new cover discs are
   deposited into the accommodation space below a base level: to the base
   level (fill) or at a rate of disc area per unit length and time (rate).
   Their radii follow the scene's radius law; each is put, at rest, into the
   lowest pocket of the surface where it touches two discs and overlaps no
   other by more than a tolerance, so it settles without a fall.  All ranks
   place the same discs: they gather the discs near the surface, sorted by
   atom ID, and draw from one seeded generator.  Each new disc gets the
   interval's number (its epoch) in a per-atom integer, for growth strata.
   Optionally the discs of a group above an erosion level are deleted.
   The generator, the epoch and the counters go to restart files.
------------------------------------------------------------------------- */

#include "fix_saltdem_sediment.h"

#include "pair_saltdem.h"
#include "saltdem_check.h"

#include "arg_info.h"
#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "group.h"
#include "input.h"
#include "math_const.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"
#include "variable.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <numeric>

using namespace LAMMPS_NS;
using namespace FixConst;
using MathConst::MY_PI;

// exponent of the paper's radius law p(r) ~ r^-Q (tools/pack.in, dist paper)
static constexpr double PAPER_Q = 1.7522293;
// a restart record starts with this number (and its layout version)
static constexpr double RESTART_TAG = 18003.0;
static constexpr double RESTART_TAG_V1 = 18002.0;    // before the window (no last_xlo, last_xhi)
// radii drawn in a row that find no room before an interval stops depositing
static constexpr int MAX_REDRAWS = 50;

/* ---------------------------------------------------------------------- */

FixSaltdemSediment::FixSaltdemSediment(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), mode(MODE_NONE), rate(0.0), ntype(0), rmin(0.0), rmax(0.0),
    dist(DIST_UNIFORM), density(0.0), tol(0.01), maxper(1000000), drive_kind(DRIVE_STEPS),
    every(0.0), nsteps(0), drive_index(0), drive_ivar(-1), drive_fix(nullptr), erode_igroup(-1),
    erode_groupbit(0), epoch_index(-1), epoch_offset(0), window_given(0), xlo(0.0), xhi(0.0),
    foreset(-1.0), length(0.0), length_given(0), settle_steps(0), settle_gamma(0.0), rng(0),
    epoch(0), ndep(0.0), nero(0.0), adep(0.0), aero(0.0), abyp(0.0), carry(0.0), t_last(0.0),
    t_last_set(0), next_drive(0.0), next_set(0), last_level(0.0), last_n(0.0), last_area(0.0),
    last_xlo(0.0), last_xhi(0.0), pending(0), drive_at_decision(0.0)
{
  up[0] = up[1] = along[0] = along[1] = 0.0;
  usage = fmt::format(
      "fix ID group {} fill|rate R|none type T base LEVEL every N [drive SOURCE] rmin R1 rmax R2 "
      "density RHO seed S [dist uniform|paper] [overlap TOL] [epoch i_NAME] [offset K] "
      "[erode LEVEL] [erode_group G] [group G] [x XLO XHI] [foreset S] [length L] [down DX DY] "
      "[settle N GAMMA] [maxper N]",
      style);
  if (domain->dimension != 2) error->all(FLERR, "Fix {} requires dimension 2 (discs)", style);
  if (domain->triclinic) error->all(FLERR, "Fix {} requires an orthogonal box", style);
  if (domain->xperiodic || domain->yperiodic)
    error->all(FLERR,
               "Fix {}: the box must be non-periodic in x and y (the model's walls bound "
               "the section)",
               style);
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR, "Fix {} requires per-atom radius, rmass and omega: use 'atom_style sphere'",
               style);
  if (narg < 4) utils::missing_cmd_args(FLERR, fmt::format("fix {}", style), error);

  int iarg = 3;
  const std::string m = arg[iarg];
  if (m == "fill") {
    mode = MODE_FILL;
    iarg += 1;
  } else if (m == "none") {
    mode = MODE_NONE;
    iarg += 1;
  } else if (m == "rate") {
    if (iarg + 2 > narg) utils::missing_cmd_args(FLERR, fmt::format("fix {} rate", style), error);
    mode = MODE_RATE;
    rate = SaltDEM::numeric(FLERR, arg[iarg + 1], fmt::format("Fix {}: rate", style), lmp);
    if (rate < 0.0)
      error->all(FLERR,
                 "Fix {}: rate = {} must be >= 0 (sediment area per unit length and time, "
                 "m^2/(m s))",
                 style, rate);
    iarg += 2;
  } else
    error->all(FLERR, "Fix {}: mode '{}' must be fill, rate R or none; usage: {}", style, m, usage);

  double seed = 0.0;
  int every_given = 0;
  std::string every_text;
  auto need = [&](int n) {
    if (iarg + n >= narg)
      utils::missing_cmd_args(FLERR, fmt::format("fix {} {}", style, arg[iarg]), error);
  };
  auto num = [&](const char *kw, const char *val) {
    return SaltDEM::numeric(FLERR, val, fmt::format("Fix {}: {}", style, kw), lmp);
  };
  auto find_group = [&](const char *kw, const char *name) {
    const int g = group->find(name);
    if (g < 0) error->all(FLERR, "Fix {}: {} group '{}' does not exist", style, kw, name);
    return g;
  };

  while (iarg < narg) {
    const std::string kw = arg[iarg];
    if (kw == "type") {
      need(1);
      ntype = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (ntype < 1 || ntype > atom->ntypes)
        error->all(FLERR, "Fix {}: type {} is not an atom type (1 to {})", style, ntype,
                   atom->ntypes);
      iarg += 2;
    } else if (kw == "base") {
      need(1);
      parse_level(base, arg[iarg + 1], "base");
      if (base.kind == Level::ATOM)
        error->all(FLERR, "Fix {}: base level v_{} must be a constant or an equal-style variable",
                   style, base.name);
      iarg += 2;
    } else if (kw == "every") {
      need(1);
      every_given = 1;
      every_text = arg[iarg + 1];
      every = num("every", arg[iarg + 1]);
      if (every <= 0.0)
        error->all(FLERR,
                   "Fix {}: every = {} must be > 0 (steps, or drive displacement with "
                   "'drive')",
                   style, every);
      iarg += 2;
    } else if (kw == "drive") {
      need(1);
      ArgInfo argi(arg[iarg + 1], ArgInfo::VARIABLE | ArgInfo::FIX);
      if (argi.get_type() == ArgInfo::VARIABLE && argi.get_dim() == 0) {
        drive_kind = DRIVE_VARIABLE;
      } else if (argi.get_type() == ArgInfo::FIX && argi.get_dim() <= 1) {
        drive_kind = DRIVE_FIX;
        drive_index = argi.get_index1();
      } else
        error->all(FLERR,
                   "Fix {}: drive '{}' must be v_NAME (an equal-style variable), f_ID or "
                   "f_ID[N] (a fix's global scalar or vector element)",
                   style, arg[iarg + 1]);
      drive_name = argi.get_name();
      iarg += 2;
    } else if (kw == "rmin" || kw == "rmax") {
      need(1);
      const double r = num(kw.c_str(), arg[iarg + 1]);
      if (r <= 0.0) error->all(FLERR, "Fix {}: {} = {} must be > 0", style, kw, r);
      (kw == "rmin" ? rmin : rmax) = r;
      iarg += 2;
    } else if (kw == "dist") {
      need(1);
      const std::string d = arg[iarg + 1];
      if (d == "uniform")
        dist = DIST_UNIFORM;
      else if (d == "paper")
        dist = DIST_PAPER;
      else
        error->all(FLERR, "Fix {}: dist '{}' must be uniform or paper", style, d);
      iarg += 2;
    } else if (kw == "density") {
      need(1);
      density = num("density", arg[iarg + 1]);
      if (density <= 0.0) error->all(FLERR, "Fix {}: density = {} must be > 0", style, density);
      iarg += 2;
    } else if (kw == "seed") {
      need(1);
      seed = utils::numeric(FLERR, arg[iarg + 1], false, lmp);
      if (seed <= 0.0 || seed != std::floor(seed) || seed > 9.0e15)
        error->all(FLERR, "Fix {}: seed = {} must be a positive integer", style, arg[iarg + 1]);
      iarg += 2;
    } else if (kw == "overlap") {
      need(1);
      tol = num("overlap", arg[iarg + 1]);
      if (tol < 0.0 || tol >= 1.0)
        error->all(FLERR,
                   "Fix {}: overlap = {} must be in [0, 1) (a fraction of the smaller "
                   "radius)",
                   style, tol);
      iarg += 2;
    } else if (kw == "epoch") {
      need(1);
      if (strncmp(arg[iarg + 1], "i_", 2) != 0 || strlen(arg[iarg + 1]) < 3)
        error->all(FLERR,
                   "Fix {}: epoch '{}' must name a per-atom integer, i_NAME (fix "
                   "property/atom)",
                   style, arg[iarg + 1]);
      epoch_name = arg[iarg + 1] + 2;
      iarg += 2;
    } else if (kw == "offset") {
      need(1);
      epoch_offset = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      if (epoch_offset < 0 || epoch_offset > 1000000000)
        error->all(FLERR, "Fix {}: offset = {} must be in [0, 1e9]", style, epoch_offset);
      iarg += 2;
    } else if (kw == "erode") {
      need(1);
      if (strcmp(arg[iarg + 1], "none") == 0)
        erode = Level();
      else
        parse_level(erode, arg[iarg + 1], "erode");
      iarg += 2;
    } else if (kw == "erode_group") {
      need(1);
      erode_igroup = find_group("erode_group", arg[iarg + 1]);
      iarg += 2;
    } else if (kw == "group") {
      need(1);
      extra_groups.push_back(find_group("group", arg[iarg + 1]));
      iarg += 2;
    } else if (kw == "x") {
      need(2);
      parse_window_end(wlo, arg[iarg + 1]);
      parse_window_end(whi, arg[iarg + 2]);
      xlo = wlo.value;
      xhi = whi.value;
      if (wlo.kind == Level::CONSTANT && whi.kind == Level::CONSTANT && xlo >= xhi)
        error->all(FLERR, "Fix {}: x {} {}: the window's low end must be below its high end", style,
                   xlo, xhi);
      window_given = 1;
      iarg += 3;
    } else if (kw == "foreset") {
      need(1);
      foreset = num("foreset", arg[iarg + 1]);
      if (foreset < 0.0)
        error->all(FLERR,
                   "Fix {}: foreset = {} must be >= 0 (the fall of the base level per unit "
                   "length outside the window, the tangent of the foreset dip)",
                   style, foreset);
      iarg += 2;
    } else if (kw == "length") {
      need(1);
      length = num("length", arg[iarg + 1]);
      if (length <= 0.0) error->all(FLERR, "Fix {}: length = {} must be > 0", style, length);
      length_given = 1;
      iarg += 2;
    } else if (kw == "down") {
      need(2);
      const double dx = num("down", arg[iarg + 1]), dy = num("down", arg[iarg + 2]);
      const double n = sqrt(dx * dx + dy * dy);
      if (!(n > 0.0) || !std::isfinite(n))
        error->all(FLERR, "Fix {}: down {} {} must be a non-zero direction (of gravity)", style, dx,
                   dy);
      up[0] = -dx / n;
      up[1] = -dy / n;
      iarg += 3;
    } else if (kw == "settle") {
      need(2);
      settle_steps = utils::inumeric(FLERR, arg[iarg + 1], false, lmp);
      settle_gamma = num("settle", arg[iarg + 2]);
      if (settle_steps < 0 || settle_gamma < 0.0)
        error->all(FLERR, "Fix {}: settle {} {}: steps and drag must be >= 0", style, settle_steps,
                   settle_gamma);
      iarg += 3;
    } else if (kw == "maxper") {
      need(1);
      maxper = utils::bnumeric(FLERR, arg[iarg + 1], false, lmp);
      if (maxper < 1) error->all(FLERR, "Fix {}: maxper = {} must be >= 1", style, maxper);
      iarg += 2;
    } else
      error->all(FLERR, "Fix {}: unknown keyword '{}'; usage: {}", style, kw, usage);
  }
  if (up[0] == 0.0 && up[1] == 0.0) {    // (the 'down' keyword was not given)
    up[0] = 0.0;
    up[1] = 1.0;
  }
  along[0] = up[1];
  along[1] = -up[0];

  // required input
  if (!every_given)
    error->all(FLERR, "Fix {}: keyword 'every' is required; usage: {}", style, usage);
  if (drive_kind == DRIVE_STEPS) {
    if (every != std::floor(every) || every > 1e15)
      error->all(FLERR,
                 "Fix {}: every = {} must be a whole number of steps (or give 'drive' for "
                 "an interval of drive displacement)",
                 style, every_text);
    nsteps = (bigint) every;
  }
  if (mode != MODE_NONE) {
    if (ntype == 0)
      error->all(FLERR, "Fix {}: keyword 'type' is required; usage: {}", style, usage);
    if (base.kind == Level::NONE)
      error->all(FLERR, "Fix {}: keyword 'base' (the base level) is required; usage: {}", style,
                 usage);
    if (rmin == 0.0 || rmax == 0.0)
      error->all(FLERR, "Fix {}: keywords 'rmin' and 'rmax' are required; usage: {}", style, usage);
    if (rmin > rmax)
      error->all(FLERR, "Fix {}: rmin = {} must not exceed rmax = {}", style, rmin, rmax);
    if (density == 0.0)
      error->all(FLERR, "Fix {}: keyword 'density' is required; usage: {}", style, usage);
    if (seed == 0.0)
      error->all(FLERR, "Fix {}: keyword 'seed' is required; usage: {}", style, usage);
  } else if (erode.kind == Level::NONE)
    error->all(FLERR, "Fix {}: mode none needs 'erode LEVEL' (it only erodes)", style);
  if (foreset >= 0.0 && !window_given)
    error->all(FLERR,
               "Fix {}: foreset needs the window 'x XLO XHI' (the base level falls outside it)",
               style);
  if (erode_igroup < 0) erode_igroup = igroup;
  erode_groupbit = group->bitmask[erode_igroup];
  // constant levels inside the box (variables are checked when they are used)
  if (base.kind == Level::CONSTANT) check_in_box(base.value, "base");
  if (erode.kind == Level::CONSTANT) check_in_box(erode.value, "erode");

  rng = (uint64_t) seed;

  force_reneighbor = 1;
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = 11;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  nevery = 1;
}

/* ---------------------------------------------------------------------- */

int FixSaltdemSediment::setmask()
{
  return PRE_EXCHANGE | END_OF_STEP | POST_FORCE;
}

/* LEVEL is a number (m) or v_NAME */

void FixSaltdemSediment::parse_level(Level &l, const char *text, const char *kw)
{
  if (strncmp(text, "v_", 2) == 0) {
    l.name = text + 2;
    l.kind = Level::EQUAL;    // or ATOM, decided by resolve_level()
    const int ivar = input->variable->find(l.name.c_str());
    if (ivar < 0)
      error->all(FLERR, "Fix {}: {} level variable {} does not exist", style, kw, l.name);
    if (input->variable->atomstyle(ivar))
      l.kind = Level::ATOM;
    else if (!input->variable->equalstyle(ivar))
      error->all(FLERR, "Fix {}: {} level variable {} must be equal-style{}", style, kw, l.name,
                 strcmp(kw, "erode") == 0 ? " or atom-style" : "");
  } else {
    l.kind = Level::CONSTANT;
    l.value = SaltDEM::numeric(FLERR, text, fmt::format("Fix {}: {} level", style, kw), lmp);
  }
}

/* an end of the window 'x': a number (m) or v_NAME, an equal-style variable (a front that moves) */

void FixSaltdemSediment::parse_window_end(Level &l, const char *text)
{
  if (strncmp(text, "v_", 2) == 0) {
    l.name = text + 2;
    l.kind = Level::EQUAL;
    const int ivar = input->variable->find(l.name.c_str());
    if (ivar < 0) error->all(FLERR, "Fix {}: x window variable {} does not exist", style, l.name);
    if (!input->variable->equalstyle(ivar))
      error->all(FLERR,
                 "Fix {}: x window variable {} must be equal-style (one position for the "
                 "whole window end)",
                 style, l.name);
  } else {
    if (!utils::is_double(text))
      error->all(FLERR,
                 "Fix {}: x window end '{}' must be a number (m) or v_NAME (an equal-style "
                 "variable)",
                 style, text);
    l.kind = Level::CONSTANT;
    l.value = SaltDEM::numeric(FLERR, text, fmt::format("Fix {}: x", style), lmp);
  }
}

/* the window at an interval: its variable ends evaluated now */

void FixSaltdemSediment::update_window()
{
  if (!window_given) return;
  for (Level *l : {&wlo, &whi}) {
    if (l->kind != Level::EQUAL) continue;
    const double v = input->variable->compute_equal(l->ivar);
    if (!std::isfinite(v))
      error->all(FLERR, "Fix {} {}: x window variable {} is not finite ({})", style, id, l->name,
                 v);
    (l == &wlo ? xlo : xhi) = v;
  }
  if (xlo >= xhi)
    error->all(FLERR,
               "Fix {} {}: the window x {} {} at step {} ({} to {} m): its low end must be below "
               "its high end",
               style, id, wlo.kind == Level::EQUAL ? "v_" + wlo.name : fmt::format("{}", wlo.value),
               whi.kind == Level::EQUAL ? "v_" + whi.name : fmt::format("{}", whi.value),
               update->ntimestep, xlo, xhi);
}

void FixSaltdemSediment::resolve_level(Level &l, const char *kw)
{
  if (l.kind != Level::EQUAL && l.kind != Level::ATOM) return;
  l.ivar = input->variable->find(l.name.c_str());
  if (l.ivar < 0)
    error->all(FLERR, "Fix {}: {} level variable {} does not exist", style, kw, l.name);
  if (l.kind == Level::EQUAL && !input->variable->equalstyle(l.ivar))
    error->all(FLERR, "Fix {}: {} level variable {} is no longer equal-style", style, kw, l.name);
  if (l.kind == Level::ATOM && !input->variable->atomstyle(l.ivar))
    error->all(FLERR, "Fix {}: {} level variable {} is no longer atom-style", style, kw, l.name);
}

double FixSaltdemSediment::level_value(Level &l, const char *kw)
{
  double v = l.value;
  if (l.kind == Level::EQUAL) {
    v = input->variable->compute_equal(l.ivar);
    check_in_box(v, kw);
  }
  return v;
}

/* a level is a height along 'up' (-gravity) through the origin: it must cut the box */

void FixSaltdemSediment::check_in_box(double level, const char *kw)
{
  double lo = DBL_MAX, hi = -DBL_MAX;
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      const double u = up[0] * (a ? domain->boxhi[0] : domain->boxlo[0]) +
          up[1] * (b ? domain->boxhi[1] : domain->boxlo[1]);
      lo = MIN(lo, u);
      hi = MAX(hi, u);
    }
  if (!std::isfinite(level) || level < lo || level > hi)
    error->all(FLERR, "Fix {}: {} level = {} m is outside the box ({} to {} m{})", style, kw, level,
               lo, hi, (up[0] == 0.0 && up[1] == 1.0) ? " in y" : " along the up direction");
}

/* ---------------------------------------------------------------------- */

bool FixSaltdemSediment::has_cover_law(int itype)
{
  for (PairSaltdem *p : PairSaltdem::saltdem_styles(lmp, "saltdem/cohesive"))
    if (p->allocated && p->setflag[itype][itype]) return true;
  return false;
}

void FixSaltdemSediment::init()
{
  // drive source
  if (drive_kind == DRIVE_VARIABLE) {
    drive_ivar = input->variable->find(drive_name.c_str());
    if (drive_ivar < 0)
      error->all(FLERR, "Fix {}: drive variable {} does not exist", style, drive_name);
    if (!input->variable->equalstyle(drive_ivar))
      error->all(FLERR, "Fix {}: drive variable {} must be equal-style", style, drive_name);
  } else if (drive_kind == DRIVE_FIX) {
    drive_fix = modify->get_fix_by_id(drive_name);
    if (!drive_fix) error->all(FLERR, "Fix {}: drive fix ID {} does not exist", style, drive_name);
    if (drive_index == 0 && !drive_fix->scalar_flag)
      error->all(FLERR, "Fix {}: drive fix {} computes no global scalar", style, drive_name);
    if (drive_index > 0 && (!drive_fix->vector_flag || drive_index > drive_fix->size_vector))
      error->all(FLERR, "Fix {}: drive fix {} has no global vector element {}", style, drive_name,
                 drive_index);
  }
  resolve_level(base, "base");
  resolve_level(erode, "erode");
  for (Level *l : {&wlo, &whi}) {
    if (l->kind != Level::EQUAL) continue;
    l->ivar = input->variable->find(l->name.c_str());
    if (l->ivar < 0)
      error->all(FLERR, "Fix {}: x window variable {} does not exist", style, l->name);
    if (!input->variable->equalstyle(l->ivar))
      error->all(FLERR, "Fix {}: x window variable {} is no longer equal-style", style, l->name);
  }

  if (!epoch_name.empty()) {
    int flag, cols;
    epoch_index = atom->find_custom(epoch_name.c_str(), flag, cols);
    if (epoch_index < 0 || flag != 0 || cols != 0)
      error->all(FLERR,
                 "Fix {}: epoch i_{} is not a per-atom integer vector (define it with fix "
                 "property/atom i_{})",
                 style, epoch_name, epoch_name);
  }

  // the deposition window (along the 'along' axis) and the length the rate is given per
  if (!window_given) {
    xlo = DBL_MAX;
    xhi = -DBL_MAX;
    for (int a = 0; a < 2; a++)
      for (int b = 0; b < 2; b++) {
        const double s = along[0] * (a ? domain->boxhi[0] : domain->boxlo[0]) +
            along[1] * (b ? domain->boxhi[1] : domain->boxlo[1]);
        xlo = MIN(xlo, s);
        xhi = MAX(xhi, s);
      }
  }

  // every discs of the group takes the cover law (new discs join the group)
  const int ntypes = atom->ntypes;
  std::vector<int> law(ntypes + 1, 0);
  for (int t = 1; t <= ntypes; t++) law[t] = has_cover_law(t) ? 1 : 0;
  if (mode != MODE_NONE && !law[ntype])
    error->all(FLERR,
               "Fix {} {}: type {} of the new discs has no cover law: it needs 'pair_coeff "
               "{} {} saltdem/cohesive ...' (pair style saltdem/cohesive or a hybrid with it)",
               style, id, ntype, ntype, ntype);
  int bad = 0, badall;
  for (int i = 0; i < atom->nlocal; i++)
    if ((atom->mask[i] & groupbit) && !law[atom->type[i]]) bad = MAX(bad, atom->type[i]);
  MPI_Allreduce(&bad, &badall, 1, MPI_INT, MPI_MAX, world);
  if (badall)
    error->all(FLERR,
               "Fix {} {}: group {} holds discs of type {}, which has no cover law "
               "(saltdem/cohesive): the fix's group is the cover the new discs join",
               style, id, group->names[igroup], badall);

  // the pair styles size their cutoffs by the largest disc of each type present at the start
  // of a run, and their stable time step by the lightest: the new discs must fit in both
  if (mode != MODE_NONE) {
    double loc[2] = {0.0, -DBL_MAX}, all[2];    // largest radius, -(smallest mass) of ntype
    for (int i = 0; i < atom->nlocal; i++)
      if (atom->type[i] == ntype) {
        loc[0] = MAX(loc[0], atom->radius[i]);
        loc[1] = MAX(loc[1], -atom->rmass[i]);
      }
    MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_MAX, world);
    if (all[0] <= 0.0)
      error->all(FLERR,
                 "Fix {} {}: no discs of type {} at the start of the run: the pair styles "
                 "size their cutoffs and stable time step by the discs present, so the cover "
                 "must exist before discs are deposited on it",
                 style, id, ntype);
    const double margin = 0.5 * neighbor->skin;
    if (rmax > all[0] + margin)
      error->all(FLERR,
                 "Fix {} {}: rmax = {} exceeds the largest disc of type {} ({}) by more "
                 "than half the neighbour skin ({}): the pair cutoffs would miss its contacts",
                 style, id, rmax, ntype, all[0], margin);
    const double mnew = density * MY_PI * rmin * rmin, mold = -all[1];
    if (mnew < 0.95 * mold)
      error->all(FLERR,
                 "Fix {} {}: the lightest new disc (density {} x pi rmin^2 = {} kg/m) is "
                 "below 0.95 of the lightest disc of type {} ({}), which sets the stable time "
                 "step",
                 style, id, density, mnew, ntype, mold);
  }
}

/* ---------------------------------------------------------------------- */

double FixSaltdemSediment::now() const
{
  return update->atime + (update->ntimestep - update->atimestep) * update->dt;
}

double FixSaltdemSediment::drive_value()
{
  if (drive_kind == DRIVE_VARIABLE) return input->variable->compute_equal(drive_ivar);
  if (drive_index == 0) return drive_fix->compute_scalar();
  return drive_fix->compute_vector(drive_index - 1);
}

/* at the end of a step: deposit at the next one?  (Restart files are written after this, and
   setup() decides again from the same state, so a resumed run deposits at the same step.) */

void FixSaltdemSediment::decide()
{
  const bigint n = update->ntimestep;
  int due;
  if (drive_kind == DRIVE_STEPS) {
    due = ((n + 1) % nsteps == 0);
  } else {
    const double d = drive_value();
    if (!std::isfinite(d))
      error->all(FLERR, "Fix {}: drive {} is not finite ({})", style, drive_name, d);
    if (!next_set) {
      next_drive = (std::floor(d / every) + 1.0) * every;
      next_set = 1;
    }
    due = (d >= next_drive);
    drive_at_decision = d;
  }
  pending = due;
  if (due) next_reneighbor = n + 1;
}

void FixSaltdemSediment::setup(int)
{
  if (!t_last_set) {
    t_last = now();
    t_last_set = 1;
  }
  decide();
}

void FixSaltdemSediment::end_of_step()
{
  decide();
}

/* ---------------------------------------------------------------------- */

void FixSaltdemSediment::pre_exchange()
{
  if (!pending || next_reneighbor != update->ntimestep) return;
  pending = 0;

  // variables first, while the atom map and the ghosts are intact
  const double time = now();
  const double level = (mode != MODE_NONE) ? level_value(base, "base") : 0.0;
  if (mode != MODE_NONE) update_window();
  std::vector<double> elev;
  double econst = 0.0;
  if (erode.kind == Level::ATOM) {
    elev.assign(MAX(atom->nlocal, 1), 0.0);
    input->variable->compute_atom(erode.ivar, erode_igroup, elev.data(), 1, 0);
  } else if (erode.kind != Level::NONE)
    econst = level_value(erode, "erode");

  // the same as the start of Comm::exchange(): new discs overwrite the ghosts
  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  epoch++;
  if (drive_kind != DRIVE_STEPS)
    while (next_drive <= drive_at_decision) next_drive += every;

  const double nero0 = nero, aero0 = aero;
  if (erode.kind != Level::NONE) erosion(elev, econst);
  last_n = last_area = 0.0;
  if (mode != MODE_NONE) {
    last_level = level;
    last_xlo = xlo;
    last_xhi = xhi;
    deposition(level, time);
  }

  if (atom->map_style != Atom::MAP_NONE) {
    atom->map_init();
    atom->map_set();
  }

  if (comm->me == 0) {
    std::string where;
    if (mode != MODE_NONE) {
      where = fmt::format(" below base level {:.6g} m", last_level);
      if (wlo.kind == Level::EQUAL || whi.kind == Level::EQUAL)
        where += fmt::format(" in x {:.6g} to {:.6g} m", xlo, xhi);
    }
    if (erode.kind != Level::NONE)
      where +=
          fmt::format(", eroded {} discs ({:.10g} m^2)", (bigint) (nero - nero0), aero - aero0);
    utils::logmesg(lmp, "fix {} {}: epoch {} at step {}: deposited {} discs ({:.10g} m^2){}\n",
                   style, id, epoch, update->ntimestep, (bigint) last_n, last_area, where);
  }
}

/* delete the discs of the erosion group whose centre lies above the erosion level */

void FixSaltdemSediment::erosion(const std::vector<double> &lev, double lconst)
{
  AtomVec *avec = atom->avec;
  double **x = atom->x;
  double *radius = atom->radius;
  int *mask = atom->mask;
  int nlocal = atom->nlocal;
  std::vector<char> gone(nlocal, 0);
  double loc[2] = {0.0, 0.0}, all[2];
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & erode_groupbit)) continue;
    const double level = (erode.kind == Level::ATOM) ? lev[i] : lconst;
    const double u = up[0] * x[i][0] + up[1] * x[i][1];
    if (u > level) {
      gone[i] = 1;
      loc[0] += 1.0;
      loc[1] += MY_PI * radius[i] * radius[i];
    }
  }
  int i = 0;
  while (i < nlocal) {
    if (gone[i]) {
      avec->copy(nlocal - 1, i, 1);
      gone[i] = gone[nlocal - 1];
      nlocal--;
    } else
      i++;
  }
  atom->nlocal = nlocal;
  MPI_Allreduce(loc, all, 2, MPI_DOUBLE, MPI_SUM, world);
  atom->natoms -= (bigint) all[0];
  nero += all[0];
  aero += all[1];
}

/* ---------------------------------------------------------------------- */

uint64_t FixSaltdemSediment::next_random()
{
  uint64_t z = (rng += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double FixSaltdemSediment::uniform()
{
  return (double) (next_random() >> 11) * (1.0 / 9007199254740992.0);    // [0, 1)
}

double FixSaltdemSediment::draw_radius()
{
  const double u = uniform();
  if (dist == DIST_UNIFORM || rmax == rmin) return rmin + u * (rmax - rmin);
  const double e = 1.0 - PAPER_Q;
  const double a = pow(rmin, e), b = pow(rmax, e);
  return MIN(rmax, MAX(rmin, pow(a + u * (b - a), 1.0 / e)));
}

namespace {
struct Disc {
  double X, Y, r, tag;
};
}    // namespace

/* Deposit the discs of one interval.  Coordinates: X along the surface, Y up (against gravity).
   The surface is cut into columns of width w = 2 rbig (rbig: the largest disc, old or new);
   s(c) is the highest disc top in column c.  Every rank takes the discs that a new disc could
   touch: those whose top is within 'depth' of the lowest surface of the columns around them and
   whose bottom is below the base level plus rmax; sorted by atom ID, they are the same list on
   every rank.  A new disc (radius from the generator) goes to the lowest open column: the
   lowest pocket around it where the disc touches two discs, lies between them (stable under
   gravity), has its centre below the base level, lies in the window and the box, and overlaps
   no other disc by more than tol of the smaller radius; a column without such a pocket takes
   only smaller discs until a disc is put near it.  When no column takes the drawn radius, a
   few more radii are drawn; then the interval ends (no room).  A pocket must also lie above the lowest surface of its columns minus
   'depth', so it cannot reach a disc that was not gathered. */

void FixSaltdemSediment::deposition(double level, double time)
{
  double target = 0.0;
  if (mode == MODE_RATE) {
    target = rate * (length_given ? length : xhi - xlo) * (time - t_last) + carry;
    t_last = time;
    carry = 0.0;
    if (target <= 0.0) {
      carry = target;
      return;
    }
  }

  const int nlocal = atom->nlocal;
  double **x = atom->x;
  double *radius = atom->radius;
  tagint *tag = atom->tag;

  double rloc = 0.0, rall;
  tagint tloc = 0, maxtag;
  for (int i = 0; i < nlocal; i++) {
    rloc = MAX(rloc, radius[i]);
    tloc = MAX(tloc, tag[i]);
  }
  MPI_Allreduce(&rloc, &rall, 1, MPI_DOUBLE, MPI_MAX, world);
  MPI_Allreduce(&tloc, &maxtag, 1, MPI_LMP_TAGINT, MPI_MAX, world);
  const double rbig = MAX(rmax, rall);
  const double w = 2.0 * rbig, depth = 4.0 * rbig;
  // the columns span the window, or with a foreset (deposits outside the window) the box
  double glo = xlo, ghi = xhi;
  if (foreset >= 0.0)
    for (int a = 0; a < 2; a++)
      for (int b = 0; b < 2; b++) {
        const double sb = along[0] * (a ? domain->boxhi[0] : domain->boxlo[0]) +
            along[1] * (b ? domain->boxhi[1] : domain->boxlo[1]);
        glo = MIN(glo, sb);
        ghi = MAX(ghi, sb);
      }
  const double X0 = glo - w;
  const double span = std::ceil((ghi - glo) / w) + 2.0;
  if (span > 1.0e7)
    error->all(FLERR,
               "Fix {} {}: the window ({} to {} m) is more than 1e7 columns of {} m: give "
               "a narrower 'x'",
               style, id, glo, ghi, w);
  // the base level at X: flat in the window, falling by 'foreset' per unit length outside it
  auto level_at = [&](double X) {
    return level - foreset * MAX(0.0, MAX(xlo - X, X - xhi));
  };
  const int ncol = (int) span;
  auto column = [&](double X) -> int {
    const double c = std::floor((X - X0) / w);
    return (c < 0.0 || c >= ncol) ? -1 : (int) c;
  };

  // column surfaces
  std::vector<double> sloc(ncol, -DBL_MAX), s(ncol);
  std::vector<double> XX(nlocal), YY(nlocal);
  std::vector<int> cc(nlocal);
  for (int i = 0; i < nlocal; i++) {
    XX[i] = along[0] * x[i][0] + along[1] * x[i][1];
    YY[i] = up[0] * x[i][0] + up[1] * x[i][1];
    cc[i] = column(XX[i]);
    if (cc[i] >= 0) sloc[cc[i]] = MAX(sloc[cc[i]], YY[i] + radius[i]);
  }
  MPI_Allreduce(sloc.data(), s.data(), ncol, MPI_DOUBLE, MPI_MAX, world);
  auto lowest = [&](const std::vector<double> &surf, int c, int k) {    // DBL_MAX: all empty
    double m = DBL_MAX;
    for (int q = MAX(0, c - k); q <= MIN(ncol - 1, c + k); q++)
      if (surf[q] > -DBL_MAX) m = MIN(m, surf[q]);
    return m;
  };
  std::vector<double> gmin(ncol), amin(ncol);
  for (int c = 0; c < ncol; c++) {
    gmin[c] = lowest(s, c, 2);
    amin[c] = lowest(s, c, 1);
  }

  // gather the discs near the surface from every rank
  std::vector<double> mine;
  for (int i = 0; i < nlocal; i++) {
    const int c = cc[i];
    if (c < 0) continue;
    if (YY[i] + radius[i] < gmin[c] - depth) continue;
    if (YY[i] - radius[i] > level + rmax) continue;
    mine.insert(mine.end(), {(double) tag[i], XX[i], YY[i], radius[i]});
  }
  const int nprocs = comm->nprocs;
  int nmine = (int) mine.size();
  std::vector<int> counts(nprocs), displs(nprocs, 0);
  MPI_Allgather(&nmine, 1, MPI_INT, counts.data(), 1, MPI_INT, world);
  bigint total = 0;
  for (int p = 0; p < nprocs; p++) {
    displs[p] = (int) total;
    total += counts[p];
  }
  if (total > MAXSMALLINT)
    error->all(FLERR, "Fix {} {}: too many discs near the surface to gather", style, id);
  std::vector<double> flat(MAX(total, (bigint) 1));
  MPI_Allgatherv(mine.data(), nmine, MPI_DOUBLE, flat.data(), counts.data(), displs.data(),
                 MPI_DOUBLE, world);
  std::vector<Disc> discs((size_t) (total / 4));
  for (size_t k = 0; k < discs.size(); k++)
    discs[k] = {flat[4 * k + 1], flat[4 * k + 2], flat[4 * k + 3], flat[4 * k]};
  std::sort(discs.begin(), discs.end(), [](const Disc &a, const Disc &b) {
    return a.tag < b.tag;
  });
  std::vector<std::vector<int>> cols(ncol);
  for (size_t k = 0; k < discs.size(); k++) cols[column(discs[k].X)].push_back((int) k);

  // place the discs, the same on every rank
  std::vector<double> scur = s;
  // failmin[c]: the smallest radius that found no pocket around column c since a disc was
  // last put near it (only smaller discs are tried there until then)
  std::vector<double> failmin(ncol, DBL_MAX);
  int redraws = 0;
  const double boxlo0 = domain->boxlo[0], boxhi0 = domain->boxhi[0];
  const double boxlo1 = domain->boxlo[1], boxhi1 = domain->boxhi[1];
  size_t first_new = discs.size();
  double area = 0.0;
  double r = 0.0;
  int have_r = 0, roomless = 0;
  std::vector<int> formers;

  while (true) {
    if (mode == MODE_RATE && area >= target) break;
    if ((bigint) (discs.size() - first_new) >= maxper) break;
    if (!have_r) {
      r = draw_radius();
      have_r = 1;
    }
    int c = -1;
    for (int q = 0; q < ncol; q++)
      if (r < failmin[q] && (c < 0 || scur[q] < scur[c])) c = q;
    if (c < 0) {
      // no room for a disc of this radius: a smaller one may still fit (a few more draws)
      int smaller = 0;
      for (int q = 0; q < ncol && !smaller; q++)
        if (failmin[q] > rmin) smaller = 1;
      if (!smaller || ++redraws > MAX_REDRAWS) {
        roomless = 1;
        break;
      }
      have_r = 0;
      continue;
    }

    // pocket formers: discs around column c near its surface
    formers.clear();
    const double mprune = lowest(scur, c, 1);
    if (mprune < DBL_MAX)
      for (int q = MAX(0, c - 1); q <= MIN(ncol - 1, c + 1); q++)
        for (int k : cols[q]) {
          const Disc &d = discs[k];
          if (d.Y + d.r < mprune - depth) continue;
          if (d.Y - d.r > level + r) continue;
          formers.push_back(k);
        }

    double bestX = 0.0, bestY = DBL_MAX;
    int bestc = -1;
    const size_t nf = formers.size();
    for (size_t a = 0; a < nf; a++)
      for (size_t b = a + 1; b < nf; b++) {
        const int i = MIN(formers[a], formers[b]), j = MAX(formers[a], formers[b]);
        const Disc &di = discs[i], &dj = discs[j];
        const double ra = di.r + r, rb = dj.r + r;
        const double dx = dj.X - di.X, dy = dj.Y - di.Y;
        if (dx == 0.0) continue;    // one above the other: no stable pocket
        const double d2 = dx * dx + dy * dy;
        if (d2 >= (ra + rb) * (ra + rb)) continue;
        const double d = sqrt(d2);
        if (d <= fabs(ra - rb)) continue;
        const double l = (ra * ra - rb * rb + d2) / (2.0 * d);
        const double h2 = ra * ra - l * l;
        if (h2 <= 0.0) continue;
        const double h = sqrt(h2);
        // the upper of the two points touching both
        const double sgn = (dx > 0.0) ? 1.0 : -1.0;
        const double PX = di.X + (l * dx - sgn * h * dy) / d;
        const double PY = di.Y + (l * dy + sgn * h * dx) / d;
        if (PY > level) continue;
        if (PY > bestY || (PY == bestY && PX >= bestX)) continue;
        if (PX <= MIN(di.X, dj.X) || PX >= MAX(di.X, dj.X)) continue;    // would roll off
        if (foreset < 0.0) {
          if (PX - r < xlo || PX + r > xhi) continue;
        } else if (PY > level_at(PX))
          continue;
        const double px = along[0] * PX + up[0] * PY, py = along[1] * PX + up[1] * PY;
        if (px - r < boxlo0 || px + r > boxhi0 || py - r < boxlo1 || py + r > boxhi1) continue;
        const int cp = column(PX);
        if (cp < 1 || cp > ncol - 2) continue;
        if (amin[cp] < DBL_MAX && PY - r < amin[cp] - depth) continue;
        bool ok = true;
        for (int q = cp - 1; q <= cp + 1 && ok; q++)
          for (int k : cols[q]) {
            if (k == i || k == j) continue;
            const Disc &dk = discs[k];
            const double lim = r + dk.r;
            const double ey = dk.Y - PY;
            if (fabs(ey) >= lim) continue;
            const double ex = dk.X - PX;
            const double e2 = ex * ex + ey * ey;
            if (e2 >= lim * lim) continue;
            if (lim - sqrt(e2) > tol * MIN(r, dk.r)) {
              ok = false;
              break;
            }
          }
        if (!ok) continue;
        bestX = PX;
        bestY = PY;
        bestc = cp;
      }

    if (bestc < 0) {
      failmin[c] = r;
      continue;
    }
    discs.push_back({bestX, bestY, r, (double) (maxtag + (tagint) (discs.size() - first_new) + 1)});
    cols[bestc].push_back((int) discs.size() - 1);
    scur[bestc] = MAX(scur[bestc], bestY + r);
    // the new disc makes new pockets around it
    for (int q = MAX(0, bestc - 2); q <= MIN(ncol - 1, bestc + 2); q++) failmin[q] = DBL_MAX;
    area += MY_PI * r * r;
    have_r = 0;
    redraws = 0;
  }

  if (mode == MODE_RATE) {
    if (area < target && roomless)
      abyp += target - area;    // no room below the base level
    else
      carry = target - area;    // <= 0, or the maxper rest
  }

  // the discs of this rank's sub-domain (every rank placed the same ones: check their count)
  const bigint nnew = (bigint) (discs.size() - first_new);
  bigint nrange[2] = {nnew, -nnew}, nrange_all[2];
  MPI_Allreduce(nrange, nrange_all, 2, MPI_LMP_BIGINT, MPI_MAX, world);
  if (nrange_all[0] != -nrange_all[1])
    error->all(FLERR, "Fix {} {}: the ranks placed {} to {} discs: their placements differ (a bug)",
               style, id, -nrange_all[1], nrange_all[0]);
  const int newmask = [&] {
    int m = 1 | groupbit;
    for (int g : extra_groups) m |= group->bitmask[g];
    return m;
  }();
  double *sublo = domain->sublo, *subhi = domain->subhi;
  bigint mycount = 0, allcount;
  for (size_t k = first_new; k < discs.size(); k++) {
    const Disc &d = discs[k];
    double coord[3] = {along[0] * d.X + up[0] * d.Y, along[1] * d.X + up[1] * d.Y, 0.0};
    if (coord[0] < sublo[0] || coord[0] >= subhi[0] || coord[1] < sublo[1] ||
        coord[1] >= subhi[1] || coord[2] < sublo[2] || coord[2] >= subhi[2])
      continue;
    atom->avec->create_atom(ntype, coord);
    const int n = atom->nlocal - 1;
    atom->tag[n] = (tagint) d.tag;
    atom->mask[n] = newmask;
    atom->radius[n] = d.r;
    atom->rmass[n] = density * MY_PI * d.r * d.r;
    for (int k2 = 0; k2 < 3; k2++) {
      atom->v[n][k2] = 0.0;
      atom->omega[n][k2] = 0.0;
    }
    for (int q = 0; q < atom->nivector; q++)
      if (atom->ivector[q]) atom->ivector[q][n] = 0;
    for (int q = 0; q < atom->ndvector; q++)
      if (atom->dvector[q]) atom->dvector[q][n] = 0.0;
    for (int q = 0; q < atom->niarray; q++)
      if (atom->iarray[q])
        for (int k2 = 0; k2 < atom->icols[q]; k2++) atom->iarray[q][n][k2] = 0;
    for (int q = 0; q < atom->ndarray; q++)
      if (atom->darray[q])
        for (int k2 = 0; k2 < atom->dcols[q]; k2++) atom->darray[q][n][k2] = 0.0;
    modify->create_attribute(n);
    if (epoch_index >= 0) atom->ivector[epoch_index][n] = epoch_offset + epoch;
    mycount++;
  }
  MPI_Allreduce(&mycount, &allcount, 1, MPI_LMP_BIGINT, MPI_SUM, world);
  if (allcount != nnew)
    error->all(FLERR, "Fix {} {}: {} of {} new discs fell in no sub-domain", style, id,
               nnew - allcount, nnew);
  atom->natoms += nnew;
  if (maxtag + nnew >= MAXTAGINT)
    error->all(FLERR, "Fix {} {}: new atom IDs exceed the largest allowed ID", style, id);

  ndep += (double) nnew;
  adep += area;
  last_n = (double) nnew;
  last_area = area;
  if (nnew > 0 && settle_steps > 0 && settle_gamma > 0.0)
    settles.push_back({maxtag + 1, maxtag + (tagint) nnew, update->ntimestep + settle_steps});
}

/* damped settling of the discs of recent intervals */

void FixSaltdemSediment::post_force(int)
{
  if (settles.empty()) return;
  const bigint n = update->ntimestep;
  settles.erase(std::remove_if(settles.begin(), settles.end(),
                               [n](const Settle &s) {
                                 return s.end < n;
                               }),
                settles.end());
  if (settles.empty()) return;
  double **v = atom->v, **f = atom->f, **omega = atom->omega, **torque = atom->torque;
  double *radius = atom->radius;
  tagint *tag = atom->tag;
  for (int i = 0; i < atom->nlocal; i++)
    for (const auto &s : settles)
      if (tag[i] >= s.lo && tag[i] <= s.hi) {
        for (int k = 0; k < 2; k++) f[i][k] -= settle_gamma * v[i][k];
        torque[i][2] -= settle_gamma * radius[i] * radius[i] * omega[i][2];
        break;
      }
}

/* ---------------------------------------------------------------------- */

double FixSaltdemSediment::compute_vector(int n)
{
  switch (n) {
    case 0:
      return epoch;
    case 1:
      return ndep;
    case 2:
      return adep;
    case 3:
      return nero;
    case 4:
      return aero;
    case 5:
      return abyp;
    case 6:
      return last_level;
    case 7:
      return last_n;
    case 8:
      return last_area;
    case 9:
      return last_xlo;
    default:
      return last_xhi;
  }
}

void FixSaltdemSediment::write_restart(FILE *fp)
{
  std::vector<double> list = {RESTART_TAG,
                              (double) epoch,
                              ndep,
                              nero,
                              adep,
                              aero,
                              abyp,
                              carry,
                              t_last,
                              (double) t_last_set,
                              next_drive,
                              (double) next_set,
                              last_level,
                              last_n,
                              last_area,
                              (double) (rng >> 32),
                              (double) (rng & 0xffffffffULL),
                              (double) settles.size()};
  for (const auto &s : settles)
    list.insert(list.end(), {(double) s.lo, (double) s.hi, (double) s.end});
  list.insert(list.end(), {last_xlo, last_xhi});
  if (comm->me == 0) {
    int size = (int) (list.size() * sizeof(double));
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list.data(), sizeof(double), list.size(), fp);
  }
}

void FixSaltdemSediment::restart(char *buf)
{
  auto list = (double *) buf;
  if (list[0] != RESTART_TAG && list[0] != RESTART_TAG_V1)
    error->all(FLERR, "Fix {} {}: the restart file's state is not one of this fix", style, id);
  int k = 1;
  epoch = (int) list[k++];
  ndep = list[k++];
  nero = list[k++];
  adep = list[k++];
  aero = list[k++];
  abyp = list[k++];
  carry = list[k++];
  t_last = list[k++];
  t_last_set = (int) list[k++];
  next_drive = list[k++];
  next_set = (int) list[k++];
  last_level = list[k++];
  last_n = list[k++];
  last_area = list[k++];
  const auto hi = (uint64_t) list[k++], lo = (uint64_t) list[k++];
  rng = (hi << 32) | lo;
  const int ns = (int) list[k++];
  settles.clear();
  for (int q = 0; q < ns; q++, k += 3)
    settles.push_back({(tagint) list[k], (tagint) list[k + 1], (bigint) list[k + 2]});
  if (list[0] == RESTART_TAG) {
    last_xlo = list[k++];
    last_xhi = list[k++];
  }
}
