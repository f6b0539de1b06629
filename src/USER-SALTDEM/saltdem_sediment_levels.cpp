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

   The levels and the window of fix saltdem/sediment (SaltdemSedimentLevels, see the header).
------------------------------------------------------------------------- */

#include "saltdem_sediment_levels.h"

#include "saltdem_check.h"

#include "domain.h"
#include "error.h"
#include "fix.h"
#include "input.h"
#include "update.h"
#include "variable.h"

#include <cfloat>
#include <cmath>
#include <cstring>

using namespace LAMMPS_NS;

SaltdemSedimentLevels::SaltdemSedimentLevels(LAMMPS *lmp, Fix *owner) :
    Pointers(lmp), window_given(0), xlo(0.0), xhi(0.0), foreset(-1.0), fix(owner)
{
  up[0] = 0.0;
  up[1] = 1.0;
  along[0] = up[1];
  along[1] = -up[0];
}

/* LEVEL is a number (m) or v_NAME */

void SaltdemSedimentLevels::parse(Level &l, const char *text, const char *kw)
{
  const char *style = fix->style;
  if (strncmp(text, "v_", 2) == 0) {
    l.name = text + 2;
    l.kind = Level::EQUAL;
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

void SaltdemSedimentLevels::parse_window(const char *lo, const char *hi)
{
  parse_window_end(wlo, lo);
  parse_window_end(whi, hi);
  xlo = wlo.value;
  xhi = whi.value;
  if (wlo.kind == Level::CONSTANT && whi.kind == Level::CONSTANT && xlo >= xhi)
    error->all(FLERR, "Fix {}: x {} {}: the window's low end must be below its high end",
               fix->style, xlo, xhi);
  window_given = 1;
}

/* an end of the window 'x': a number (m) or v_NAME, an equal-style variable (a front that moves) */

void SaltdemSedimentLevels::parse_window_end(Level &l, const char *text)
{
  const char *style = fix->style;
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

/* gravity along (dx, dy) */

void SaltdemSedimentLevels::set_down(double dx, double dy)
{
  const double n = sqrt(dx * dx + dy * dy);
  if (!(n > 0.0) || !std::isfinite(n))
    error->all(FLERR, "Fix {}: down {} {} must be a non-zero direction (of gravity)", fix->style,
               dx, dy);
  up[0] = -dx / n;
  up[1] = -dy / n;
  along[0] = up[1];
  along[1] = -up[0];
}

/* the variables by index (they may have been redefined since the fix was), the default window */

void SaltdemSedimentLevels::init()
{
  const char *style = fix->style;
  for (auto lk : {std::make_pair(&base, "base"), std::make_pair(&erode, "erode")}) {
    Level &l = *lk.first;
    const char *kw = lk.second;
    if (l.kind != Level::EQUAL && l.kind != Level::ATOM) continue;
    l.ivar = input->variable->find(l.name.c_str());
    if (l.ivar < 0)
      error->all(FLERR, "Fix {}: {} level variable {} does not exist", style, kw, l.name);
    if (l.kind == Level::EQUAL && !input->variable->equalstyle(l.ivar))
      error->all(FLERR, "Fix {}: {} level variable {} is no longer equal-style", style, kw, l.name);
    if (l.kind == Level::ATOM && !input->variable->atomstyle(l.ivar))
      error->all(FLERR, "Fix {}: {} level variable {} is no longer atom-style", style, kw, l.name);
  }
  for (Level *l : {&wlo, &whi}) {
    if (l->kind != Level::EQUAL) continue;
    l->ivar = input->variable->find(l->name.c_str());
    if (l->ivar < 0)
      error->all(FLERR, "Fix {}: x window variable {} does not exist", style, l->name);
    if (!input->variable->equalstyle(l->ivar))
      error->all(FLERR, "Fix {}: x window variable {} is no longer equal-style", style, l->name);
  }
  if (!window_given) {
    xlo = DBL_MAX;
    xhi = -DBL_MAX;
    box_range(along, xlo, xhi);
  }
}

double SaltdemSedimentLevels::value(Level &l, const char *kw)
{
  double v = l.value;
  if (l.kind == Level::EQUAL) {
    v = input->variable->compute_equal(l.ivar);
    check_in_box(v, kw);
  }
  return v;
}

/* the window at an interval: its variable ends evaluated now */

void SaltdemSedimentLevels::update_window()
{
  if (!window_given) return;
  for (Level *l : {&wlo, &whi}) {
    if (l->kind != Level::EQUAL) continue;
    const double v = input->variable->compute_equal(l->ivar);
    if (!std::isfinite(v))
      error->all(FLERR, "Fix {} {}: x window variable {} is not finite ({})", fix->style, fix->id,
                 l->name, v);
    (l == &wlo ? xlo : xhi) = v;
  }
  if (xlo >= xhi)
    error->all(FLERR,
               "Fix {} {}: the window x {} {} at step {} ({} to {} m): its low end must be below "
               "its high end",
               fix->style, fix->id,
               wlo.kind == Level::EQUAL ? "v_" + wlo.name : fmt::format("{}", wlo.value),
               whi.kind == Level::EQUAL ? "v_" + whi.name : fmt::format("{}", whi.value),
               update->ntimestep, xlo, xhi);
}

/* a level is a height along 'up' through the origin: it must cut the box */

void SaltdemSedimentLevels::check_in_box(double level, const char *kw)
{
  double lo = DBL_MAX, hi = -DBL_MAX;
  box_range(up, lo, hi);
  if (!std::isfinite(level) || level < lo || level > hi)
    error->all(FLERR, "Fix {}: {} level = {} m is outside the box ({} to {} m{})", fix->style, kw,
               level, lo, hi, (up[0] == 0.0 && up[1] == 1.0) ? " in y" : " along the up direction");
}

void SaltdemSedimentLevels::box_range(const double *axis, double &lo, double &hi) const
{
  for (int a = 0; a < 2; a++)
    for (int b = 0; b < 2; b++) {
      const double s = axis[0] * (a ? domain->boxhi[0] : domain->boxlo[0]) +
          axis[1] * (b ? domain->boxhi[1] : domain->boxlo[1]);
      lo = MIN(lo, s);
      hi = MAX(hi, s);
    }
}
