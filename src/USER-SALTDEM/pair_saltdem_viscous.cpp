/* ----------------------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   pair saltdem/viscous: the linear Newtonian salt, and the no-slip
   boundary contact of cover-salt, salt-wall and cover-wall pairs.  The laws
   are SaltDEM::viscous_fluid_force and viscous_contact_force
   (saltdem_contact.h); this file turns the requested viscosity into dashpot
   coefficients, carries the fluid's density and sets the stable dt.
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous.h"

#include "saltdem_check.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "suffix.h"

#include "omp_compat.h"

#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

static const char RHO_FIX_ID[] = "SALTDEM_VISCOUS_RHO";

PairSaltdemViscous::PairSaltdemViscous(LAMMPS *lmp) :
    PairSaltdem(lmp, "saltdem/viscous", nullptr), params(nullptr), eta(nullptr), vol(nullptr), apress(nullptr), rho(nullptr), index_rho(-1), fluidself(nullptr), isfluid(nullptr), nmax(0),
    any_fluid(false),
    calibration(DEFAULT_CALIBRATION), correction(DEFAULT_CORRECTION), viscfactor(0.5),
    calibration_checked(DEFAULT_CALIBRATION), salt_inertia(1.0)
{
  comm_forward = 2;
  comm_reverse = 1;
}

PairSaltdemViscous::~PairSaltdemViscous()
{
  if (copymode) return;
  memory->destroy(params);
  memory->destroy(eta);
  memory->destroy(vol);
  memory->destroy(apress);
  memory->destroy(rho);
  memory->destroy(isfluid);
  memory->destroy(fluidself);
  if (modify->get_fix_by_id(RHO_FIX_ID)) modify->delete_fix(RHO_FIX_ID);
}

void PairSaltdemViscous::allocate_params(int n)
{
  memory->create(params, n + 1, n + 1, "pair:params");
  memset(&params[0][0], 0, sizeof(SaltDEM::ViscousParams) * (n + 1) * (n + 1));
  memory->create(eta, n + 1, n + 1, "pair:eta");
  memory->create(isfluid, n + 1, "pair:isfluid");
  memory->create(fluidself, n + 1, "pair:fluidself");
}

void PairSaltdemViscous::compute(int eflag, int vflag)
{
  compute_serial(this, eflag, vflag);
}

/* pair_style saltdem/viscous [correction C] [calibration C] [dtfactor C] [viscfactor C] */

void PairSaltdemViscous::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    if (iarg + 2 > narg)
      utils::missing_cmd_args(FLERR, fmt::format("pair_style {} {}", name, arg[iarg]), error);
    const double v = SaltDEM::numeric(FLERR, arg[iarg + 1],
                                      fmt::format("Pair style {}: {}", name, arg[iarg]), lmp);
    if (strcmp(arg[iarg], "correction") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style {}: correction {} must be > 0", name, v);
      correction = v;
    } else if (strcmp(arg[iarg], "calibration") == 0) {
      if (v <= 0.0) error->all(FLERR, "Pair style {}: calibration {} must be > 0", name, v);
      calibration = v;
    } else if (strcmp(arg[iarg], "dtfactor") == 0) {
      if (v <= 0.0 || v > 0.8)
        error->all(FLERR, "Pair style {}: dtfactor {} must be in (0, 0.8]", name, v);
      dtfactor = v;
    } else if (strcmp(arg[iarg], "viscfactor") == 0) {
      if (v <= 0.0 || v > 1.0)
        error->all(FLERR, "Pair style {}: viscfactor {} must be in (0, 1]", name, v);
      viscfactor = v;
    } else
      error->all(FLERR,
                 "Pair style {}: unknown keyword '{}' (expected: correction, calibration, "
                 "dtfactor, viscfactor)",
                 name, arg[iarg]);
    iarg += 2;
  }
}

/* pair_coeff I J eta kn fluid h
   pair_coeff I J eta kn contact gap [tangential ratio] */

void PairSaltdemViscous::coeff(int narg, char **arg)
{
  const char *usage =
      "pair_coeff I J eta kn fluid h K  or  pair_coeff I J eta kn contact gap [tangential R]";
  int ilo, ihi, jlo, jhi;
  check_types(narg, arg, 6, usage, ilo, ihi, jlo, jhi);

  SaltDEM::ViscousParams p{};
  auto value = [&](const char *str, const char *what) {
    return SaltDEM::numeric(FLERR, str, fmt::format("Pair style {}: {}", name, what), lmp);
  };
  p.eta = value(arg[2], "eta");
  p.kn = value(arg[3], "kn");
  if (p.eta <= 0.0) error->all(FLERR, "Pair style {}: eta = {} must be > 0", name, p.eta);
  if (p.kn < 0.0) error->all(FLERR, "Pair style {}: kn = {} must be >= 0", name, p.kn);
  p.ratio = 1.0;

  std::string kw = arg[4];
  if (kw == "fluid") {
    p.mode = SaltDEM::VISCOUS_FLUID;
    p.h = value(arg[5], "fluid h");
    if (p.h <= 0.0) error->all(FLERR, "Pair style {}: fluid h = {} must be > 0", name, p.h);
    if (narg != 7)
      error->all(FLERR, "Pair style {}: 'fluid' takes h and K, got {} values; usage: {}", name,
                 narg - 5, usage);
    p.K = value(arg[6], "fluid K");
    if (p.K < 0.0) error->all(FLERR, "Pair style {}: fluid K = {} must be >= 0", name, p.K);
  } else if (kw == "contact") {
    p.mode = SaltDEM::VISCOUS_CONTACT;
    if (p.kn <= 0.0)
      error->all(FLERR, "Pair style {}: contact kn = {} must be > 0 (a boundary needs its elastic "
                 "repulsion)", name, p.kn);
    p.gap = value(arg[5], "contact gap");
    if (p.gap < 0.0) error->all(FLERR, "Pair style {}: contact gap = {} must be >= 0", name, p.gap);
    if (narg == 8 && strcmp(arg[6], "tangential") == 0) {
      p.ratio = value(arg[7], "tangential ratio");
      if (p.ratio < 0.0)
        error->all(FLERR, "Pair style {}: tangential ratio = {} must be >= 0", name, p.ratio);
    } else if (narg != 6)
      error->all(FLERR, "Pair style {}: unexpected arguments after 'contact {}' (allowed: "
                 "tangential R); usage: {}", name, arg[5], usage);
  } else
    error->all(FLERR, "Pair style {}: unknown law '{}' (expected fluid or contact); usage: {}",
               name, kw, usage);

  assign_coeffs(ilo, ihi, jlo, jhi, [&](int i, int j) {
    params[i][j] = p;
    eta[i][j] = p.eta;
    // under pair hybrid, whose restart files hold no coefficients, the pair_coeff given
    // again after read_restart keeps the reference density of the file (same kernel h)
    if (i == j && p.mode == SaltDEM::VISCOUS_FLUID && i < (int) rho0_restart.size() &&
        rho0_restart[i] > 0.0 && fabs(h_restart[i] - p.h) <= 1e-12 * p.h) {
      params[i][i].rho0 = rho0_restart[i];
      if (comm->me == 0)
        utils::logmesg(lmp, "pair {}: reference density of fluid type {} = {:.15g} (from the "
                       "restart file)\n", name, i, rho0_restart[i]);
    }
  });
}

/* cross types of the same law: springs and dashpots in series, lengths
   averaged; two different laws do not mix (set the pair explicitly) */

void PairSaltdemViscous::mix(int i, int j)
{
  const auto &a = params[i][i];
  const auto &b = params[j][j];
  if (a.mode != b.mode)
    error->all(FLERR,
               "Pair style {}: types {} ({}) and {} ({}) use different laws and cannot be mixed; "
               "add 'pair_coeff {} {} ...' (contact for a boundary)",
               name, i, a.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", j,
               b.mode == SaltDEM::VISCOUS_FLUID ? "fluid" : "contact", i, j);
  auto &p = params[i][j];
  p = a;
  p.eta = mix_series(eta[i][i], eta[j][j]);
  p.kn = mix_series(a.kn, b.kn);
  p.h = 0.5 * (a.h + b.h);
  p.K = sqrt(a.K * b.K);
  p.rho0 = 0.0;
  p.ratio = 0.5 * (a.ratio + b.ratio);
  p.gap = 0.5 * (a.gap + b.gap);
  eta[i][j] = p.eta;
}

void PairSaltdemViscous::init_style()
{
  rho0_restart.clear();    // only the pair_coeff commands before the first run keep them
  h_restart.clear();
  dim2 = (domain->dimension == 2);
  volfac = dim2 ? M_PI : 4.0 * M_PI / 3.0;
  any_fluid = false;
  for (int i = 1; i <= atom->ntypes; i++) {
    // (under pair hybrid, types of other sub-styles have no coefficients here)
    fluidself[i] = (setflag[i][i] && params[i][i].mode == SaltDEM::VISCOUS_FLUID) ? 1 : 0;
    isfluid[i] = (fluidself[i] && params[i][i].K > 0.0) ? 1 : 0;
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && params[i][j].mode == SaltDEM::VISCOUS_FLUID) any_fluid = true;
  }
  // the continuity density of fluid particles lives with the atoms
  if (any_fluid) {
    if (!modify->get_fix_by_id(RHO_FIX_ID))
      modify->add_fix(fmt::format("{} all property/atom d_saltdem_rho writedata no", RHO_FIX_ID));
    int flag, cols;
    index_rho = atom->find_custom("saltdem_rho", flag, cols);
    if (index_rho < 0 || flag != 1 || cols != 0)
      error->all(FLERR, "Pair style {}: per-atom property d_saltdem_rho is missing", name);
  }
  PairSaltdem::init_style();
}

/* the kernel density rho[i] = sum_j m_j W_ij (j = i included) of every owned
   atom of a type whose own pair is FLUID, over the FLUID pairs of the list
   (summed onto the owners with newton on): once, for the reference density */

template <int DIM> void PairSaltdemViscous::kernel_density()
{
  const auto x = atom->x ? (const double (*)[3]) atom->x[0] : nullptr;    // (none on an empty rank)
  const double *m = atom->rmass;
  const int *type = atom->type;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  const int newton_pair = force->newton_pair;
  for (int i = 0; i < nall; i++) {
    const int t = type[i];
    rho[i] = (i < nlocal && fluidself[t]) ? m[i] * SaltDEM::wendland_c2(DIM, params[t][t].h, 0.0) : 0.0;
  }
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    const SaltDEM::ViscousParams *prow = params[type[i]];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const SaltDEM::ViscousParams &p = prow[type[j]];
      if (p.mode != SaltDEM::VISCOUS_FLUID) continue;
      double rsq = 0.0;
      for (int k = 0; k < DIM; k++) rsq += (x[i][k] - x[j][k]) * (x[i][k] - x[j][k]);
      const double w = SaltDEM::wendland_c2(DIM, p.h, sqrt(rsq));
      rho[i] += m[j] * w;
      if (newton_pair || j < nlocal) rho[j] += m[i] * w;
    }
  }
  if (newton_pair) comm->reverse_comm(this);
}

/* FLUID density, volume and pressure.  The density of a fluid particle is
   carried per atom (fix property/atom d_saltdem_rho, so it migrates and
   restarts with the atom) and follows the continuity equation
     d rho_i / dt = sum_j m_j (v_i - v_j) . grad_i W_ij
   over the FLUID pairs (walls and cover included: moving boundaries compress
   the fluid), summed in the force pass and applied after it (post_loop), as
   LAMMPS's SPH styles do: the pressure of a step is that of the density at
   the end of the step before.  It starts at the reference rho0 of its type,
   the mean kernel density sum_j m_j W_ij of that type at the first step, so
   the fluid starts free of pressure.  A summed kernel density would instead
   drift upwards as particles pair up (the mean of sum_j W grows while the
   volume does not).  Here, before the force pass: the volume m / rho, the
   pressure P = K (rho / rho0 - 1) and a = m P / rho^2, sent to the ghosts. */

void PairSaltdemViscous::pre_loop()
{
  // the force pass sums every pair's q (0 for CONTACT pairs) into rho, or under -sf omp into
  // one slice per thread (post_loop adds them up): needed with no FLUID pair too
  grow_arrays();
  const int nthreads = (suffix_flag & Suffix::OMP) ? comm->nthreads : 1;
  if (nthreads > 1 && (bigint) nthreads * nmax > (bigint) rho_thr.size())
    rho_thr.resize((size_t) nthreads * nmax);
  if (!any_fluid) return;
  const int nlocal = atom->nlocal;
  double *m = atom->rmass;
  int *type = atom->type;
  double *rhoc = atom->dvector[index_rho];
  const int dim = domain->dimension;
  const int nt = atom->ntypes;

  // reference density of each fluid type, once: mean kernel density
  bool need = false;
  for (int t = 1; t <= nt; t++)
    if (fluidself[t] && params[t][t].rho0 <= 0.0) need = true;
  if (need) {
    if (dim == 2)
      kernel_density<2>();
    else
      kernel_density<3>();
    // per type: kernel density sum and count, and the continuity densities that atoms
    // already carry (from an earlier run or a restart file) with their count
    std::vector<double> sum(4 * (nt + 1), 0.0), all(4 * (nt + 1));
    for (int i = 0; i < nlocal; i++) {
      sum[4 * type[i]] += rho[i];
      sum[4 * type[i] + 1] += 1.0;
      if (rhoc[i] > 0.0) {
        sum[4 * type[i] + 2] += rhoc[i];
        sum[4 * type[i] + 3] += 1.0;
      }
    }
    MPI_Allreduce(sum.data(), all.data(), 4 * (nt + 1), MPI_DOUBLE, MPI_SUM, world);
    for (int t = 1; t <= nt; t++)
      if (fluidself[t] && params[t][t].rho0 <= 0.0 && all[4 * t + 1] > 0.0) {
        params[t][t].rho0 = all[4 * t] / all[4 * t + 1];
        if (comm->me == 0)
          utils::logmesg(lmp, "pair {}: reference density of fluid type {} = {:.15g}\n", name,
                         t, params[t][t].rho0);
        if (all[4 * t + 3] > 0.0 && comm->me == 0) {
          const double carried = all[4 * t + 2] / all[4 * t + 3];
          error->warning(FLERR,
                         "Pair style {}: the reference density of fluid type {} was "
                         "measured again ({:.6g}) while its atoms carry densities from an earlier "
                         "run or a restart file: their pressure is reset (mean now {:.3g}), and a "
                         "fluid under load loses the pressure that carried it. After read_restart "
                         "give only the pair_coeff commands, not pair_style, to keep the "
                         "reference density of the file",
                         name, t, params[t][t].rho0,
                         params[t][t].K * (carried / params[t][t].rho0 - 1.0));
        }
      }
  }
  for (int i = 0; i < nlocal; i++)
    if (fluidself[type[i]] && rhoc[i] <= 0.0) rhoc[i] = params[type[i]][type[i]].rho0;

  // a boundary particle (wall, cover) gets the volume it would have at the
  // fluid's reference density
  double rhob = 0.0;
  for (int t = 1; t <= nt; t++)
    if (fluidself[t]) rhob = MAX(rhob, params[t][t].rho0);
  for (int i = 0; i < nlocal; i++) {
    const auto &p = params[type[i]][type[i]];
    const double r = fluidself[type[i]] ? rhoc[i] : rhob;
    vol[i] = (r > 0.0) ? m[i] / r : 0.0;
    apress[i] = (isfluid[type[i]] && p.rho0 > 0.0) ? m[i] * p.K * (r / p.rho0 - 1.0) / (r * r) : 0.0;
  }
  comm->forward_comm(this);
}

void PairSaltdemViscous::grow_arrays()
{
  if (atom->nmax <= nmax) return;
  memory->destroy(vol);
  memory->destroy(apress);
  memory->destroy(rho);
  nmax = atom->nmax;
  memory->create(vol, nmax, "pair:vol");
  memory->create(apress, nmax, "pair:apress");
  memory->create(rho, nmax, "pair:rho");
}

/* the array the force pass sums d rho / dt into: rho, or thread tid's slice
   (zeroed here, by the thread that fills it) */

double *PairSaltdemViscous::loop_sum(int tid, int nthreads)
{
  const int nall = atom->nlocal + atom->nghost;
  double *out = (nthreads > 1) ? rho_thr.data() + (size_t) tid * nmax : rho;
  for (int i = 0; i < nall; i++) out[i] = 0.0;
  return out;
}

/* continuity: rho += dt * d rho / dt for the owned fluid particles (not
   during setup, like the history of the contact styles) */

void PairSaltdemViscous::post_loop(int nthreads)
{
  if (!any_fluid || update->setupflag) return;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;
  if (nthreads > 1) {
    const double *part = rho_thr.data();
#if defined(_OPENMP)
#pragma omp parallel for num_threads(nthreads) schedule(static) LMP_DEFAULT_NONE LMP_SHARED(part, nall, nthreads)
#endif
    for (int i = 0; i < nall; i++) {
      double add = 0.0;
      for (int t = 0; t < nthreads; t++) add += part[(size_t) t * nmax + i];
      rho[i] = add;
    }
  }
  if (force->newton_pair) comm->reverse_comm(this);
  const int *type = atom->type;
  double *rhoc = atom->dvector[index_rho];
  const double dt = update->dt;
  for (int i = 0; i < nlocal; i++)
    if (fluidself[type[i]]) rhoc[i] += dt * rho[i];
}

int PairSaltdemViscous::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  int k = 0;
  for (int i = 0; i < n; i++) {
    buf[k++] = vol[list[i]];
    buf[k++] = apress[list[i]];
  }
  return k;
}

void PairSaltdemViscous::unpack_forward_comm(int n, int first, double *buf)
{
  int k = 0;
  for (int i = first; i < first + n; i++) {
    vol[i] = buf[k++];
    apress[i] = buf[k++];
  }
}

int PairSaltdemViscous::pack_reverse_comm(int n, int first, double *buf)
{
  for (int i = 0; i < n; i++) buf[i] = rho[first + i];
  return n;
}

void PairSaltdemViscous::unpack_reverse_comm(int n, int *list, double *buf)
{
  for (int i = 0; i < n; i++) rho[list[i]] += buf[i];
}

double PairSaltdemViscous::memory_usage()
{
  return PairSaltdem::memory_usage() + 3.0 * nmax * sizeof(double);
}

/* the dashpots from the viscosity, which may have been changed through extract("eta") since
   the last run (fix adapt, fix saltdem/viscosity) */

void PairSaltdemViscous::derive(int i, int j)
{
  if (setflag[i][j]) {
    // a viscosity set through extract("eta") (fix adapt, fix saltdem/viscosity) passes the
    // bounds of pair_coeff too
    if (!(eta[i][j] > 0.0) || !SaltDEM::in_bounds(eta[i][j]))
      error->all(FLERR,
                 "Pair style {}: eta = {} of types {} {}, set through extract(\"eta\") (fix adapt "
                 "or fix saltdem/viscosity), must be > 0, finite and of a magnitude in [{:g}, "
                 "{:g}]; check the variable or the viscosity that sets it",
                 name, eta[i][j], i, j, SaltDEM::MIN_VALUE, SaltDEM::MAX_VALUE);
    params[i][j].eta = eta[i][j];
  }
  auto &p = params[i][j];
  p.cw = SaltDEM::wendland_c2_grad_over_r(domain->dimension, p.h > 0.0 ? p.h : 1.0);
  p.ih2 = (p.h > 0.0) ? 0.5 / p.h : 0.0;
  p.kfac = 2.0 * correction * p.eta * p.cw;
  p.gn = calibration * p.eta;
  p.gt = p.ratio * p.gn;
  if (!std::isfinite(p.cw) || !std::isfinite(p.kfac) || !std::isfinite(p.gn) ||
      !std::isfinite(p.gt) || !std::isfinite(p.ih2))
    error->all(FLERR,
               "Pair style {}: the dashpot coefficients of types {} {} are not finite (2 "
               "correction eta W'(h) = {}, calibration eta = {}, tangential ratio x that = {}) "
               "from eta = {}, h = {}, correction = {}, calibration = {}, tangential ratio = {}; "
               "use values of physical size",
               name, i, j, p.kfac, p.gn, p.gt, p.eta, p.h, correction, calibration, p.ratio);
  eta[j][i] = eta[i][j] = p.eta;
}

/* a change of the viscosity or calibration since the last time step check (during a run: fix
   adapt calls reinit(), hence init_one()): the next force computation checks again */

double PairSaltdemViscous::init_one(int i, int j)
{
  const double cut = PairSaltdem::init_one(i, j);
  const auto &p = params[i][j];
  if (setflag[i][j] && i < (int) eta_checked.size() && j < (int) eta_checked[i].size() &&
      (eta_checked[i][j] != p.eta || calibration_checked != calibration)) {
    recheck = true;
    recheck_what = calibration_checked != calibration
        ? fmt::format("the calibration ({:.6g} -> {:.6g})", calibration_checked, calibration)
        : fmt::format("eta of types {} {} ({:.6g} -> {:.6g} Pa s, e.g. by fix adapt)", i, j,
                      eta_checked[i][j], p.eta);
  }
  return cut;
}

/* the viscosities and calibration of the last time step check */

void PairSaltdemViscous::limits_checked()
{
  PairSaltdem::limits_checked();
  const int n = allocated ? atom->ntypes : 0;
  eta_checked.assign(n + 1, std::vector<double>(n + 1, 0.0));
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) eta_checked[i][j] = eta[i][j];
  calibration_checked = calibration;
}

/* Limits per type pair.  Elastic: dtfactor * sqrt(m/kn).  Viscous: an
   explicit dashpot network is stable while dt < m / sum(gamma) for every
   particle (Gershgorin).  FLUID: the kernel sums to sum(gamma) = 7 eta V / h^2
   (2D and 3D), so dt < S m h^2 / (7 eta V).
   CONTACT: a disc's tangential dashpot also spins it (SaltDEM::rotation_factor),
   so dt < m / (g (1 + rot ratio)).  Both times viscfactor. */

void PairSaltdemViscous::pair_limit(int i, int j, double m, double mv, double &best,
                                    std::string &why)
{
  const double rot = SaltDEM::rotation_factor(domain->dimension);
  const double f2v = force->ftm2v;    // (1 in SI) forces and dashpots act on m / ftm2v
  const double e = eta[i][j];
  const auto &p = params[i][j];
  if (p.kn > 0.0)
    consider_limit(dtfactor * sqrt(m / (p.kn * f2v)), best, why, [&] {
      return fmt::format("kn = {:.6g} of types {} {} with the lightest mass {:.6g} "
                         "(dt < {} * sqrt(m/kn))", p.kn, i, j, m, dtfactor);
    });
  double lim;
  std::string formula;
  if (p.mode == SaltDEM::VISCOUS_FLUID) {
    // V = 1/sum W is not known before the first step: bound it by the
    // disc volume over a packing fraction of 0.7
    lim = viscfactor * mv * 0.7 * p.h * p.h / (7.0 * correction * e * f2v);
    formula = fmt::format("dt < {} * S m h^2 / (7 correction eta V), V = disc/0.7, h = {:.6g}, "
                          "correction = {:.6g}", viscfactor, p.h, correction);
    // sound: c^2 = K / rho with the inertial density, CFL 0.25 h / c
    if (p.K > 0.0) {
      const double c = sqrt(p.K * f2v / (0.7 * mv));
      consider_limit(0.25 * p.h / c, best, why, [&] {
        return fmt::format("K = {:.6g} of types {} {} (sound speed {:.4g} with the inertial "
                           "density; dt < 0.25 h / c, h = {:.6g}); a larger dt needs a smaller "
                           "K or more inertia", p.K, i, j, c, p.h);
      });
    }
  } else {
    lim = viscfactor * m / (calibration * e * (1.0 + rot * p.ratio) * f2v);
    formula = fmt::format("dt < {} * S m / (calibration * eta * (1 + {} * ratio)), "
                          "calibration = {:.6g}, ratio = {:.6g}, lightest mass {:.6g}",
                          viscfactor, rot, calibration, p.ratio, m);
  }
  consider_limit(lim, best, why, [&] {
    return fmt::format("eta = {:.6g} of types {} {} ({}); a larger dt needs a smaller eta "
                       "or more inertia for the viscous discs ('fix saltdem/nve ... inertia "
                       "S' with S >= {:.3g} times the present one)",
                       e, i, j, formula, update->dt / lim);
  });
}

/* ---------------------------------------------------------------------- */

void PairSaltdemViscous::read_restart(FILE *fp)
{
  PairSaltdem::read_restart(fp);
  for (int i = 1; i <= atom->ntypes; i++)
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j]) eta[i][j] = params[i][j].eta;
  // the coefficients came with the file: a pair_coeff given again resets rho0 as usual
  rho0_restart.clear();
  h_restart.clear();
}

void PairSaltdemViscous::write_restart_settings(FILE *fp)
{
  write_restart_format(fp);
  fwrite(&calibration, sizeof(double), 1, fp);
  fwrite(&correction, sizeof(double), 1, fp);
  fwrite(&dtfactor, sizeof(double), 1, fp);
  fwrite(&viscfactor, sizeof(double), 1, fp);
  // the reference density (and h) of each fluid type: pair hybrid writes only the settings of
  // its sub-styles, and a restarted fluid must not measure it again
  const int n = allocated ? atom->ntypes : 0;
  fwrite(&n, sizeof(int), 1, fp);
  for (int t = 1; t <= n; t++) {
    double v[2] = {0.0, 0.0};
    if (setflag[t][t] && params[t][t].mode == SaltDEM::VISCOUS_FLUID) {
      v[0] = params[t][t].rho0;
      v[1] = params[t][t].h;
    }
    fwrite(v, sizeof(double), 2, fp);
  }
}

void PairSaltdemViscous::read_restart_settings(FILE *fp)
{
  read_restart_format(fp);
  double buf[4];
  if (comm->me == 0) utils::sfread(FLERR, buf, sizeof(double), 4, fp, nullptr, error);
  MPI_Bcast(buf, 4, MPI_DOUBLE, 0, world);
  calibration = buf[0];
  correction = buf[1];
  dtfactor = buf[2];
  viscfactor = buf[3];
  int n = 0;
  if (comm->me == 0) utils::sfread(FLERR, &n, sizeof(int), 1, fp, nullptr, error);
  MPI_Bcast(&n, 1, MPI_INT, 0, world);
  std::vector<double> v(2 * n + 2, 0.0);
  if (comm->me == 0 && n > 0) utils::sfread(FLERR, v.data(), sizeof(double), 2 * n, fp, nullptr, error);
  MPI_Bcast(v.data(), 2 * n, MPI_DOUBLE, 0, world);
  rho0_restart.assign(n + 1, 0.0);
  h_restart.assign(n + 1, 0.0);
  for (int t = 1; t <= n; t++) {
    rho0_restart[t] = v[2 * (t - 1)];
    h_restart[t] = v[2 * (t - 1) + 1];
  }
}

/* the inertia factor S of the viscous discs: the largest of the integrated atoms of the types
   whose own pair I,I is this style's (the salt), 1 if none is integrated.  Collective. */

double PairSaltdemViscous::find_salt_inertia()
{
  double s = 0.0, all = 0.0;
  if (allocated)
    for (int i = 0; i < atom->nlocal; i++)
      if (setflag[atom->type[i]][atom->type[i]]) s = MAX(s, inertia_scale(i));
  MPI_Allreduce(&s, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return (all > 0.0) ? all : 1.0;
}

/* "eta": per type pair viscosity (dim 2), read and changed by fix adapt and
   fix saltdem/viscosity; "calibration": dashpot per unit viscosity; "inertia": the inertia
   factor of the salt's discs (find_salt_inertia(), collective: every rank must ask) */

void *PairSaltdemViscous::extract(const char *str, int &dim)
{
  if (strcmp(str, "eta") == 0) {
    dim = 2;
    return (void *) eta;
  }
  dim = 0;
  if (strcmp(str, "calibration") == 0) return (void *) &calibration;
  if (strcmp(str, "inertia") == 0) {
    salt_inertia = find_salt_inertia();
    return (void *) &salt_inertia;
  }
  return nullptr;
}
