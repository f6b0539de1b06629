/* Unit test of SaltDEM::SphFields (src/USER-SALTDEM/saltdem_sph_fields.{h,cpp}) without
   LAMMPS: a square lattice of equal discs, one fluid type, a brute-force half neighbour list.
   Compiled and run by tests/test_sph_fields.py; prints FAIL lines and exits 1 on a failure. */

#include "saltdem_contact_viscous.h"
#include "saltdem_sph_fields.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "unit_check.h"

using namespace LAMMPS_NS::SaltDEM;

static bool close(double a, double b, double rel)
{
  return std::fabs(a - b) <= rel * std::fabs(b);
}

int main()
{
  const int n = 21;    // n x n discs, spacing a
  const double a = 10.0, h = 2.0 * a, m = 220.0, K = 1e8;
  const int N = n * n;
  std::vector<double> x(3 * N, 0.0), v(3 * N, 0.0), rmass(N, m), radius(N, 0.5 * a);
  std::vector<int> type(N, 1);
  for (int i = 0; i < N; i++) {
    x[3 * i] = a * (i % n);
    x[3 * i + 1] = a * (i / n);
  }
  // a half list: each pair within 2h once
  std::vector<std::vector<int>> neigh(N);
  for (int i = 0; i < N; i++)
    for (int j = i + 1; j < N; j++) {
      const double dx = x[3 * i] - x[3 * j], dy = x[3 * i + 1] - x[3 * j + 1];
      if (dx * dx + dy * dy < 4.0 * h * h) neigh[i].push_back(j);
    }
  std::vector<int> ilist(N), numneigh(N);
  std::vector<int *> firstneigh(N);
  for (int i = 0; i < N; i++) {
    ilist[i] = i;
    numneigh[i] = (int) neigh[i].size();
    firstneigh[i] = neigh[i].data();
  }

  ViscousParams p{};
  p.mode = VISCOUS_FLUID;
  p.h = h;
  p.K = K;
  p.cw = wendland_c2_grad_over_r(2, h);
  p.ih2 = 0.5 / h;
  p.cW = wendland_c2(2, h, 0.0);
  ViscousParams row[2] = {p, p};
  const ViscousParams *params[2] = {row, row};
  const int fluidself[2] = {0, 1}, isfluid[2] = {0, 1}, influid[2] = {0, 1};

  SphFields F;
  F.params = params;
  F.fluidself = fluidself;
  F.isfluid = isfluid;
  F.ntypes = 1;
  F.grow(N);
  const SphInput in = {(const double(*)[3]) x.data(), (const double(*)[3]) v.data(),
                       rmass.data(), radius.data(), type.data(), N, N, false, N, ilist.data(),
                       numneigh.data(), firstneigh.data(), ~0};
  check(F.material_density(in, 2, influid) == -1, "material_density: every disc has a size", 0, 0);

  // kernel density: the brute-force sum over the lattice (i included), and at the centre the
  // continuum value m / a^2 (the lattice sum of a smooth kernel with h = 2 a: within 0.2 %)
  std::vector<double> rho(N), interior(N);
  int reversed = 0;
  F.kernel_density(2, in, [&] { reversed++; }, rho.data(), interior.data());
  check(reversed == 0, "no reverse communication with newton off", reversed, 0);
  const int c = (n / 2) * n + n / 2;
  double sum = 0.0;
  for (int j = 0; j < N; j++) {
    const double dx = x[3 * c] - x[3 * j], dy = x[3 * c + 1] - x[3 * j + 1];
    sum += m * wendland_c2(2, h, std::sqrt(dx * dx + dy * dy));
  }
  check(close(rho[c], sum, 1e-13), "kernel density = lattice sum", rho[c], sum);
  check(close(rho[c], m / (a * a), 2e-3), "kernel density = m / a^2", rho[c], m / (a * a));
  check(interior[c] == 1.0, "the centre's kernel is full", interior[c], 1.0);
  check(interior[0] == 0.0, "a corner's kernel is not", interior[0], 0.0);
  check(rho[0] < 0.6 * rho[c], "a corner has less than the centre", rho[0], rho[c]);

  // pressure matrices at a density 1 % above the reference: the volume m / rho, no fill, and
  // the corrected matrix A = a (S / rho)^-1 of Bonet & Lok, i.e. S A = a rho I with
  // a = m P / rho^2 and S the kernel moment
  const double rho0[2] = {0.0, rho[c]};
  std::vector<double> dens(N, 1.01 * rho[c]);
  F.pressure_matrices(2, in, dens.data(), rho0, [&] { reversed++; });
  const double r = dens[c];
  check(close(F.vol[c], m / r, 1e-15), "volume m / rho", F.vol[c], m / r);
  check(F.fill[c] == 1.0, "fill off", F.fill[c], 1.0);
  const double at = pressure_term(m, K, r, rho0[1]);
  const double *S = &F.moment[SphLayout<2>::NMOM * c], *A = &F.pmat[SphLayout<2>::NS * c];
  check(close(S[0] * A[0] + S[2] * A[2], at * r, 1e-12), "(S A)_xx = a rho", S[0] * A[0] + S[2] * A[2],
        at * r);
  check(close(S[2] * A[2] + S[1] * A[1], at * r, 1e-12), "(S A)_yy = a rho", S[2] * A[2] + S[1] * A[1],
        at * r);
  check(std::fabs(S[0] * A[2] + S[2] * A[1]) <= 1e-12 * at * r, "(S A)_xy = 0",
        S[0] * A[2] + S[2] * A[1], 0.0);
  check(std::fabs(S[2]) <= 1e-12 * S[0], "a square lattice has no xy moment", S[2], 0.0);

  // pair weights of two fluid discs of one size: their masses and volumes
  const Weights w = F.pair_weights<2>(radius.data(), c, c + 1, 1, 1);
  check(close(w.mi, m, 1e-15) && close(w.mj, m, 1e-15), "pair masses", w.mi, m);
  check(w.vi == F.vol[c] && w.vj == F.vol[c + 1], "pair volumes", w.vi, F.vol[c]);

  return report();
}
