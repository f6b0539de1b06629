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

   fix saltdem/tiltwall: a model tilted by an angle A and extended by its
   end wall.  The run is set in the tilted frame: the base is the x axis and
   the end walls are normal to it, so gravity is rotated, g (sin A, -cos A)
   for a model that dips toward +x.  The group (the end wall's discs) moves
   outward along the base, +x (or -x with 'toward left'), at a given rate up
   to a target.  With 'gravity GROUP' the fix applies the rotated gravity to
   that group through an internal fix gravity, so the tilt is set in one place.
------------------------------------------------------------------------- */

#include "fix_saltdem_tiltwall.h"

#include "saltdem_check.h"

#include "error.h"
#include "group.h"
#include "modify.h"
#include "update.h"

#include <cmath>
#include <cstring>

static constexpr double DEFAULT_G = 9.81;    // m/s^2 (units si only)

using namespace LAMMPS_NS;

FixSaltdemTiltwall::FixSaltdemTiltwall(LAMMPS *lmp, int narg, char **arg) :
    FixSaltdemMotion(lmp, narg, arg), tilt(0.0), g(0.0), g_given(0), igravity(-1)
{
  has_toward = 1;
  usage = fmt::format("fix ID group {} tilt A rate V target T [toward right|left] "
                      "[gravity GROUP] [g G] [at_target stop|end]",
                      style);
  parse(narg, arg);
  if (tilt == 0.0) error->all(FLERR, "Fix {}: tilt is required; usage: {}", style, usage);
  // the default g is the Earth's in m/s^2: SI only
  if (!g_given) {
    if (strcmp(update->unit_style, "si") != 0)
      error->all(FLERR,
                 "Fix {}: the default g = {} is in m/s^2 (units si); under units {} give "
                 "'g G' in the deck's units (length/time^2)",
                 style, DEFAULT_G, update->unit_style);
    g = DEFAULT_G;
  }
  if (g <= 0.0) error->all(FLERR, "Fix {}: g = {} must be > 0", style, g);
  if (igravity == igroup)
    error->all(FLERR,
               "Fix {}: the gravity group must be the discs that move freely, not the "
               "wall group {}",
               style, group->names[igroup]);
  blocks.push_back(translation(-1, double(sense), 0.0));
  size_vector = 3;
}

FixSaltdemTiltwall::~FixSaltdemTiltwall()
{
  if (!gravity_id.empty() && modify->nfix && modify->get_fix_by_id(gravity_id))
    modify->delete_fix(gravity_id);
}

int FixSaltdemTiltwall::parse_keyword(const std::string &kw, const std::string &val)
{
  if (kw == "tilt")
    tilt = angle_arg(kw, val);
  else if (kw == "gravity")
    igravity = group_arg(kw, val);
  else if (kw == "g") {
    g = SaltDEM::numeric(FLERR, val.c_str(), fmt::format("Fix {}: g", style), lmp);
    g_given = 1;
  } else
    return 0;
  return 1;
}

void FixSaltdemTiltwall::post_constructor()
{
  if (igravity < 0) return;
  gravity_id = std::string(id) + "_GRAVITY";
  const double a = tilt * M_PI / 180.0;
  modify->add_fix(fmt::format("{} {} gravity {:.17g} vector {:.17g} {:.17g} 0", gravity_id,
                              group->names[igravity], g, sense * sin(a), -cos(a)));
}

/* 1 wall displacement, 2-3 the gravity vector of the tilted frame (m/s^2) */

double FixSaltdemTiltwall::compute_vector(int n)
{
  const double a = tilt * M_PI / 180.0;
  if (n == 0) return disp;
  if (n == 1) return sense * g * sin(a);
  return -g * cos(a);
}
