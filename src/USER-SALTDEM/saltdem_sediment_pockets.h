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

   The pocket search of fix saltdem/sediment: where the new discs of an interval come to rest.
   Coordinates: X along the surface, Y up (against gravity).  The surface is cut into columns
   of width w = 2 rbig (rbig: the largest disc, old or new); a column's surface is its highest
   disc top.  A new disc goes to the lowest open column: the lowest pocket around it where the
   disc touches two discs, lies between them (stable under gravity), has its centre below the
   base level, lies in the window and the box, and overlaps no other disc by more than tol of
   the smaller radius.  A column without such a pocket takes only smaller discs until a disc
   is put near it.  When no column takes the drawn radius, a few more radii are drawn; then the
   interval ends (no room).  A pocket must lie above the lowest surface of its columns minus
   'depth', so it cannot reach a disc below the layer the caller gathered (near_surface()).
   The discs are sorted by ID, so the result depends on the discs and the draws alone: every
   rank places the same discs.  Nothing here depends on LAMMPS classes (unit test:
   tests/unit/sediment_pockets_test.cpp).
------------------------------------------------------------------------- */

#ifndef LMP_SALTDEM_SEDIMENT_POCKETS_H
#define LMP_SALTDEM_SEDIMENT_POCKETS_H

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace LAMMPS_NS {
namespace SaltDEM {

  struct SedimentDisc {
    double X, Y, r, tag;    // along, up, radius, atom ID (0 for a new disc)
  };

  // what the pockets of one interval must respect
  struct SedimentFrame {
    double level;                 // base level (Y) in the window
    double foreset;               // < 0: nothing outside the window; else the level's fall per
                                  // unit length outside it
    double xlo, xhi;              // the window (X)
    double rmin, rmax;            // radius law of the new discs
    double tol;                   // accepted overlap, fraction of the smaller radius
    double along[2], up[2];       // the X and Y axes in box coordinates
    double boxlo[2], boxhi[2];    // the box (x, y)
  };

  class SedimentPockets {
   public:
    static constexpr double MAX_COLUMNS = 1.0e7;
    static constexpr int MAX_REDRAWS = 50;    // radii drawn in a row that find no room

    // rbig: the largest disc; the columns span [glo, ghi] and one more on each side
    SedimentPockets(const SedimentFrame &f, double rbig, double glo, double ghi) :
        frame(f), w(2.0 * rbig), depth(4.0 * rbig), X0(glo - w),
        span(std::ceil((ghi - glo) / w) + 2.0), ncol(span > MAX_COLUMNS ? 0 : (int) span),
        surface(ncol, -DBL_MAX), first_new(0), area(0.0), roomless(false)
    {
    }

    const SedimentFrame frame;
    const double w, depth, X0;    // column width, depth of the surface layer, left end
    const double span;            // columns wanted (the caller refuses more than MAX_COLUMNS)
    const int ncol;
    // per column the highest disc top over all ranks (-DBL_MAX: empty); the caller sets it,
    // then calls survey()
    std::vector<double> surface;
    std::vector<SedimentDisc> discs;    // the gathered discs by ID, then the new ones
    size_t first_new;
    double area;      // of the new discs
    bool roomless;    // the interval ended for want of room

    int column(double X) const    // -1: outside the columns
    {
      const double c = std::floor((X - X0) / w);
      return (c < 0.0 || c >= ncol) ? -1 : (int) c;
    }

    // after the surface is set: the lowest surfaces around each column
    void survey()
    {
      gmin.resize(ncol);
      amin.resize(ncol);
      for (int c = 0; c < ncol; c++) {
        gmin[c] = lowest(surface, c, 2);
        amin[c] = lowest(surface, c, 1);
      }
      scur = surface;
      failmin.assign(ncol, DBL_MAX);
    }

    // a disc of column c a new disc could touch: near the surface, not far above the base level
    bool near_surface(int c, double Y, double r) const
    {
      return !(Y + r < gmin[c] - depth) && !(Y - r > frame.level + frame.rmax);
    }

    void set_discs(std::vector<SedimentDisc> gathered)
    {
      discs = std::move(gathered);
      std::sort(discs.begin(), discs.end(), [](const SedimentDisc &a, const SedimentDisc &b) {
        return a.tag < b.tag;
      });
      cols.assign(ncol, {});
      for (size_t k = 0; k < discs.size(); k++) cols[column(discs[k].X)].push_back((int) k);
      first_new = discs.size();
    }

    // place discs of radius draw() until the area reaches target (rate) or none finds room, at
    // most maxper
    template <class Draw> void fill(Draw &&draw, bool rate, double target, int64_t maxper)
    {
      int redraws = 0;
      double r = 0.0;
      bool have_r = false;
      while (true) {
        if (rate && area >= target) break;
        if ((int64_t) (discs.size() - first_new) >= maxper) break;
        if (!have_r) {
          r = draw();
          have_r = true;
        }
        int c = -1;
        for (int q = 0; q < ncol; q++)
          if (r < failmin[q] && (c < 0 || scur[q] < scur[c])) c = q;
        if (c < 0) {
          // no room for a disc of this radius: a smaller one may still fit (a few more draws)
          bool smaller = false;
          for (int q = 0; q < ncol && !smaller; q++)
            if (failmin[q] > frame.rmin) smaller = true;
          if (!smaller || ++redraws > MAX_REDRAWS) {
            roomless = true;
            break;
          }
          have_r = false;
          continue;
        }
        double X, Y;
        const int cp = pocket(c, r, X, Y);
        if (cp < 0) {
          failmin[c] = r;
          continue;
        }
        discs.push_back({X, Y, r, 0.0});
        cols[cp].push_back((int) discs.size() - 1);
        scur[cp] = dmax(scur[cp], Y + r);
        // the new disc makes new pockets around it
        for (int q = std::max(0, cp - 2); q <= std::min(ncol - 1, cp + 2); q++)
          failmin[q] = DBL_MAX;
        area += PI * r * r;
        have_r = false;
        redraws = 0;
      }
    }

    // the lowest pocket of a disc of radius r around column c (the leftmost of equal ones):
    // its column, or -1 if there is none
    int pocket(int c, double r, double &bestX, double &bestY)
    {
      const SedimentFrame &f = frame;
      // the pocket formers: discs around column c near its surface
      formers.clear();
      const double mprune = lowest(scur, c, 1);
      if (mprune < DBL_MAX)
        for (int q = std::max(0, c - 1); q <= std::min(ncol - 1, c + 1); q++)
          for (int k : cols[q]) {
            const SedimentDisc &d = discs[k];
            if (d.Y + d.r < mprune - depth) continue;
            if (d.Y - d.r > f.level + r) continue;
            formers.push_back(k);
          }

      bestX = 0.0;
      bestY = DBL_MAX;
      int bestc = -1;
      const size_t nf = formers.size();
      for (size_t a = 0; a < nf; a++)
        for (size_t b = a + 1; b < nf; b++) {
          const int i = std::min(formers[a], formers[b]), j = std::max(formers[a], formers[b]);
          const SedimentDisc &di = discs[i], &dj = discs[j];
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
          if (PY > f.level) continue;
          if (PY > bestY || (PY == bestY && PX >= bestX)) continue;
          if (PX <= dmin(di.X, dj.X) || PX >= dmax(di.X, dj.X)) continue;    // would roll off
          if (f.foreset < 0.0) {
            if (PX - r < f.xlo || PX + r > f.xhi) continue;
          } else if (PY > level_at(PX))
            continue;
          const double px = f.along[0] * PX + f.up[0] * PY, py = f.along[1] * PX + f.up[1] * PY;
          if (px - r < f.boxlo[0] || px + r > f.boxhi[0] || py - r < f.boxlo[1] ||
              py + r > f.boxhi[1])
            continue;
          const int cp = column(PX);
          if (cp < 1 || cp > ncol - 2) continue;
          if (amin[cp] < DBL_MAX && PY - r < amin[cp] - depth) continue;
          if (overlaps(cp, i, j, PX, PY, r)) continue;
          bestX = PX;
          bestY = PY;
          bestc = cp;
        }
      return bestc;
    }

   private:
    static constexpr double PI = 3.14159265358979323846;
    std::vector<double> gmin, amin;    // the lowest surface within 2 and 1 columns
    std::vector<double> scur;          // the surface with the new discs
    // failmin[c]: the smallest radius that found no pocket around column c since a disc was
    // last put near it (only smaller discs are tried there until then)
    std::vector<double> failmin;
    std::vector<std::vector<int>> cols;    // the discs of each column
    std::vector<int> formers;

    // (as LAMMPS's MIN and MAX)
    static double dmin(double a, double b) { return a < b ? a : b; }
    static double dmax(double a, double b) { return a > b ? a : b; }

    // the lowest surface of columns c - k to c + k, DBL_MAX if all are empty
    double lowest(const std::vector<double> &surf, int c, int k) const
    {
      double m = DBL_MAX;
      for (int q = std::max(0, c - k); q <= std::min(ncol - 1, c + k); q++)
        if (surf[q] > -DBL_MAX) m = dmin(m, surf[q]);
      return m;
    }

    // the base level at X: flat in the window, falling by 'foreset' per unit length outside it
    double level_at(double X) const
    {
      return frame.level - frame.foreset * dmax(0.0, dmax(frame.xlo - X, X - frame.xhi));
    }

    // does a disc of radius r at (X, Y) in column cp overlap a disc other than i and j by more
    // than the tolerance?
    bool overlaps(int cp, int i, int j, double X, double Y, double r) const
    {
      for (int q = cp - 1; q <= cp + 1; q++)
        for (int k : cols[q]) {
          if (k == i || k == j) continue;
          const SedimentDisc &dk = discs[k];
          const double lim = r + dk.r;
          const double ey = dk.Y - Y;
          if (fabs(ey) >= lim) continue;
          const double ex = dk.X - X;
          const double e2 = ex * ex + ey * ey;
          if (e2 >= lim * lim) continue;
          if (lim - sqrt(e2) > frame.tol * dmin(r, dk.r)) return true;
        }
      return false;
    }
  };

}    // namespace SaltDEM
}    // namespace LAMMPS_NS

#endif
