/* ----------------------------------------------------------------------
   SaltDEM: discrete-element salt tectonics for LAMMPS.

   saltdem/timestep F: sets the time step to F times the smallest stable
   limit of the SaltDEM pair styles (alone or in pair hybrid) for the
   present atoms, coefficients and integrators - the limit their run-time
   check enforces - so that a deck states its margin instead of a number
   that is right for one resolution only.
------------------------------------------------------------------------- */

#include "saltdem_timestep.h"

#include "comm.h"
#include "domain.h"
#include "error.h"
#include "force.h"
#include "input.h"
#include "pair_saltdem.h"

#include <cmath>

using namespace LAMMPS_NS;

void SaltdemTimestep::command(int narg, char **arg)
{
  if (narg != 1) error->all(FLERR, "Illegal saltdem/timestep command: usage: saltdem/timestep F");
  if (domain->box_exist == 0)
    error->all(FLERR, "saltdem/timestep command before simulation box is defined");
  const double frac = utils::numeric(FLERR, arg[0], false, lmp);
  if (!(frac > 0.0 && frac <= 1.0))
    error->all(FLERR, "saltdem/timestep: fraction {} of the stable limit must be in (0, 1]", frac);

  // every SaltDEM sub-style of a hybrid (pair_match returns the n-th match, and the only one
  // again past the last), or the pair style itself
  double best = 0.0;
  std::string why, style;
  PairSaltdem *last = nullptr;
  for (int n = 1; n <= 64; n++) {
    auto pair = dynamic_cast<PairSaltdem *>(force->pair_match("saltdem/", 0, n));
    if (!pair || pair == last) break;
    last = pair;
    std::string reason;
    const double lim = pair->stable_limit(reason);
    if (!std::isfinite(lim) || lim < 0.0)
      error->all(FLERR, "saltdem/timestep: pair style {} reports a stable limit of {} ({}): "
                 "check the coefficient it names", pair->name_of(), lim, reason);
    if (lim > 0.0 && (best == 0.0 || lim < best)) {
      best = lim;
      why = reason;
      style = pair->name_of();
    }
  }
  if (!last)
    error->all(FLERR, "saltdem/timestep needs a SaltDEM pair style (saltdem/cohesive, "
               "saltdem/viscous; alone or in pair_style hybrid) with its coefficients set");
  if (best == 0.0)
    error->all(FLERR, "saltdem/timestep: no stable limit applies (no integrated particles "
               "interact through a SaltDEM pair style yet): set the time step with 'timestep'");

  const double dt = frac * best;
  if (comm->me == 0)
    utils::logmesg(lmp, "saltdem/timestep: timestep {:.6g} = {} of the stable limit {:.6g} of "
                   "pair style {} ({})\n", dt, frac, best, style, why);
  input->one(fmt::format("timestep {:.17g}", dt));
}
