/* Unit test of the frictional-viscous fluid's plastic stress (src/USER-SALTDEM/saltdem_plastic.h
   and its pass in SaltDEM::SphFields) without LAMMPS.  Compiled and run by
   tests/test_plastic.py; prints FAIL lines and exits 1 on a failure.
   - the corrected SPH velocity gradient of a linear velocity field on a lattice is exact, and
     the rate of the plastic stress is 2 G dev(D);
   - the strength is C + MU P of the pressure of the particle's density;
   - the stress term of the pressure matrices gives the particle the virial tau V;
   - simple shear of the elastic-plastic stress (Jaumann rate, radial return) against its
     closed form: tau_xy = G sin(gamma), tau_xx = G (1 - cos gamma) below yield, and at steady
     yield tau_xx = Y^2 / G, tau_xy = Y sqrt(1 - (Y / G)^2). */

#include "saltdem_contact_viscous.h"
#include "saltdem_plastic.h"
#include "saltdem_sph_fields.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "unit_check.h"

using namespace LAMMPS_NS::SaltDEM;

static bool close(double a, double b, double tol)
{
  return std::fabs(a - b) <= tol;
}

static void simple_shear()
{
  // 2D simple shear v_x = rate y: grad v = [[0, rate], [0, 0]]
  const double G = 1e9, rate = 1e-4, dt = 0.01;
  const double gv[4] = {0.0, rate, 0.0, 0.0};
  double tau[3] = {0.0, 0.0, 0.0}, dtau[3];
  // below yield (Y infinite): the hypoelastic closed form, to the Euler step's error
  const int n = 20000;    // gamma 0.02
  for (int s = 0; s < n; s++) {
    plastic_stress_rate<2>(G, gv, tau, dtau);
    for (int k = 0; k < 3; k++) tau[k] += dt * dtau[k];
    plastic_return<2>(1e300, tau);
  }
  const double g = rate * dt * n;
  check(close(tau[2], G * std::sin(g), 1e-6 * G * g), "elastic tau_xy = G sin(gamma)", tau[2],
        G * std::sin(g));
  check(close(tau[0], G * (1.0 - std::cos(g)), 1e-3 * G * g * g), "elastic tau_xx", tau[0],
        G * (1.0 - std::cos(g)));
  check(close(tau[1], -tau[0], 1e-12 * G), "a deviator", tau[1], -tau[0]);
  // at yield, steady: Y 1e7 (yield strain 1 %), 50 yield strains of shear
  const double Y = 1e7;
  for (int k = 0; k < 3; k++) tau[k] = 0.0;
  double first_yield = -1.0;
  for (int s = 0; s < 500000; s++) {
    plastic_stress_rate<2>(G, gv, tau, dtau);
    for (int k = 0; k < 3; k++) tau[k] += dt * dtau[k];
    plastic_return<2>(Y, tau);
    if (first_yield < 0.0 && plastic_norm<2>(tau) >= Y * (1.0 - 1e-12)) first_yield = rate * dt * (s + 1);
  }
  check(close(first_yield, Y / G, 0.02 * Y / G), "yield at the strain Y / G", first_yield, Y / G);
  check(close(plastic_norm<2>(tau), Y, 1e-9 * Y), "at yield sqrt(J2) = Y", plastic_norm<2>(tau), Y);
  const double txy = Y * std::sqrt(1.0 - (Y / G) * (Y / G)), txx = Y * Y / G;
  check(close(tau[2], txy, 1e-4 * Y), "steady tau_xy = Y sqrt(1 - (Y/G)^2)", tau[2], txy);
  check(close(tau[0], txx, 0.02 * txx), "steady tau_xx = Y^2 / G", tau[0], txx);
  // the strength
  check(plastic_yield(0.1, 2e5, 1e7) == 2e5 + 1e6, "C + MU P", plastic_yield(0.1, 2e5, 1e7),
        1.2e6);
  check(plastic_yield(0.1, 2e5, -1e7) == 2e5, "no strength from a tension",
        plastic_yield(0.1, 2e5, -1e7), 2e5);
  // 3D: a shear in xz gives the same stress as the 2D xy one
  const double gv3[9] = {0.0, 0.0, rate, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  double t3[6] = {0, 0, 0, 0, 0, 0}, d3[6];
  plastic_stress_rate<3>(G, gv3, t3, d3);
  check(close(d3[4], G * rate, 1e-12 * G * rate), "3D: d tau_xz / dt = G rate", d3[4], G * rate);
  check(d3[0] == 0.0 && d3[3] == 0.0 && d3[5] == 0.0, "3D: nothing else from zero stress", d3[0], 0);
}

static void lattice()
{
  const int n = 21;    // n x n discs, spacing a
  const double a = 10.0, h = 2.0 * a, m = 220.0, K = 1e8, Gm = 5e7;
  const int N = n * n;
  // a linear velocity field with stretch, shear and spin
  const double L[4] = {2e-4, 3e-4, -1e-4, -0.5e-4};
  std::vector<double> x(3 * N, 0.0), v(3 * N, 0.0), rmass(N, m), radius(N, 0.5 * a);
  std::vector<int> type(N, 1);
  for (int i = 0; i < N; i++) {
    x[3 * i] = a * (i % n);
    x[3 * i + 1] = a * (i / n);
    v[3 * i] = L[0] * x[3 * i] + L[1] * x[3 * i + 1];
    v[3 * i + 1] = L[2] * x[3 * i] + L[3] * x[3 * i + 1];
  }
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
  p.mu_y = 0.2;
  p.coh_y = 1e4;
  p.G = Gm;
  ViscousParams row[2] = {p, p};
  const ViscousParams *params[2] = {row, row};
  const int fluidself[2] = {0, 1}, isfluid[2] = {0, 1}, influid[2] = {0, 1}, isplastic[2] = {0, 1};
  std::vector<double> tau(NSYM * N, 0.0), dtau(NSYM * N, -1.0), ystress(N, -1.0);

  SphFields F;
  F.params = params;
  F.fluidself = fluidself;
  F.isfluid = isfluid;
  F.isplastic = isplastic;
  F.plastic = true;
  F.tau = tau.data();
  F.dtau = dtau.data();
  F.ystress = ystress.data();
  F.ntypes = 1;
  F.grow(N);
  const SphInput in = {(const double(*)[3]) x.data(), (const double(*)[3]) v.data(),
                       rmass.data(), radius.data(), type.data(), N, N, false, N, ilist.data(),
                       numneigh.data(), firstneigh.data(), ~0};
  check(F.material_density(in, 2, influid) == -1, "material_density", 0, 0);
  std::vector<double> rho(N), interior(N);
  F.kernel_density(2, in, [] {}, rho.data(), interior.data());
  const int c = (n / 2) * n + n / 2;
  const double rho0[2] = {0.0, rho[c]};
  std::vector<double> dens(N, 1.02 * rho[c]);
  // a stress on the centre particle, to see its term in the pressure matrix
  const double tc[3] = {3e4, -3e4, 5e4};
  for (int k = 0; k < 3; k++) tau[NSYM * c + k] = tc[k];
  std::vector<double> A0(3);
  F.pressure_matrices(2, in, dens.data(), rho0, [] {});
  // rate 2 G dev(D) + W tau - tau W with the lattice's exact gradient
  double want[3];
  const double gv[4] = {L[0], L[1], L[2], L[3]};
  plastic_stress_rate<2>(Gm, gv, &tau[NSYM * c], want);
  for (int k = 0; k < 3; k++)
    check(close(dtau[NSYM * c + k], want[k], 1e-9 * Gm * 3e-4), "rate from the exact gradient",
          dtau[NSYM * c + k], want[k]);
  const double P = eos_pressure(K, dens[c], rho0[1]);
  check(close(ystress[c], 1e4 + 0.2 * P, 1e-9 * P), "strength C + MU P", ystress[c],
        1e4 + 0.2 * P);
  // the pressure matrix now holds a (S/rho)^-1 - (m / rho^2) sym(tau (S/rho)^-1): on a square
  // lattice S is isotropic, so A - A(no stress) = -(m / rho^2) tau (S/rho)^-1 exactly
  const double r = dens[c];
  const double *S = &F.moment[SphLayout<2>::NMOM * c];
  double Ap[3] = {S[0], S[1], S[2]};
  pressure_matrix<2>(pressure_term(m, K, r, rho0[1]), r, Ap);
  const double *A = &F.pmat[SphLayout<2>::NS * c];
  const double sx = S[0] / r;
  for (int k = 0; k < 3; k++) {
    const double got = A[k] - Ap[k], w = -m / (r * r) * tc[k] / sx;
    check(close(got, w, 1e-9 * std::fabs(m / (r * r) * 5e4)), "stress term of A", got, w);
  }
  // a particle without plastic strength has no rate and no strength
  check(ystress[0] >= 0.0, "a corner has a strength", ystress[0], 0.0);
}

int main()
{
  simple_shear();
  lattice();
  return report();
}
