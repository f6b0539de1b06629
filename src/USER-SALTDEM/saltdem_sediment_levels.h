/* -*- c++ -*- ----------------------------------------------------------
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

   Where fix saltdem/sediment deposits and erodes: the frame of gravity (levels are heights
   along 'up', through the origin), the base and erosion levels and the deposition window
   along 'along'.  A level or a window end is a constant or a variable evaluated at each
   interval; a level must cut the box.
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_LEVELS_H
#define LMP_SALTDEM_SEDIMENT_LEVELS_H

#include "pointers.h"

namespace LAMMPS_NS {

class SaltdemSedimentLevels : protected Pointers {
 public:
  SaltdemSedimentLevels(class LAMMPS *, class Fix *);

  // a level: a constant, an equal-style variable, or (erosion only) an atom-style variable
  struct Level {
    enum { NONE, CONSTANT, EQUAL, ATOM };
    int kind = NONE;
    double value = 0.0;
    std::string name;    // variable name (without v_)
    int ivar = -1;
  };

  Level base, erode;
  Level wlo, whi;    // the window's ends: constants or equal-style variables (a front)
  int window_given;
  double xlo, xhi;           // the window at the last interval (default: the box)
  double foreset;            // outside the window the base level falls by this per unit length
                             // (< 0: no deposit outside the window)
  double up[2], along[2];    // frame of gravity: up = -g / |g|, along = (up_y, -up_x)

  void parse(Level &, const char *text, const char *kw);
  void parse_window(const char *lo, const char *hi);
  void set_down(double dx, double dy);
  void init();
  double value(Level &, const char *kw);    // now, inside the box
  void update_window();
  void check_in_box(double level, const char *kw);
  // extends [lo, hi] to the box's extent along axis
  void box_range(const double *axis, double &lo, double &hi) const;

 private:
  class Fix *fix;
  void parse_window_end(Level &, const char *text);
};

}    // namespace LAMMPS_NS

#endif
