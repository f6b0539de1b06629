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

   fix saltdem/sediment: syn-tectonic sedimentation and erosion.  Every N steps, or every given
   amount of drive displacement, new cover discs are deposited into the accommodation space
   below a base level: to the base level (fill) or at a rate of disc area per unit length and
   time (rate).  Their radii follow the scene's radius law; each is put, at rest, into the
   lowest pocket of the surface where it touches two discs and overlaps no other by more than
   a tolerance, so it settles without a fall.  All ranks place the same discs.  Each new disc
   gets the interval's number (its epoch) in a per-atom integer, for growth strata.
   Optionally the discs of a group above an erosion level are deleted.  The generator, the
   epoch and the counters go to restart files.  This file keeps the intervals, the counters
   and the restart state; the jobs are in saltdem_sediment_levels (where),
   saltdem_sediment_deposit with saltdem_sediment_pockets and saltdem_sediment_random (the new
   discs), saltdem_sediment_erosion and saltdem_sediment_settle.
------------------------------------------------------------------------- */

#include "fix_saltdem_sediment.h"

#include "pair_saltdem.h"
#include "saltdem_check.h"
#include "saltdem_sediment_deposit.h"
#include "saltdem_sediment_erosion.h"
#include "saltdem_sediment_levels.h"
#include "saltdem_sediment_settle.h"

#include "arg_info.h"
#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "group.h"
#include "input.h"
#include "modify.h"
#include "update.h"
#include "variable.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <map>

using namespace LAMMPS_NS;
using namespace FixConst;
using Level = SaltdemSedimentLevels::Level;

// a restart record starts with this number (and its layout version)
static constexpr double RESTART_TAG = 18003.0;
static constexpr double RESTART_TAG_V1 = 18002.0;    // before the window (no last_xlo, last_xhi)

/* ---------------------------------------------------------------------- */

FixSaltdemSediment::FixSaltdemSediment(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), mode(MODE_NONE), rate(0.0), length(0.0), length_given(0),
    drive_kind(DRIVE_STEPS), every(0.0), nsteps(0), drive_index(0), drive_ivar(-1),
    drive_fix(nullptr), erode_igroup(-1), erode_groupbit(0), levels(nullptr), deposit(nullptr),
    settle(nullptr), epoch(0), ndep(0.0), nero(0.0), adep(0.0), aero(0.0), abyp(0.0), carry(0.0),
    t_last(0.0), t_last_set(0), next_drive(0.0), next_set(0), last_level(0.0), last_n(0.0),
    last_area(0.0), last_xlo(0.0), last_xhi(0.0), pending(0), drive_at_decision(0.0)
{
  usage = fmt::format("fix ID group {} fill|rate R|none type T base LEVEL every N [drive SOURCE] "
                      "rmin R1 rmax R2 density RHO seed S [dist uniform|paper] [overlap TOL] "
                      "[epoch i_NAME] [offset K] [erode LEVEL] [erode_group G] [group G] "
                      "[x XLO XHI] [foreset S] [length L] [down DX DY] [settle N GAMMA] "
                      "[maxper N]",
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
  levels = new SaltdemSedimentLevels(lmp, this);
  deposit = new SaltdemSedimentDeposit(lmp, this);
  settle = new SaltdemSedimentSettle(lmp);
  SaltdemSedimentLevels &lev = *levels;
  SaltdemSedimentDeposit &dep = *deposit;

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
  std::string every_text;
  auto num = [&](const char *kw, const char *val) {
    return SaltDEM::numeric(FLERR, val, fmt::format("Fix {}: {}", style, kw), lmp);
  };
  auto positive = [&](const char *kw, const char *val) {
    const double v = num(kw, val);
    if (v <= 0.0) error->all(FLERR, "Fix {}: {} = {} must be > 0", style, kw, v);
    return v;
  };
  auto find_group = [&](const char *kw, const char *name) {
    const int g = group->find(name);
    if (g < 0) error->all(FLERR, "Fix {}: {} group '{}' does not exist", style, kw, name);
    return g;
  };

  // keyword: the number of its values and what it does with them
  std::map<std::string, std::pair<int, std::function<void(char **)>>> keywords;
  auto keyword = [&](const char *name, int nvalues, std::function<void(char **)> set) {
    keywords[name] = {nvalues, set};
  };
  keyword("type", 1, [&](char **v) {
    dep.ntype = utils::inumeric(FLERR, v[0], false, lmp);
    if (dep.ntype < 1 || dep.ntype > atom->ntypes)
      error->all(FLERR, "Fix {}: type {} is not an atom type (1 to {})", style, dep.ntype,
                 atom->ntypes);
  });
  keyword("base", 1, [&](char **v) {
    lev.parse(lev.base, v[0], "base");
    if (lev.base.kind == Level::ATOM)
      error->all(FLERR, "Fix {}: base level v_{} must be a constant or an equal-style variable",
                 style, lev.base.name);
  });
  keyword("every", 1, [&](char **v) {
    every_text = v[0];
    every = num("every", v[0]);
    if (every <= 0.0)
      error->all(FLERR,
                 "Fix {}: every = {} must be > 0 (steps, or drive displacement with 'drive')",
                 style, every);
  });
  keyword("drive", 1, [&](char **v) {
    ArgInfo argi(v[0], ArgInfo::VARIABLE | ArgInfo::FIX);
    if (argi.get_type() == ArgInfo::VARIABLE && argi.get_dim() == 0) {
      drive_kind = DRIVE_VARIABLE;
    } else if (argi.get_type() == ArgInfo::FIX && argi.get_dim() <= 1) {
      drive_kind = DRIVE_FIX;
      drive_index = argi.get_index1();
    } else
      error->all(FLERR,
                 "Fix {}: drive '{}' must be v_NAME (an equal-style variable), f_ID or "
                 "f_ID[N] (a fix's global scalar or vector element)",
                 style, v[0]);
    drive_name = argi.get_name();
  });
  keyword("rmin", 1, [&](char **v) {
    dep.rmin = positive("rmin", v[0]);
  });
  keyword("rmax", 1, [&](char **v) {
    dep.rmax = positive("rmax", v[0]);
  });
  keyword("dist", 1, [&](char **v) {
    if (strcmp(v[0], "uniform") != 0 && strcmp(v[0], "paper") != 0)
      error->all(FLERR, "Fix {}: dist '{}' must be uniform or paper", style, v[0]);
    dep.paper = strcmp(v[0], "paper") == 0;
  });
  keyword("density", 1, [&](char **v) {
    dep.density = positive("density", v[0]);
  });
  keyword("seed", 1, [&](char **v) {
    seed = utils::numeric(FLERR, v[0], false, lmp);
    if (seed <= 0.0 || seed != std::floor(seed) || seed > 9.0e15)
      error->all(FLERR, "Fix {}: seed = {} must be a positive integer", style, v[0]);
  });
  keyword("overlap", 1, [&](char **v) {
    dep.tol = num("overlap", v[0]);
    if (dep.tol < 0.0 || dep.tol >= 1.0)
      error->all(FLERR, "Fix {}: overlap = {} must be in [0, 1) (a fraction of the smaller radius)",
                 style, dep.tol);
  });
  keyword("epoch", 1, [&](char **v) {
    if (strncmp(v[0], "i_", 2) != 0 || strlen(v[0]) < 3)
      error->all(FLERR,
                 "Fix {}: epoch '{}' must name a per-atom integer, i_NAME (fix property/atom)",
                 style, v[0]);
    epoch_name = v[0] + 2;
  });
  keyword("offset", 1, [&](char **v) {
    dep.epoch_offset = utils::inumeric(FLERR, v[0], false, lmp);
    if (dep.epoch_offset < 0 || dep.epoch_offset > 1000000000)
      error->all(FLERR, "Fix {}: offset = {} must be in [0, 1e9]", style, dep.epoch_offset);
  });
  keyword("erode", 1, [&](char **v) {
    if (strcmp(v[0], "none") == 0)
      lev.erode = Level();
    else
      lev.parse(lev.erode, v[0], "erode");
  });
  keyword("erode_group", 1, [&](char **v) {
    erode_igroup = find_group("erode_group", v[0]);
  });
  keyword("group", 1, [&](char **v) {
    dep.groups.push_back(find_group("group", v[0]));
  });
  keyword("x", 2, [&](char **v) {
    lev.parse_window(v[0], v[1]);
  });
  keyword("foreset", 1, [&](char **v) {
    lev.foreset = num("foreset", v[0]);
    if (lev.foreset < 0.0)
      error->all(FLERR,
                 "Fix {}: foreset = {} must be >= 0 (the fall of the base level per unit length "
                 "outside the window, the tangent of the foreset dip)",
                 style, lev.foreset);
  });
  keyword("length", 1, [&](char **v) {
    length = positive("length", v[0]);
    length_given = 1;
  });
  keyword("down", 2, [&](char **v) {
    lev.set_down(num("down", v[0]), num("down", v[1]));
  });
  keyword("settle", 2, [&](char **v) {
    settle->steps = utils::inumeric(FLERR, v[0], false, lmp);
    settle->gamma = num("settle", v[1]);
    if (settle->steps < 0 || settle->gamma < 0.0)
      error->all(FLERR, "Fix {}: settle {} {}: steps and drag must be >= 0", style, settle->steps,
                 settle->gamma);
  });
  keyword("maxper", 1, [&](char **v) {
    dep.maxper = utils::bnumeric(FLERR, v[0], false, lmp);
    if (dep.maxper < 1) error->all(FLERR, "Fix {}: maxper = {} must be >= 1", style, dep.maxper);
  });
  while (iarg < narg) {
    const auto kw = keywords.find(arg[iarg]);
    if (kw == keywords.end())
      error->all(FLERR, "Fix {}: unknown keyword '{}'; usage: {}", style, arg[iarg], usage);
    const int nvalues = kw->second.first;
    if (iarg + nvalues >= narg)
      utils::missing_cmd_args(FLERR, fmt::format("fix {} {}", style, arg[iarg]), error);
    kw->second.second(&arg[iarg + 1]);
    iarg += 1 + nvalues;
  }

  // required input
  if (every_text.empty())
    error->all(FLERR, "Fix {}: keyword 'every' is required; usage: {}", style, usage);
  if (drive_kind == DRIVE_STEPS) {
    if (every != std::floor(every) || every > 1e15)
      error->all(FLERR,
                 "Fix {}: every = {} must be a whole number of steps (or give 'drive' for an "
                 "interval of drive displacement)",
                 style, every_text);
    nsteps = (bigint) every;
  }
  if (mode != MODE_NONE) {
    if (dep.ntype == 0)
      error->all(FLERR, "Fix {}: keyword 'type' is required; usage: {}", style, usage);
    if (lev.base.kind == Level::NONE)
      error->all(FLERR, "Fix {}: keyword 'base' (the base level) is required; usage: {}", style,
                 usage);
    if (dep.rmin == 0.0 || dep.rmax == 0.0)
      error->all(FLERR, "Fix {}: keywords 'rmin' and 'rmax' are required; usage: {}", style, usage);
    if (dep.rmin > dep.rmax)
      error->all(FLERR, "Fix {}: rmin = {} must not exceed rmax = {}", style, dep.rmin, dep.rmax);
    if (dep.density == 0.0)
      error->all(FLERR, "Fix {}: keyword 'density' is required; usage: {}", style, usage);
    if (seed == 0.0)
      error->all(FLERR, "Fix {}: keyword 'seed' is required; usage: {}", style, usage);
  } else if (lev.erode.kind == Level::NONE)
    error->all(FLERR, "Fix {}: mode none needs 'erode LEVEL' (it only erodes)", style);
  if (lev.foreset >= 0.0 && !lev.window_given)
    error->all(FLERR,
               "Fix {}: foreset needs the window 'x XLO XHI' (the base level falls outside it)",
               style);
  if (erode_igroup < 0) erode_igroup = igroup;
  erode_groupbit = group->bitmask[erode_igroup];
  // constant levels inside the box (variables are checked when they are used)
  if (lev.base.kind == Level::CONSTANT) lev.check_in_box(lev.base.value, "base");
  if (lev.erode.kind == Level::CONSTANT) lev.check_in_box(lev.erode.value, "erode");

  dep.rng.state = (uint64_t) seed;

  force_reneighbor = 1;
  next_reneighbor = -1;
  vector_flag = 1;
  size_vector = 11;
  global_freq = 1;
  extvector = 0;
  restart_global = 1;
  nevery = 1;
}

FixSaltdemSediment::~FixSaltdemSediment()
{
  delete levels;
  delete deposit;
  delete settle;
}

/* ---------------------------------------------------------------------- */

int FixSaltdemSediment::setmask()
{
  return PRE_EXCHANGE | END_OF_STEP | POST_FORCE;
}

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
  levels->init();

  if (!epoch_name.empty()) {
    int flag, cols;
    deposit->epoch_index = atom->find_custom(epoch_name.c_str(), flag, cols);
    if (deposit->epoch_index < 0 || flag != 0 || cols != 0)
      error->all(FLERR,
                 "Fix {}: epoch i_{} is not a per-atom integer vector (define it with fix "
                 "property/atom i_{})",
                 style, epoch_name, epoch_name);
  }

  // every disc of the group takes the cover law (new discs join the group)
  const int ntypes = atom->ntypes, ntype = deposit->ntype;
  std::vector<int> law(ntypes + 1, 0);
  for (int t = 1; t <= ntypes; t++) law[t] = has_cover_law(t) ? 1 : 0;
  if (mode != MODE_NONE && !law[ntype])
    error->all(FLERR,
               "Fix {} {}: type {} of the new discs has no cover law: it needs 'pair_coeff {} {} "
               "saltdem/cohesive ...' (pair style saltdem/cohesive or a hybrid with it)",
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

  if (mode != MODE_NONE) deposit->check_fit();
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
  Level &erode = levels->erode;

  // variables first, while the atom map and the ghosts are intact
  const double time = now();
  const double level = (mode != MODE_NONE) ? levels->value(levels->base, "base") : 0.0;
  if (mode != MODE_NONE) levels->update_window();
  std::vector<double> elev;
  double econst = 0.0;
  if (erode.kind == Level::ATOM) {
    elev.assign(MAX(atom->nlocal, 1), 0.0);
    input->variable->compute_atom(erode.ivar, erode_igroup, elev.data(), 1, 0);
  } else if (erode.kind != Level::NONE)
    econst = levels->value(erode, "erode");

  // the same as the start of Comm::exchange(): new discs overwrite the ghosts
  if (atom->map_style != Atom::MAP_NONE) atom->map_clear();
  atom->nghost = 0;
  atom->avec->clear_bonus();

  epoch++;
  if (drive_kind != DRIVE_STEPS)
    while (next_drive <= drive_at_decision) next_drive += every;

  const double nero0 = nero, aero0 = aero;
  if (erode.kind != Level::NONE) {
    double n, area;
    SaltDEM::sediment_erode(lmp, erode_groupbit, levels->up,
                            erode.kind == Level::ATOM ? elev.data() : nullptr, econst, n, area);
    nero += n;
    aero += area;
  }
  last_n = last_area = 0.0;
  if (mode != MODE_NONE) {
    last_level = level;
    last_xlo = levels->xlo;
    last_xhi = levels->xhi;
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
      if (levels->wlo.kind == Level::EQUAL || levels->whi.kind == Level::EQUAL)
        where += fmt::format(" in x {:.6g} to {:.6g} m", levels->xlo, levels->xhi);
    }
    if (erode.kind != Level::NONE)
      where +=
          fmt::format(", eroded {} discs ({:.10g} m^2)", (bigint) (nero - nero0), aero - aero0);
    utils::logmesg(lmp, "fix {} {}: epoch {} at step {}: deposited {} discs ({:.10g} m^2){}\n",
                   style, id, epoch, update->ntimestep, (bigint) last_n, last_area, where);
  }
}

/* the discs of one interval: the area a rate asks for, its shortfall carried to the next
   interval or, without room below the base level, bypassed */

void FixSaltdemSediment::deposition(double level, double time)
{
  double target = 0.0;
  if (mode == MODE_RATE) {
    target = rate * (length_given ? length : levels->xhi - levels->xlo) * (time - t_last) + carry;
    t_last = time;
    carry = 0.0;
    if (target <= 0.0) {
      carry = target;
      return;
    }
  }
  const bigint nnew = deposit->deposit(*levels, level, mode == MODE_RATE, target, epoch);
  const double area = deposit->area;
  if (mode == MODE_RATE) {
    if (area < target && deposit->roomless)
      abyp += target - area;    // no room below the base level
    else
      carry = target - area;    // <= 0, or the maxper rest
  }
  ndep += (double) nnew;
  adep += area;
  last_n = (double) nnew;
  last_area = area;
  settle->add(deposit->maxtag + 1, deposit->maxtag + (tagint) nnew);
}

/* damped settling of the discs of recent intervals */

void FixSaltdemSediment::post_force(int)
{
  settle->apply();
}

/* ---------------------------------------------------------------------- */

double FixSaltdemSediment::compute_vector(int n)
{
  const double v[] = {(double) epoch, ndep,   adep,      nero,     aero,    abyp,
                      last_level,     last_n, last_area, last_xlo, last_xhi};
  return v[(n >= 0 && n < 10) ? n : 10];
}

void FixSaltdemSediment::write_restart(FILE *fp)
{
  const uint64_t rng = deposit->rng.state;
  // the layout: the tag, the counters and times, the generator, the settling discs, the window
  std::vector<double> list = {RESTART_TAG, (double) epoch, ndep, nero, adep, aero, abyp, carry};
  list.insert(list.end(), {t_last, (double) t_last_set, next_drive, (double) next_set});
  list.insert(list.end(), {last_level, last_n, last_area});
  list.insert(list.end(), {(double) (rng >> 32), (double) (rng & 0xffffffffULL)});
  settle->pack(list);
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
  deposit->rng.state = (hi << 32) | lo;
  k += settle->unpack(list + k);
  if (list[0] == RESTART_TAG) {
    last_xlo = list[k++];
    last_xhi = list[k++];
  }
}
