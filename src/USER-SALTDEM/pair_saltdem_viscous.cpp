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

   pair saltdem/viscous: the linear Newtonian salt, and the no-slip
   boundary contact of cover-salt, salt-wall and cover-wall pairs.  The laws
   are SaltDEM::viscous_fluid_force and viscous_contact_force
   (saltdem_contact_viscous.h), its law policy SaltDEM::ViscousLaw (saltdem_viscous_law.h);
   this file turns the requested viscosity into dashpot coefficients, sets the stable dt,
   keeps the restart data, and runs the SPH field passes (SaltDEM::SphFields) and the viscous
   sub-steps or implicit step (SaltdemViscousSplit) it owns.
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous.h"

#include "fix_saltdem_density.h"
#include "fix_saltdem_plastic.h"
#include "saltdem_check.h"
#include "saltdem_contact_viscous.h"
#include "saltdem_pair_loop.h"
#include "saltdem_plastic.h"
#include "saltdem_sph_fields.h"
#include "saltdem_viscous_args.h"
#include "saltdem_viscous_law.h"
#include "saltdem_viscous_split.h"

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "update.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

PairSaltdemViscous::PairSaltdemViscous(LAMMPS *lmp) :
    PairSaltdem(lmp, "saltdem/viscous", nullptr), params(nullptr), eta(nullptr),
    fields(new SaltDEM::SphFields), substep(new SaltdemViscousSplit(lmp, this)),
    fix_density(nullptr), fix_plastic(nullptr), fluidself(nullptr), isfluid(nullptr), nmax(0),
    any_fluid(false), calibration(DEFAULT_CALIBRATION), correction(DEFAULT_CORRECTION),
    viscfactor(0.8), fill_max(DEFAULT_FILL_MAX), substeps(1), noslip_surface(false),
    implicit(false), tolerance(DEFAULT_TOLERANCE), maxiter(DEFAULT_MAXITER),
    comm_mode(COMM_PRESSURE), calibration_checked(DEFAULT_CALIBRATION), salt_inertia(1.0)
{
  // volume, boundary fill, pressure matrix and no-slip offset, or the sub-step velocities; the
  // kernel sums (and velocity-gradient sums) of ghosts (newton on), or their sub-step forces
  comm_forward = 2 + SaltDEM::NSYM + 3;
  comm_reverse = SaltDEM::SPH_NMOM_MAX + SaltDEM::PLASTIC_NVG_MAX;
  // compute pair: the implicit step's iterations (last step, mean) and last residual
  nextra = 3;
  pvector = new double[nextra]();
}

PairSaltdemViscous::~PairSaltdemViscous()
{
  if (copymode) return;
  memory->destroy(params);
  memory->destroy(eta);
  delete fields;
  delete substep;
  delete[] pvector;
  memory->destroy(isfluid);
  memory->destroy(fluidself);
  // the salt's density and plastic stress are this pair style's state: they go with it
  for (const auto &id : {density_id, plastic_id})
    if (!id.empty() && modify->get_fix_by_id(id)) modify->delete_fix(id);
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
  compute_serial(law(), eflag, vflag);
}

SaltDEM::ViscousLaw PairSaltdemViscous::law() const
{
  return {params, isfluid, fields};
}

void PairSaltdemViscous::apply_substeps()
{
  if (!any_fluid) return;
  if (implicit) {
    substep->implicit(tolerance, maxiter);
    if (comm->me == 0) {
      pvector[0] = substep->iter_last;
      pvector[1] = substep->solves > 0.0 ? substep->iter_sum / substep->solves : 0.0;
      pvector[2] = substep->resid_last;
    }
  } else if (substeps > 1)
    substep->substeps(substeps);
}

void PairSaltdemViscous::implicit_report()
{
  if (!implicit || !any_fluid || substep->solves == 0.0) return;
  if (comm->me == 0)
    utils::logmesg(lmp,
                   "Pair style {}: implicit viscous step: {:.1f} iterations per step over {:.0f} "
                   "steps (last {}, residual {:.3g} of the explicit step's, tolerance {:.3g})\n",
                   name, substep->iter_sum / substep->solves, substep->solves, substep->iter_last,
                   substep->resid_last, tolerance);
  substep->iter_sum = substep->solves = 0.0;
}

void *PairSaltdemViscous::pair_params(int i, int j)
{
  return &params[i][j];
}

size_t PairSaltdemViscous::params_size() const
{
  return sizeof(SaltDEM::ViscousParams);
}

/* the dashpots of a CONTACT pair act up to its gap beyond contact; a FLUID pair reaches 2h
   between the centres */

double PairSaltdemViscous::range(int i, int j) const
{
  return params[i][j].mode == SaltDEM::VISCOUS_CONTACT ? params[i][j].gap : 0.0;
}

double PairSaltdemViscous::range_abs(int i, int j) const
{
  return params[i][j].mode == SaltDEM::VISCOUS_FLUID ? 2.0 * params[i][j].h : 0.0;
}

double PairSaltdemViscous::fluid_h(int t) const
{
  return params[t][t].h;
}

double PairSaltdemViscous::fluid_K(int t) const
{
  return params[t][t].K;
}

/* pair_style saltdem/viscous [correction C] [calibration C] [dtfactor C] [viscfactor C]
   [fill F] [substeps N] [noslip centre|surface] (saltdem_viscous_args.cpp) */

void PairSaltdemViscous::settings(int narg, char **arg)
{
  SaltDEM::ViscousSettings st = settings_now();
  SaltDEM::parse_viscous_settings(lmp, name, narg, arg, st, DTFACTOR_MAX, MAX_SUBSTEPS);
  set_settings(st);
}

SaltDEM::ViscousSettings PairSaltdemViscous::settings_now() const
{
  return {correction, calibration,    dtfactor, viscfactor, fill_max,
          substeps,   noslip_surface, implicit, tolerance,  maxiter};
}

void PairSaltdemViscous::set_settings(const SaltDEM::ViscousSettings &st)
{
  correction = st.correction;
  calibration = st.calibration;
  dtfactor = st.dtfactor;
  viscfactor = st.viscfactor;
  fill_max = st.fill_max;
  substeps = st.substeps;
  noslip_surface = st.noslip_surface;
  implicit = st.implicit;
  tolerance = st.tolerance;
  maxiter = st.maxiter;
  if (implicit && substeps > 1)
    error->all(FLERR,
               "Pair style {}: implicit yes and substeps {} both take the viscosity out of the "
               "force pass; choose one (implicit yes has no viscous step limit)",
               name, substeps);
}

/* saltdem/timestep F substeps N: the sub-steps of a style read from a restart file too */

bool PairSaltdemViscous::set_substeps(int n)
{
  substeps = SaltDEM::parse_viscous_substeps(lmp, name, std::to_string(n).c_str(), MAX_SUBSTEPS);
  if (implicit && substeps > 1)
    error->all(FLERR,
               "saltdem/timestep: substeps {} for pair style {}, whose viscosity is implicit "
               "(implicit yes): it has no viscous step limit to lift",
               substeps, name);
  return true;
}

/* saltdem/timestep F implicit yes|no [tolerance T] [maxiter N]: likewise (implicit yes clears
   the sub-steps; a tolerance or maxiter below zero keeps the style's) */

bool PairSaltdemViscous::set_implicit(bool on, double tol, int niter)
{
  implicit = on;
  if (on) substeps = 1;
  if (tol > 0.0) tolerance = tol;
  if (niter > 0) maxiter = niter;
  return true;
}

/* pair_coeff I J eta kn fluid h K [yield MU C] [modulus G]
   pair_coeff I J eta kn contact gap [tangential ratio] (saltdem_viscous_args.cpp) */

void PairSaltdemViscous::coeff(int narg, char **arg)
{
  const char *usage = "pair_coeff I J eta kn fluid h K [yield MU C] [modulus G]  or  "
                      "pair_coeff I J eta kn contact gap [tangential R]";
  int ilo, ihi, jlo, jhi;
  check_types(narg, arg, 6, usage, ilo, ihi, jlo, jhi);
  double eta_given = 0.0;
  const SaltDEM::ViscousParams p =
      SaltDEM::parse_viscous_coeff(lmp, name, narg, arg, usage, eta_given);
  assign_coeffs(ilo, ihi, jlo, jhi, [&](int i, int j) {
    params[i][j] = p;
    eta[i][j] = eta_given;
  });
}

/* the internal fix of style STYLE, created here (see the header) */

template <class F>
F *PairSaltdemViscous::internal_fix(const char *style, std::string &id, const char *what)
{
  const auto subs = substyles();
  const int nth = 1 + (int) (std::find(subs.begin(), subs.end(), this) - subs.begin());
  id = (nth == 1) ? std::string(style) : fmt::format("{}_{}", style, nth);
  Fix *f = modify->get_fix_by_id(id);
  if (!f) f = modify->add_fix(fmt::format("{} all {}", id, style));
  auto *fix = dynamic_cast<F *>(f);
  if (!fix)
    error->all(FLERR,
               "Pair style {}: fix ID {} is taken by a fix of style {}; the pair style keeps the "
               "salt's {} in an internal fix of that ID",
               name, id, f->style, what);
  return fix;
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
  eta[i][j] = mix_series(eta[i][i], eta[j][j]);
  p.kn = mix_series(a.kn, b.kn);
  p.h = 0.5 * (a.h + b.h);
  p.K = sqrt(a.K * b.K);
  p.ratio = 0.5 * (a.ratio + b.ratio);
  p.gap = 0.5 * (a.gap + b.gap);
  p.mu_y = p.coh_y = p.G = 0.0;    // (a type's plastic strength is its own pair's)
}

void PairSaltdemViscous::init_style()
{
  any_fluid = false;
  influid.assign(atom->ntypes + 1, 0);
  for (int i = 1; i <= atom->ntypes; i++) {
    // (under pair hybrid, types of other sub-styles have no coefficients here)
    fluidself[i] = (setflag[i][i] && params[i][i].mode == SaltDEM::VISCOUS_FLUID) ? 1 : 0;
    isfluid[i] = (fluidself[i] && params[i][i].K > 0.0) ? 1 : 0;
    for (int j = i; j <= atom->ntypes; j++)
      if (setflag[i][j] && params[i][j].mode == SaltDEM::VISCOUS_FLUID)
        any_fluid = influid[i] = influid[j] = 1;
  }
  // the continuity density of the fluid particles is the state of an internal fix
  // (FixSaltdemDensity), created here so that it finds its data in a restart file.  Its ID:
  // SALTDEM_DENSITY, or SALTDEM_DENSITY_N for the N-th saltdem/viscous sub-style of pair
  // hybrid (N > 1), the same for the same deck after read_restart
  fix_density = nullptr;
  fix_plastic = nullptr;
  isplastic.assign(atom->ntypes + 1, 0);
  bool any_plastic = false;
  for (int i = 1; i <= atom->ntypes; i++)
    if (isfluid[i] && (params[i][i].mu_y > 0.0 || params[i][i].coh_y > 0.0))
      any_plastic = isplastic[i] = 1;
  if (any_fluid) {
    fix_density = internal_fix<FixSaltdemDensity>("SALTDEM_DENSITY", density_id, "density");
    fix_density->pair = this;
  }
  // a frictional-viscous fluid's plastic stress: SALTDEM_PLASTIC likewise
  if (any_plastic) {
    fix_plastic = internal_fix<FixSaltdemPlastic>("SALTDEM_PLASTIC", plastic_id, "plastic stress");
    fix_plastic->pair = this;
  }
  fields->params = params;
  fields->fluidself = fluidself;
  fields->isfluid = isfluid;
  fields->ntypes = atom->ntypes;
  fields->fill_max = fill_max;
  fields->noslip = noslip_surface;
  fields->plastic = any_plastic;
  fields->isplastic = isplastic.data();
  fields->keep_pairs = substeps > 1 || implicit;
  // the sub-steps move the atoms that a fix integrates, with the inertia it gives them
  integrators = find_integrators();
  // (here, where every rank takes part: extract() may be called by one rank alone)
  salt_inertia = find_salt_inertia();
  if (any_fluid && noslip_surface && comm->me == 0)
    utils::logmesg(lmp,
                   "Pair style {}: no-slip at the surfaces of the boundary discs (noslip "
                   "surface: the fluid's velocity extrapolated into them)\n",
                   name);
  // said at every run: a resumed run keeps the file's sub-steps unless they are set again
  if (any_fluid && substeps > 1 && comm->me == 0)
    utils::logmesg(lmp, "Pair style {}: the viscosity in {} sub-steps per step (substeps)\n", name,
                   substeps);
  if (any_fluid && implicit && comm->me == 0)
    utils::logmesg(lmp,
                   "Pair style {}: the viscosity in an implicit step (tolerance {:.3g}, maxiter "
                   "{})\n",
                   name, tolerance, maxiter);
  PairSaltdem::init_style();
}

/* the kernel density of the owned atoms (SaltDEM::SphFields::kernel_density): for the
   reference density (FixSaltdemDensity) */

void PairSaltdemViscous::kernel_density(double *out, double *interior)
{
  grow_arrays();
  material_density();
  fields->kernel_density(
      domain->dimension, sph_input(),
      [this] {
        reverse_kernel_sums();
      },
      out, interior);
}

/* the atoms (owned, then ghosts) and the neighbour list of the field passes */

SaltDEM::SphInput PairSaltdemViscous::sph_input() const
{
  using row = const double(*)[3];
  SaltDEM::SphInput in;
  in.x = atom->x ? (row) atom->x[0] : nullptr;    // (none on an empty rank)
  in.v = atom->v ? (row) atom->v[0] : nullptr;
  in.rmass = atom->rmass;
  in.radius = atom->radius;
  in.type = atom->type;
  in.nlocal = atom->nlocal;
  in.nall = atom->nlocal + atom->nghost;
  in.newton = force->newton_pair != 0;
  in.inum = list->inum;
  in.ilist = list->ilist;
  in.numneigh = list->numneigh;
  in.firstneigh = list->firstneigh;
  in.neighmask = NEIGHMASK;
  return in;
}

void PairSaltdemViscous::reverse_kernel_sums()
{
  comm_mode = COMM_PRESSURE;
  comm->reverse_comm(this);
}

/* FLUID: before the force pass, the kernel sums of the present positions, each fluid
   particle's boundary fill, volume and pressure matrix (SaltDEM::SphFields), sent to the
   ghosts.  The density is the density fix's (see SphFields::pressure_matrices). */

void PairSaltdemViscous::pre_loop()
{
  grow_arrays();
  if (!any_fluid) return;
  material_density();
  if (fix_plastic) {
    fields->tau = fix_plastic->tau ? fix_plastic->tau[0] : nullptr;
    fields->dtau = fix_plastic->dtau ? fix_plastic->dtau[0] : nullptr;
    fields->ystress = fix_plastic->ystress;
  }
  fields->pressure_matrices(domain->dimension, sph_input(), fix_density->rho,
                            fix_density->rho0.data(), [this] {
                              reverse_kernel_sums();
                            });
  comm_mode = COMM_PRESSURE;
  comm->forward_comm(this);
}

void PairSaltdemViscous::grow_arrays()
{
  nmax = MAX(nmax, atom->nmax);
  fields->grow(nmax);
  // (sub-steps may be switched on between runs: saltdem/timestep ... substeps N)
  if (substeps > 1 || implicit) substep->grow(nmax);
}

/* a disc in a FLUID pair needs a radius: the material density m / r^dim weighs it */

void PairSaltdemViscous::material_density()
{
  const int bad = fields->material_density(sph_input(), domain->dimension, influid.data());
  if (bad >= 0)
    error->one(FLERR,
               "Pair style {}: atom {} of type {} has radius {} in a fluid pair; the fluid law "
               "weighs its partners by their size: give every disc a positive diameter (set "
               "... diameter)",
               name, atom->tag[bad], atom->type[bad], atom->radius[bad]);
}

/* the array the force pass sums d rho / dt into (zeroed here): the density fix's; with no
   FLUID pair (every q is 0) a scratch array.  The OpenMP variant sums per thread and adds
   the threads' sums into the same array. */

double *PairSaltdemViscous::loop_sum()
{
  const int nall = atom->nlocal + atom->nghost;
  if (!any_fluid && (int) scratch.size() < nmax) scratch.resize(nmax);
  double *sum = any_fluid ? fix_density->drho : scratch.data();
  for (int i = 0; i < nall; i++) sum[i] = 0.0;
  return sum;
}

int PairSaltdemViscous::pack_forward_comm(int n, int *list, double *buf, int, int *)
{
  if (comm_mode == COMM_SUBSTEP) return substep->pack_forward_comm(n, list, buf);
  return fields->pack_forward_comm(domain->dimension, n, list, buf);
}

void PairSaltdemViscous::unpack_forward_comm(int n, int first, double *buf)
{
  if (comm_mode == COMM_SUBSTEP) return substep->unpack_forward_comm(n, first, buf);
  fields->unpack_forward_comm(domain->dimension, n, first, buf);
}

int PairSaltdemViscous::pack_reverse_comm(int n, int first, double *buf)
{
  if (comm_mode == COMM_SUBSTEP) return substep->pack_reverse_comm(n, first, buf);
  return fields->pack_reverse_comm(domain->dimension, n, first, buf);
}

void PairSaltdemViscous::unpack_reverse_comm(int n, int *list, double *buf)
{
  if (comm_mode == COMM_SUBSTEP) return substep->unpack_reverse_comm(n, list, buf);
  fields->unpack_reverse_comm(domain->dimension, n, list, buf);
}

double PairSaltdemViscous::memory_usage()
{
  return PairSaltdem::memory_usage() + fields->memory_usage() + substep->memory_usage() +
      (double) scratch.capacity() * sizeof(double);
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
  }
  auto &p = params[i][j];
  const double e = eta[i][j];
  p.cw = SaltDEM::wendland_c2_grad_over_r(domain->dimension, p.h > 0.0 ? p.h : 1.0);
  p.ih2 = (p.h > 0.0) ? 0.5 / p.h : 0.0;
  p.cW = SaltDEM::wendland_c2(domain->dimension, p.h > 0.0 ? p.h : 1.0, 0.0);
  p.kvisc = 2.0 * correction * e * p.cw;
  // sub-stepped: not in the force pass (implicit: there, and corrected after)
  p.kfac = (substeps > 1) ? 0.0 : p.kvisc;
  p.gn = calibration * e;
  p.gt = p.ratio * p.gn;
  if (!std::isfinite(p.cw) || !std::isfinite(p.kvisc) || !std::isfinite(p.gn) ||
      !std::isfinite(p.gt) || !std::isfinite(p.ih2) || !std::isfinite(p.cW))
    error->all(FLERR,
               "Pair style {}: the dashpot coefficients of types {} {} are not finite (2 "
               "correction eta W'(h) = {}, calibration eta = {}, tangential ratio x that = {}) "
               "from eta = {}, h = {}, correction = {}, calibration = {}, tangential ratio = {}; "
               "use values of physical size",
               name, i, j, p.kvisc, p.gn, p.gt, e, p.h, correction, calibration, p.ratio);
  eta[j][i] = e;
}

/* a change of the viscosity or calibration since the last time step check (during a run: fix
   adapt calls reinit(), hence init_one()): the next force computation checks again */

double PairSaltdemViscous::init_one(int i, int j)
{
  const double cut = PairSaltdem::init_one(i, j);
  // a fluid that a boundary holds by its mirrored pressure alone sinks into a line of wall
  // discs and slips on it (docs/salt-validation.md 4.4: 4 m deep, slip length 14 m), and with the
  // fill it still leaks through in time (a disc after 1300 s of a 190 m film): refused
  const auto &p = params[i][j];
  if (p.mode == SaltDEM::VISCOUS_FLUID && p.kn == 0.0 && isfluid[i] != isfluid[j] &&
      !fluid_in_other_substyle(isfluid[i] ? j : i))
    error->all(FLERR,
               "Pair style {}: fluid type {} meets boundary type {} with kn 0: only the "
               "boundary's mirrored pressure would hold the fluid, and a line of wall discs "
               "lets it in (no no-slip base; with 'fill' too, in time); give the pair an "
               "elastic core (kn > 0, e.g. the boundary's kn_wall)",
               name, isfluid[i] ? i : j, isfluid[i] ? j : i);
  const double e = eta[i][j];
  if (setflag[i][j] && i < (int) eta_checked.size() && j < (int) eta_checked[i].size() &&
      (eta_checked[i][j] != e || calibration_checked != calibration)) {
    recheck = true;
    recheck_what = calibration_checked != calibration
        ? fmt::format("the calibration ({:.6g} -> {:.6g})", calibration_checked, calibration)
        : fmt::format("eta of types {} {} ({:.6g} -> {:.6g} Pa s, e.g. by fix adapt)", i, j,
                      eta_checked[i][j], e);
  }
  return cut;
}

/* the saltdem/viscous styles of the run in order: this one alone, or the sub-styles of this
   name under pair hybrid (PairSaltdem::saltdem_styles) */

std::vector<PairSaltdemViscous *> PairSaltdemViscous::substyles() const
{
  std::vector<PairSaltdemViscous *> out;
  for (auto *s : saltdem_styles(lmp, name))
    if (auto *v = dynamic_cast<PairSaltdemViscous *>(s)) out.push_back(v);
  return out;
}

/* whether type t is a fluid (its own pair FLUID with K > 0) of another saltdem/viscous
   sub-style of pair hybrid: two salts of two sub-styles meet as fluids, not at a wall */

bool PairSaltdemViscous::fluid_in_other_substyle(int t) const
{
  for (auto *s : substyles())
    if (s != this && s->allocated && s->setflag[t][t] &&
        s->params[t][t].mode == SaltDEM::VISCOUS_FLUID && s->params[t][t].K > 0.0)
      return true;
  return false;
}

/* ---------------------------------------------------------------------- */

/* the restart fields (saltdem_viscous_args.cpp), of the layout being read where one is */

std::vector<std::string> PairSaltdemViscous::setting_names() const
{
  return SaltDEM::viscous_setting_names(layout_read);
}

void PairSaltdemViscous::pack_settings(double *v) const
{
  SaltDEM::pack_viscous_settings(settings_now(), v);
}

void PairSaltdemViscous::unpack_settings(const double *v)
{
  SaltDEM::ViscousSettings st = settings_now();
  SaltDEM::unpack_viscous_settings(v, layout_read, DEFAULT_FILL_MAX, st);
  set_settings(st);
}

std::vector<std::string> PairSaltdemViscous::coeff_names() const
{
  return SaltDEM::viscous_coeff_names(layout_read);    // (of the layout being read)
}

void PairSaltdemViscous::pack_coeffs(int i, int j, double *v) const
{
  SaltDEM::pack_viscous_coeff(params[i][j], eta[i][j], v);
}

void PairSaltdemViscous::unpack_coeffs(int i, int j, const double *v)
{
  SaltDEM::unpack_viscous_coeff(v, ncoeff_read, params[i][j], eta[i][j]);
}

/* the inertia factor S of the viscous discs: the largest of the integrated atoms of the types
   whose own pair I,I is this style's (the salt), 1 if none is integrated.  Collective. */

double PairSaltdemViscous::find_salt_inertia()
{
  double s = 0.0, all = 0.0;
  const Integrators now = find_integrators();    // (also asked before the run's init)
  if (allocated)
    for (int i = 0; i < atom->nlocal; i++)
      if (setflag[atom->type[i]][atom->type[i]]) s = MAX(s, inertia_scale(atom->mask[i], now));
  MPI_Allreduce(&s, &all, 1, MPI_DOUBLE, MPI_MAX, world);
  return (all > 0.0) ? all : 1.0;
}

/* "eta": per type pair viscosity (dim 2), read and changed by fix adapt and
   fix saltdem/viscosity; "calibration": dashpot per unit viscosity; "inertia": the inertia
   factor of the salt's discs as of the last init (find_salt_inertia()) */

void *PairSaltdemViscous::extract(const char *str, int &dim)
{
  if (strcmp(str, "eta") == 0) {
    dim = 2;
    return (void *) eta;
  }
  dim = 0;
  if (strcmp(str, "calibration") == 0) return (void *) &calibration;
  if (strcmp(str, "inertia") == 0) return (void *) &salt_inertia;
  return nullptr;
}
