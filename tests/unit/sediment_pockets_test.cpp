/* Unit test of the pocket search and the radius generator of fix saltdem/sediment
   (src/USER-SALTDEM/saltdem_sediment_pockets.h, saltdem_sediment_random.h) without LAMMPS.
   Compiled and run by tests/test_sediment_pockets.py; prints FAIL lines and exits 1 on a
   failure.
   - the generator is splitmix64 (the published stream of seed 1234567) and its radius laws
     stay in [rmin, rmax], the paper's with its mean 0.4439 (rmin + rmax);
   - the pocket of two touching discs is the closed-form one, and a third disc that would
     overlap the new one by more than the tolerance refuses it;
   - a row of discs takes one disc in every pocket below the base level, in the window (or,
     with a foreset, below the falling level outside it), up to a rate's area or maxper;
   - on a random bed every new disc rests on two discs it touches, between them, below the
     level, overlapping no other beyond the tolerance, and the result does not depend on the
     order the discs were gathered in. */

#include "saltdem_sediment_pockets.h"
#include "saltdem_sediment_random.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "unit_check.h"

using namespace LAMMPS_NS::SaltDEM;

static const double PI = 3.14159265358979323846;

// X along, Y up; the box [-10, 10]^2; new discs of radius rmin to rmax
static SedimentFrame frame(double level, double xlo, double xhi, double foreset = -1.0,
                           double tol = 0.01, double rmin = 1.0, double rmax = 1.0)
{
  return {level,      foreset,        xlo,         xhi, rmin, rmax, tol, {1.0, 0.0},
          {0.0, 1.0}, {-10.0, -10.0}, {10.0, 10.0}};
}

// the surface and the gathered discs, as the fix sets them
static void prepare(SedimentPockets &pk, const std::vector<SedimentDisc> &discs)
{
  for (const auto &d : discs) {
    const int c = pk.column(d.X);
    if (c >= 0) pk.surface[c] = std::max(pk.surface[c], d.Y + d.r);
  }
  pk.survey();
  std::vector<SedimentDisc> near;
  for (const auto &d : discs) {
    const int c = pk.column(d.X);
    if (c >= 0 && pk.near_surface(c, d.Y, d.r)) near.push_back(d);
  }
  pk.set_discs(near);
}

// discs of radius 1 touching in a row on Y = 0, X = -9 to 9
static std::vector<SedimentDisc> row()
{
  std::vector<SedimentDisc> d;
  for (int k = 0; k < 10; k++) d.push_back({-9.0 + 2.0 * k, 0.0, 1.0, k + 1.0});
  return d;
}

static bool near_all(const std::vector<double> &x, const std::vector<double> &want)
{
  if (x.size() != want.size()) return false;
  for (size_t k = 0; k < x.size(); k++)
    if (std::fabs(x[k] - want[k]) > 1e-12) return false;
  return true;
}

static std::vector<double> placed_x(const SedimentPockets &pk)
{
  std::vector<double> x;
  for (size_t k = pk.first_new; k < pk.discs.size(); k++) x.push_back(pk.discs[k].X);
  std::sort(x.begin(), x.end());
  return x;
}

static void generator()
{
  SedimentRandom g;
  g.state = 1234567;
  const uint64_t want[3] = {6457827717110365317ULL, 3203168211198807973ULL, 9817491932198370423ULL};
  for (uint64_t w : want) check(g.next() == w, "splitmix64 stream", 0.0, (double) w);
  SedimentRandom a = g, b = g;
  check(a.uniform() == (double) (b.next() >> 11) / 9007199254740992.0, "uniform: top 53 bits", 0.0,
        0.0);
  double lo = 1e300, hi = 0.0, sum = 0.0;
  const int n = 200000;
  for (int k = 0; k < n; k++) {
    const double r = g.radius(6.25, 15.625, true);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    sum += r;
  }
  check(lo >= 6.25 && hi <= 15.625, "paper radii in [rmin, rmax]", lo, 6.25);
  check(std::fabs(sum / n - 9.71) < 0.03, "paper mean radius", sum / n, 9.71);
  for (int k = 0; k < 1000; k++) {
    const double r = g.radius(2.0, 3.0, false);
    check(r >= 2.0 && r < 3.0, "uniform radii in [rmin, rmax)", r, 2.0);
  }
  check(g.radius(4.0, 4.0, true) == 4.0, "rmin = rmax", g.radius(4.0, 4.0, true), 4.0);
}

static void one_pocket()
{
  // two touching discs of radius 1: the pocket of a third lies at (1, sqrt 3)
  std::vector<SedimentDisc> two = {{0.0, 0.0, 1.0, 1.0}, {2.0, 0.0, 1.0, 2.0}};
  SedimentPockets pk(frame(1.8, -10.0, 10.0), 1.0, -10.0, 10.0);
  check(pk.ncol == 12 && pk.column(0.0) == 6 && pk.column(-13.0) == -1, "columns", pk.ncol, 12);
  prepare(pk, two);
  pk.fill(
      [] {
        return 1.0;
      },
      false, 0.0, 1000);
  check(pk.discs.size() == 3, "one pocket", pk.discs.size(), 3);
  const SedimentDisc &d = pk.discs.back();
  check(std::fabs(d.X - 1.0) < 1e-14, "pocket X", d.X, 1.0);
  check(std::fabs(d.Y - std::sqrt(3.0)) < 1e-14, "pocket Y", d.Y, std::sqrt(3.0));
  check(pk.roomless && pk.area == PI, "no room left after it", pk.area, PI);

  // a disc above the pocket that the new disc would overlap by 0.1 of its
  // radius
  two.push_back({1.0, std::sqrt(3.0) + 1.9, 1.0, 3.0});
  for (double tol : {0.01, 0.2}) {
    SedimentPockets pt(frame(1.8, -10.0, 10.0, -1.0, tol), 1.0, -10.0, 10.0);
    prepare(pt, two);
    double X, Y;
    const int cp = pt.pocket(pt.column(1.0), 1.0, X, Y);
    if (tol < 0.1)
      check(cp < 0, "an overlap beyond the tolerance refuses the pocket", cp, -1);
    else
      check(cp >= 0 && std::fabs(Y - std::sqrt(3.0)) < 1e-14, "one within it does not", Y,
            std::sqrt(3.0));
  }
}

static void a_row()
{
  // every pocket of the row below the level: X = -8, -6, ..., 8
  SedimentPockets pk(frame(1.8, -10.0, 10.0), 1.0, -10.0, 10.0);
  prepare(pk, row());
  pk.fill(
      [] {
        return 1.0;
      },
      false, 0.0, 1000);
  std::vector<double> x = placed_x(pk);
  check(near_all(x, {-8.0, -6.0, -4.0, -2.0, 0.0, 2.0, 4.0, 6.0, 8.0}), "a row of pockets",
        x.size(), 9);
  for (size_t k = pk.first_new; k < pk.discs.size(); k++)
    check(std::fabs(pk.discs[k].Y - std::sqrt(3.0)) < 1e-14, "on the row", pk.discs[k].Y, 1.7);
  check(pk.roomless, "filled", 0.0, 1.0);

  // the window -3 to 3: only discs wholly inside it
  SedimentPockets pw(frame(2.5, -3.0, 3.0), 1.0, -3.0, 3.0);
  prepare(pw, row());
  pw.fill(
      [] {
        return 1.0;
      },
      false, 0.0, 1000);
  x = placed_x(pw);
  check(near_all(x, {-2.0, 0.0, 2.0}), "in the window", x.size(), 3);

  // with a foreset 0.5 the level falls outside the window: 2 at |X| = 4, 1 at
  // |X| = 6
  SedimentPockets pf(frame(2.5, -3.0, 3.0, 0.5), 1.0, -10.0, 10.0);
  prepare(pf, row());
  pf.fill(
      [] {
        return 1.0;
      },
      false, 0.0, 1000);
  x = placed_x(pf);
  check(near_all(x, {-4.0, -2.0, 0.0, 2.0, 4.0}), "below the foreset", x.size(), 5);

  // a rate's area, and maxper
  SedimentPockets pr(frame(1.8, -10.0, 10.0), 1.0, -10.0, 10.0);
  prepare(pr, row());
  pr.fill(
      [] {
        return 1.0;
      },
      true, 2.5 * PI, 1000);
  check(pr.discs.size() - pr.first_new == 3 && !pr.roomless, "rate: up to the area",
        pr.discs.size() - pr.first_new, 3);
  SedimentPockets pm(frame(1.8, -10.0, 10.0), 1.0, -10.0, 10.0);
  prepare(pm, row());
  pm.fill(
      [] {
        return 1.0;
      },
      false, 0.0, 4);
  check(pm.discs.size() - pm.first_new == 4, "maxper", pm.discs.size() - pm.first_new, 4);

  // too many columns: the caller refuses the window
  SedimentPockets huge(frame(1.8, -1e9, 1e9), 1.0, -1e9, 1e9);
  check(huge.span > SedimentPockets::MAX_COLUMNS && huge.ncol == 0, "too many columns", huge.span,
        0.0);
}

static void random_bed()
{
  // a bumpy bed: discs of radius 0.5 to 1 touching in a row on Y = 0, with some
  // raised
  SedimentRandom g;
  g.state = 7;
  std::vector<SedimentDisc> bed;
  double X = -9.0, rprev = 0.0;
  for (int k = 0; X < 9.0; k++) {
    const double r = g.radius(0.5, 1.0, false);
    X += rprev + r;
    bed.push_back({X, r + (k % 5 == 0 ? 0.3 : 0.0), r, 100.0 - k});
    rprev = r;
  }
  const double tol = 0.05, level = 4.0;
  auto run = [&](const std::vector<SedimentDisc> &discs) {
    SedimentPockets pk(frame(level, -10.0, 10.0, -1.0, tol, 0.5, 1.0), 1.0, -10.0, 10.0);
    prepare(pk, discs);
    SedimentRandom draw;
    draw.state = 11;
    pk.fill(
        [&] {
          return draw.radius(0.5, 1.0, true);
        },
        false, 0.0, 100000);
    return pk;
  };
  SedimentPockets pk = run(bed);
  const size_t n = pk.discs.size();
  check(n - pk.first_new > 20, "the bed takes many discs", n - pk.first_new, 20);
  double worst = 0.0;
  for (size_t k = pk.first_new; k < n; k++) {
    const SedimentDisc &d = pk.discs[k];
    check(d.Y <= level && d.X - d.r >= -10.0 && d.X + d.r <= 10.0, "below the level, in the box",
          d.Y, level);
    std::vector<size_t> touch;
    for (size_t q = 0; q < k; q++) {
      const SedimentDisc &e = pk.discs[q];
      const double gap = std::hypot(d.X - e.X, d.Y - e.Y) - (d.r + e.r);
      if (std::fabs(gap) < 1e-9) touch.push_back(q);
    }
    bool between = false;
    for (size_t a : touch)
      for (size_t b : touch)
        if (pk.discs[a].X < d.X && d.X < pk.discs[b].X) between = true;
    check(touch.size() >= 2 && between, "rests on two discs, between them", touch.size(), 2);
    for (size_t q = 0; q < n; q++) {
      if (q == k) continue;
      const SedimentDisc &e = pk.discs[q];
      const double ov = (d.r + e.r - std::hypot(d.X - e.X, d.Y - e.Y)) / std::min(d.r, e.r);
      worst = std::max(worst, ov);
    }
  }
  check(worst <= tol + 1e-12, "overlaps within the tolerance", worst, tol);

  // the gathered discs in another order: the same discs, bit for bit
  std::vector<SedimentDisc> shuffled(bed.rbegin(), bed.rend());
  std::rotate(shuffled.begin(), shuffled.begin() + 5, shuffled.end());
  SedimentPockets again = run(shuffled);
  bool same = again.discs.size() == n;
  for (size_t k = pk.first_new; same && k < n; k++)
    same = again.discs[k].X == pk.discs[k].X && again.discs[k].Y == pk.discs[k].Y &&
        again.discs[k].r == pk.discs[k].r;
  check(same, "independent of the gathering order", again.discs.size(), n);
}

int main()
{
  generator();
  one_pocket();
  a_row();
  random_bed();
  return report();
}
