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

   pair saltdem/viscous: the stable time step limits of its laws per type pair
   (elastic core, SPH viscosity and sound, contact dashpots), which the pair's
   time step check (PairSaltdem) compares with dt.
------------------------------------------------------------------------- */

#include "pair_saltdem_viscous.h"

#include "saltdem_contact_viscous.h"
#include "saltdem_pair_loop.h"

#include "domain.h"
#include "force.h"
#include "update.h"

#include <cmath>

using namespace LAMMPS_NS;

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

/* Limits per type pair.  Elastic: C sqrt(m/kn), C = dtfactor (2 dtfactor against a wall).
   Viscous: an explicit dashpot network is stable while dt < 2 / lambda_max, and Gershgorin
   bounds lambda_max by 2 max sum(gamma) / m.  FLUID: the kernel sums to sum(gamma) =
   7 eta V / h^2 (2D and 3D), which with V = 1/sum W gives dt < S m h^2 / (7 eta V); the
   constant 0.175 S rho h^2 / (correction eta) (viscfactor 1, rho the disc density) is the
   lowest limit measured (bench/validation/stable_limit.py: 0.177 at S 200 near the sound limit,
   0.197-0.211 in channels at S 5-80, 0.22-0.26 in the Expt 1 scene; Gershgorin's bound with
   V = disc/0.7 is 0.1).  Spheres (3D): 0.073, measured in a Couette channel of spheres (the
   sound rule holds as for discs).  CONTACT: a disc's tangential dashpot
   also spins it (SaltDEM::rotation_factor), so dt < m / (g (1 + rot ratio)); measured
   1.26-1.55 times that, so 0.625 of it at viscfactor 1.  The default viscfactor 0.8 leaves a
   margin of 1.25 on both.  An implicit FLUID viscosity (implicit yes) has no limit. */

void PairSaltdemViscous::pair_limit(int i, int j, double m, double mv, bool wall, double &best,
                                    std::string &why)
{
  const double rot = SaltDEM::rotation_factor(domain->dimension);
  const double f2v = force->ftm2v;    // (1 in SI) forces and dashpots act on m / ftm2v
  const double e = eta[i][j];
  const auto &p = params[i][j];
  const double c = elastic_factor(wall);
  const bool spheres = domain->dimension == 3;
  const double cvisc = spheres ? 0.073 : 0.175;
  if (p.kn > 0.0)
    consider_limit(c * sqrt(m / (p.kn * f2v)), best, why, [&] {
      return fmt::format("kn = {:.6g} of types {} {} with the lightest mass {:.6g} "
                         "(dt < {} * sqrt(m/kn){})",
                         p.kn, i, j, m, c, wall ? ", 2 dtfactor against a wall" : "");
    });
  double lim;
  std::string formula;
  if (p.mode == SaltDEM::VISCOUS_FLUID) {
    // V = 1/sum W is not known before the first step: bound it by the
    // disc volume over a packing fraction of 0.7
    // (sub-stepped: the same limit on each of the substeps steps of dt / substeps)
    lim = substeps * viscfactor * cvisc * mv * p.h * p.h / (correction * e * f2v);
    formula = fmt::format("dt{} < {} * {} S rho h^2 / (correction eta), rho the {} "
                          "density, h = {:.6g}, correction = {:.6g}",
                          substeps > 1 ? fmt::format(" / substeps {}", substeps) : "", viscfactor,
                          cvisc, spheres ? "sphere" : "disc", p.h, correction);
    // sound: c^2 = K / rho with the inertial density, CFL 0.25 h / c; a plastic stress
    // is elastic below yield: c^2 = (K + 4G/3) / rho
    const double Gp = (p.mu_y > 0.0 || p.coh_y > 0.0) ? p.G : 0.0;
    if (p.K > 0.0) {
      const double c = sqrt((p.K + 4.0 * Gp / 3.0) * f2v / (0.7 * mv));
      consider_limit(0.25 * p.h / c, best, why, [&] {
        return fmt::format("K = {:.6g}{} of types {} {} (sound speed {:.4g} with the inertial "
                           "density; dt < 0.25 h / c, h = {:.6g}); a larger dt needs a smaller "
                           "K{} or more inertia",
                           p.K, Gp > 0.0 ? fmt::format(" and plastic modulus G = {:.6g}", Gp) : "",
                           i, j, c, p.h, Gp > 0.0 ? " or G" : "");
      });
    }
  } else {
    lim = viscfactor * 0.625 * m / (calibration * e * (1.0 + rot * p.ratio) * f2v);
    formula = fmt::format("dt < {} * 0.625 S m / (calibration * eta * (1 + {} * ratio)), "
                          "calibration = {:.6g}, ratio = {:.6g}, lightest mass {:.6g}",
                          viscfactor, rot, calibration, p.ratio, m);
  }
  if (p.mode == SaltDEM::VISCOUS_FLUID && implicit) return;
  consider_limit(lim, best, why, [&] {
    // (the factor on S only where the step exceeds the limit: the error, not the log)
    return fmt::format(
        "eta = {:.6g} of types {} {} ({}); a larger dt needs a smaller eta, "
        "more inertia for the viscous discs ('fix saltdem/nve ... inertia "
        "S'{}){}",
        e, i, j, formula,
        update->dt > lim ? fmt::format(" with S >= {:.3g} times the present one", update->dt / lim)
                         : "",
        p.mode == SaltDEM::VISCOUS_FLUID ? ", viscous sub-steps (substeps N) or an implicit "
                                           "viscosity (implicit yes)"
                                         : "");
  });
}
