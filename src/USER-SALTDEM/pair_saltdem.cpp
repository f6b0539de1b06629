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
------------------------------------------------------------------------- */

#include "pair_saltdem.h"

#include "fix_saltdem_rebuild.h"
#include "saltdem_check.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_neigh_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neighbor.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

/* ---------------------------------------------------------------------- */

PairSaltdem::PairSaltdem(LAMMPS *lmp, const char *style_name, const char *history_id) :
    Pair(lmp), name(style_name), hist_id(history_id), fix_history(nullptr), fix_rebuild(nullptr),
    transfer_factor(nullptr), onerad(nullptr), maxrad(nullptr), extra(nullptr), reach_abs(nullptr),
    dtfactor(DTFACTOR_DEFAULT), layout_read(0), recheck(false)
{
  single_enable = 0;
  no_virial_fdotr_compute = 1;
  centroidstressflag = CENTROID_NOTAVAIL;
  finitecutflag = 1;
  history = (history_id != nullptr) ? 1 : 0;
  size_history = 0;

  // a placeholder keeps the history fix at this position in the fix list
  if (history) modify->add_fix(fmt::format("{}_DUMMY{} all DUMMY", hist_id, instance_me));
}

PairSaltdem::~PairSaltdem()
{
  if (copymode) return;
  // by ID: the fix may be gone already (unfix, or a plugin unloaded before this pair style)
  if (modify->get_fix_by_id(rebuild_id())) modify->delete_fix(rebuild_id());
  if (history) {
    if (fix_history)
      modify->delete_fix(std::string(fix_history->id));
    else
      modify->delete_fix(fmt::format("{}_DUMMY{}", hist_id, instance_me));
  }
  delete[] transfer_factor;
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
    memory->destroy(extra);
    memory->destroy(reach_abs);
    delete[] onerad;
    delete[] maxrad;
  }
}

/* ---------------------------------------------------------------------- */

void PairSaltdem::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  memory->create(extra, n + 1, n + 1, "pair:extra");
  memory->create(reach_abs, n + 1, n + 1, "pair:reach_abs");
  onerad = new double[n + 1];
  maxrad = new double[n + 1];
  allocate_params(n);
}

/* check the argument count of pair_coeff and parse its I,J type ranges,
   allocating on first use */

void PairSaltdem::check_types(int narg, char **arg, int nmin, const char *usage, int &ilo, int &ihi,
                              int &jlo, int &jhi)
{
  if (narg < nmin)
    error->all(FLERR, "Pair style {}: pair_coeff needs {} or more arguments, got {}: {}", name,
               nmin, narg, usage);
  if (!allocated) allocate();
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
}

void PairSaltdem::no_coeffs_set()
{
  error->all(FLERR, "Incorrect args for pair coefficients" + utils::errorurl(21));
}

/* ---------------------------------------------------------------------- */

void PairSaltdem::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag)
    error->all(FLERR,
               "Pair style {} requires per-atom radius, rmass and omega: use 'atom_style sphere'",
               name);
  if (comm->ghost_velocity == 0)
    error->all(FLERR,
               "Pair style {} needs the velocities of ghost atoms: add 'comm_modify vel yes'",
               name);

  // history needs the size list (it flags touching pairs); a law without
  // history uses the plain list, whose cutoff (init_one) may reach far
  if (history)
    neighbor->add_request(this, NeighConst::REQ_SIZE | NeighConst::REQ_HISTORY);
  else
    neighbor->add_request(this);

  // no suffix: NEIGH_HISTORY/omp of LAMMPS 4Feb2025 drops the history of
  // ghost partners and the non-default transfer signs
  // restart files find the history by fix ID: under pair hybrid the ID counts the sub-styles
  // of this name, not the pair instances (also after 'pair_style hybrid' is given again, which
  // makes new sub-styles); it holds the number of values, so that a restart with another
  // number (rolling switched) drops the history instead of misreading it
  if (history && !fix_history) {
    std::string fid = fmt::format("{}{}", hist_id, instance_me);
    if (force->pair != this) {
      const auto subs = saltdem_styles(lmp, name);
      const auto at = std::find(subs.begin(), subs.end(), this);
      if (at != subs.end()) fid = fmt::format("{}_SUB{}", hist_id, 1 + (at - subs.begin()));
    }
    fid += fmt::format("_N{}", size_history);
    auto cmd = fmt::format("{} all NEIGH_HISTORY {}", fid, size_history);
    fix_history = dynamic_cast<FixNeighHistory *>(
        modify->replace_fix(fmt::format("{}_DUMMY{}", hist_id, instance_me), cmd, 0));
    fix_history->pair = this;
  }

  fix_rebuild = dynamic_cast<FixSaltdemRebuild *>(modify->get_fix_by_id(rebuild_id()));
  if (fix_rebuild) fix_rebuild->range = 0.0;    // init_one() sets it again

  // largest radius per type sets the ghost cutoff
  const int n = atom->ntypes;
  for (int i = 1; i <= n; i++) onerad[i] = 0.0;
  for (int i = 0; i < atom->nlocal; i++)
    onerad[atom->type[i]] = MAX(onerad[atom->type[i]], atom->radius[i]);
  MPI_Allreduce(&onerad[1], &maxrad[1], n, MPI_DOUBLE, MPI_MAX, world);
}

/* the time step check of a run or minimization, after init_one() has derived every type
   pair's coefficients (Force::setup(), or PairHybrid::setup() for each sub-style): the time
   step must be stable for the laws of every SaltDEM style and the lightest particles; the
   stability margin of this style belongs in every run's log */

void PairSaltdem::setup()
{
  const auto limits = check_timestep("");
  for (const auto &l : limits)
    if (l.pair == this && !l.why.empty() && comm->me == 0)
      utils::logmesg(lmp,
                     "Pair style {}: timestep {:.6g} = {:.3g} of the stable limit {:.6g} ({})\n",
                     name, update->dt, update->dt / l.dt, l.dt, l.why);
}

/* I,J is this style's: given to it by pair_coeff, or (not given to any style) mixed from its
   own I,I and J,J, as Pair::init() and PairHybrid::init_one() mix */

bool PairSaltdem::owns(int i, int j) const
{
  if (setflag[i][j]) return true;
  if (!setflag[i][i] || !setflag[j][j]) return false;
  const Pair *top = force->pair;
  return top == this || !top || !top->setflag || !top->setflag[i][j];
}

void PairSaltdem::init_coeff(int i, int j)
{
  if (setflag[i][j] == 0) mix(i, j);    // Pair::init() has checked that I,I and J,J are set
  derive(i, j);
  memcpy(pair_params(j, i), pair_params(i, j), params_size());
}

void PairSaltdem::init_coeffs()
{
  if (!allocated) return;
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (owns(i, j)) init_coeff(i, j);
}

double PairSaltdem::stable_limit(std::string &why, bool cached)
{
  why.clear();
  if (!allocated) return 0.0;    // no coefficients yet
  const int n = atom->ntypes;
  if (!cached || (int) mmin_cache.size() != n + 1 || (int) mv_cache.size() != n + 1) {
    mmin_cache.assign(n + 1, -1.0);
    mv_cache.assign(n + 1, DBL_MAX);
    min_inertial_mass(mmin_cache.data(), mv_cache.data());
  }
  const double *mmin = mmin_cache.data(), *mv = mv_cache.data();
  double best = 0.0;
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) {
      if (!owns(i, j)) continue;                                 // another sub-style's pair
      if (mmin[i] < 0.0 || mmin[j] < 0.0) continue;              // a type without atoms
      if (mmin[i] == DBL_MAX && mmin[j] == DBL_MAX) continue;    // walls only
      pair_limit(i, j, MIN(mmin[i], mmin[j]), MIN(mv[i], mv[j]),
                 mmin[i] == DBL_MAX || mmin[j] == DBL_MAX, best, why);
    }
  return why.empty() ? 0.0 : best;
}

/* pair_match() returns the n-th matching sub-style of a hybrid, the only one again past the
   last (or nullptr past the last of several), and a matching pair style for every n */

std::vector<PairSaltdem *> PairSaltdem::saltdem_styles(LAMMPS *lmp, const std::string &style)
{
  std::vector<PairSaltdem *> styles;
  for (int n = 1;; n++) {
    auto pair = dynamic_cast<PairSaltdem *>(lmp->force->pair_match(style, 0, n));
    if (!pair || (!styles.empty() && pair == styles.back())) break;
    styles.push_back(pair);
  }
  return styles;
}

PairSaltdem::Limit PairSaltdem::smallest_limit(LAMMPS *lmp, const std::string &who,
                                               std::vector<Limit> *each, bool cached)
{
  Limit best{nullptr, 0.0, ""};
  for (auto pair : saltdem_styles(lmp)) {
    // (before the run's init_style: saltdem/timestep)
    if (!lmp->atom->radius_flag || !lmp->atom->rmass_flag)
      lmp->error->all(FLERR,
                      "{}Pair style {} requires per-atom radius and mass: use 'atom_style "
                      "sphere'",
                      who, pair->name);
    Limit l{pair, 0.0, ""};
    l.dt = pair->stable_limit(l.why, cached);
    if (!l.why.empty() && !(l.dt > 0.0 && std::isfinite(l.dt)))
      lmp->error->all(FLERR,
                      "{}Pair style {}: the stable time step limit is {} (not a finite positive "
                      "number), set by {}: a coefficient, inertia factor or disc mass of that "
                      "size is out of range; change the parameter named (or the masses, 'set ... "
                      "density/disc')",
                      who, pair->name, l.dt, l.why);
    if (!l.why.empty() && (!best.pair || l.dt < best.dt)) best = l;
    if (each) each->push_back(l);
  }
  return best;
}

std::vector<PairSaltdem::Limit> PairSaltdem::check_timestep(const std::string &when)
{
  std::vector<Limit> all;
  const Limit best = smallest_limit(
      lmp, when.empty() ? "" : "After a change during the run: ", &all, !when.empty());
  for (auto &l : all) l.pair->limits_checked();
  if (best.pair && update->dt > best.dt) {
    // under pair hybrid: the limit of each SaltDEM sub-style, so that the dt asked for is the
    // one every sub-style accepts
    std::string others;
    if (all.size() > 1) {
      others = " (the limits of the SaltDEM sub-styles:";
      for (const auto &l : all)
        others += l.why.empty() ? fmt::format(" {} none;", l.pair->name)
                                : fmt::format(" {} {:.6g} s;", l.pair->name, l.dt);
      others.back() = ')';
    }
    error->all(FLERR,
               "Pair style {}: {}timestep {:.6g} exceeds the stable limit {:.6g} set by {}{}. "
               "Use 'timestep {:.3g}' or smaller, or change the parameter named",
               best.pair->name, when, update->dt, best.dt, best.why, others, 0.99 * best.dt);
  }
  return all;
}

/* a coefficient changed during the run (recheck set by init_one through reinit()): the same
   check, on the masses of the check at the start of the run (no communication) */

void PairSaltdem::recheck_timestep()
{
  if (!recheck) return;
  recheck = false;
  check_timestep(fmt::format("at step {}, after {} changed during the run, the ", update->ntimestep,
                             recheck_what));
}

/* smallest mass per type that the integrator sees: rmass times the inertia
   factor of a SaltDEM integrator (fix saltdem/nve); atoms that no fix
   integrates, or whose motion is prescribed (fix move, or a fix that
   answers extract("prescribed")), are walls of unbounded mass */

double PairSaltdem::fix_inertia_scale(Fix *ifix)
{
  int dim;
  if (strcmp(ifix->style, "move") == 0 || ifix->extract("prescribed", dim)) return -1.0;
  auto s = (double *) ifix->extract("inertia", dim);
  return s ? *s : 1.0;
}

PairSaltdem::Integrators PairSaltdem::find_integrators()
{
  Integrators integrators;
  for (auto &ifix : modify->get_fix_list())
    if (ifix->time_integrate) integrators.emplace_back(ifix->groupbit, fix_inertia_scale(ifix));
  return integrators;
}

double PairSaltdem::inertia_scale(int mask, const Integrators &integrators)
{
  double scale = -1.0;    // no integrator: a wall
  for (const auto &it : integrators) {
    if (!(mask & it.first)) continue;
    scale = it.second;
    if (scale < 0.0) return -1.0;
  }
  return scale;
}

void PairSaltdem::min_inertial_mass(double *mmin, double *mvmin)
{
  const int n = atom->ntypes;
  const bool disc = (domain->dimension == 2);
  std::vector<double> local(2 * (n + 1), DBL_MAX), both(2 * (n + 1));
  std::vector<bigint> count(n + 1, 0), all(n + 1);
  const Integrators integrators = find_integrators();
  for (int i = 0; i < atom->nlocal; i++) {
    const double scale = inertia_scale(atom->mask[i], integrators);
    const int t = atom->type[i];
    const double r = atom->radius[i];
    const double vol = disc ? M_PI * r * r : 4.0 * M_PI / 3.0 * r * r * r;
    count[t]++;
    if (scale > 0.0) local[t] = MIN(local[t], scale * atom->rmass[i]);
    if (scale > 0.0 && vol > 0.0)
      local[n + 1 + t] = MIN(local[n + 1 + t], scale * atom->rmass[i] / vol);
  }
  MPI_Allreduce(local.data(), both.data(), 2 * (n + 1), MPI_DOUBLE, MPI_MIN, world);
  for (int t = 1; t <= n; t++) {
    mmin[t] = both[t];
    mvmin[t] = both[n + 1 + t];
  }
  MPI_Allreduce(&count[1], &all[1], n, MPI_LMP_BIGINT, MPI_SUM, world);
  for (int t = 1; t <= n; t++)
    if (all[t] == 0) mmin[t] = -1.0;    // no atoms of this type: no limit from it
}

/* ---------------------------------------------------------------------- */

double PairSaltdem::init_one(int i, int j)
{
  init_coeff(i, j);
  extra[i][j] = extra[j][i] = range(i, j);
  reach_abs[i][j] = reach_abs[j][i] = range_abs(i, j);

  // in the size list a pair is listed when r < ri + rj + skin: the range
  // beyond contact must fit inside the skin, and the list is rebuilt early
  // enough to hold every pair that can close to within the range
  if (history && extra[i][j] > 0.0) {
    if (!fix_rebuild)
      fix_rebuild = dynamic_cast<FixSaltdemRebuild *>(
          modify->add_fix(fmt::format("{} all SALTDEM_REBUILD", rebuild_id())));
    fix_rebuild->range = MAX(fix_rebuild->range, extra[i][j]);
  }
  if (history && extra[i][j] >= neighbor->skin)
    error->all(FLERR,
               "Pair style {}: interaction range {:.6g} beyond contact for types {} {} is not "
               "smaller than the neighbor skin {:.6g}; use e.g. 'neighbor {:.3g} bin'",
               name, extra[i][j], i, j, neighbor->skin, 4.0 * extra[i][j]);

  return MAX(maxrad[i] + maxrad[j] + extra[i][j], reach_abs[i][j]);
}

/* ---------------------------------------------------------------------- */

void PairSaltdem::write_restart(FILE *fp)
{
  write_restart_settings(fp);
  const int n = (int) coeff_names().size();
  std::vector<double> v(n);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      fwrite(&setflag[i][j], sizeof(int), 1, fp);
      if (setflag[i][j]) {
        pack_coeffs(i, j, v.data());
        fwrite(v.data(), sizeof(double), n, fp);
      }
    }
}

void PairSaltdem::read_restart(FILE *fp)
{
  read_restart_settings(fp);
  allocate();
  const int me = comm->me;
  const int n = ncoeff_read;
  std::vector<double> v(n);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++) {
      if (me == 0) utils::sfread(FLERR, &setflag[i][j], sizeof(int), 1, fp, nullptr, error);
      MPI_Bcast(&setflag[i][j], 1, MPI_INT, 0, world);
      if (setflag[i][j]) {
        if (me == 0) utils::sfread(FLERR, v.data(), sizeof(double), n, fp, nullptr, error);
        MPI_Bcast(v.data(), n, MPI_DOUBLE, 0, world);
        unpack_coeffs(i, j, v.data());
      }
    }
}

/* the mark, the style's layout version, its settings by name and value, the names of its
   coefficients (written by every style, also as a sub-style of pair hybrid) */

void PairSaltdem::write_restart_settings(FILE *fp)
{
  static_assert(RESTART_MARK == SaltDEM::RESTART_MARK, "one SaltDEM restart mark");
  const double mark = RESTART_MARK;
  fwrite(&mark, sizeof(double), 1, fp);
  const int version = restart_version();
  fwrite(&version, sizeof(int), 1, fp);
  auto write_names = [fp](const std::vector<std::string> &names) {
    const int n = (int) names.size();
    fwrite(&n, sizeof(int), 1, fp);
    for (const auto &s : names) {
      const int len = (int) s.size();
      fwrite(&len, sizeof(int), 1, fp);
      fwrite(s.data(), 1, len, fp);
    }
  };
  const auto settings = setting_names();
  write_names(settings);
  std::vector<double> v(settings.size());
  pack_settings(v.data());
  fwrite(v.data(), sizeof(double), v.size(), fp);
  write_names(coeff_names());
}

void PairSaltdem::read_restart_settings(FILE *fp)
{
  const int me = comm->me;
  double mark = 0.0;
  if (me == 0) utils::sfread(FLERR, &mark, sizeof(double), 1, fp, nullptr, error);
  MPI_Bcast(&mark, 1, MPI_DOUBLE, 0, world);
  if (mark != RESTART_MARK)
    error->all(FLERR,
               "Pair style {}: the restart file was written by another SaltDEM version ({}; this "
               "one reads restart format {:.0f}, which names its fields), whose coefficients and "
               "contact history are laid out differently. Continue the run with the version "
               "that wrote it, or start again from a data file (write_data) with this one",
               name,
               mark > 0.0 ? "one before restart formats were marked"
                          : fmt::format("restart format {:.0f}", mark),
               RESTART_MARK);
  int version = 0;
  if (me == 0) utils::sfread(FLERR, &version, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&version, 1, MPI_INT, 0, world);
  const auto reads = restart_versions_read();
  if (std::find(reads.begin(), reads.end(), version) == reads.end()) {
    std::string list = fmt::format("layout{} {}", reads.size() > 1 ? "s" : "", reads[0]);
    for (size_t k = 1; k < reads.size(); k++)
      list += fmt::format("{}{}", k + 1 < reads.size() ? ", " : " and ", reads[k]);
    error->all(FLERR,
               "Pair style {}: the restart file holds its coefficients in layout version {}, this "
               "version of the style reads {}. Continue the run with the SaltDEM version that "
               "wrote it, or start again from a data file (write_data) with this one",
               name, version, list);
  }
  layout_read = version;
  const auto settings = setting_names();
  read_names(fp, settings, "settings");
  std::vector<double> v(settings.size());
  if (me == 0 && !v.empty())
    utils::sfread(FLERR, v.data(), sizeof(double), v.size(), fp, nullptr, error);
  MPI_Bcast(v.data(), (int) v.size(), MPI_DOUBLE, 0, world);
  unpack_settings(v.data());
  const auto coeffs = coeff_names();    // (also of the layout being read)
  layout_read = 0;
  read_names(fp, coeffs, "coefficients");
  ncoeff_read = (int) coeffs.size();
}

/* a list of names in the file: it must be the style's own (the same version writes the
   same; a difference is a file edited or a style changed without its version) */

void PairSaltdem::read_names(FILE *fp, const std::vector<std::string> &want, const char *what)
{
  const int me = comm->me;
  int n = 0;
  if (me == 0) utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  if (n < 0 || n > 1000)
    error->all(FLERR, "Pair style {}: the restart file's list of {} is damaged ({} names)", name,
               what, n);
  std::vector<std::string> got;
  for (int k = 0; k < n; k++) {
    int len = 0;
    if (me == 0) utils::sfread(FLERR, &len, sizeof(int), 1, fp, nullptr, error);
    MPI_Bcast(&len, 1, MPI_INT, 0, world);
    if (len < 0 || len > 1000)
      error->all(FLERR, "Pair style {}: the restart file's list of {} is damaged", name, what);
    std::string s(len, ' ');
    if (me == 0 && len > 0) utils::sfread(FLERR, &s[0], 1, len, fp, nullptr, error);
    MPI_Bcast(&s[0], len, MPI_CHAR, 0, world);
    got.push_back(s);
  }
  if (got != want)
    error->all(FLERR,
               "Pair style {}: the restart file's {} are ({}), this version of the style "
               "has ({}); start again from a data file (write_data) with this version",
               name, what, utils::join_words(got, " "), utils::join_words(want, " "));
}

/* history of (i,j) seen from j: antisymmetric by default, but the rolling
   displacement is symmetric (see the derived style's transfer_factor) */

void PairSaltdem::transfer_history(double *source, double *target, int, int)
{
  for (int k = 0; k < size_history; k++) target[k] = transfer_factor[k] * source[k];
}

double PairSaltdem::memory_usage()
{
  const int n = atom->ntypes + 1;
  return (double) n * n * (2 * sizeof(double) + sizeof(int) + params_size());
}
