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
------------------------------------------------------------------------- */

#include "saltdem_sha256.h"

#include <cstdint>
#include <cstdio>
#include <cstring>

namespace {

const uint32_t K[64] = {
    0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5,
    0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174,
    0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da,
    0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967,
    0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85,
    0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819, 0xd6990624, 0xf40e3585, 0x106aa070,
    0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3,
    0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7, 0xc67178f2};

inline uint32_t rotr(uint32_t x, int n)
{
  return (x >> n) | (x << (32 - n));
}

class Sha256 {
 public:
  void add(const unsigned char *p, size_t n)
  {
    nbytes += n;
    while (n > 0) {
      const size_t take = (n < 64 - fill) ? n : 64 - fill;
      memcpy(block + fill, p, take);
      fill += take;
      p += take;
      n -= take;
      if (fill == 64) {
        compress();
        fill = 0;
      }
    }
  }

  std::string hex()
  {
    const uint64_t bits = nbytes * 8;
    const unsigned char one = 0x80, zero = 0;
    add(&one, 1);
    while (fill != 56) add(&zero, 1);
    unsigned char len[8];
    for (int k = 0; k < 8; k++) len[k] = (unsigned char) (bits >> (56 - 8 * k));
    add(len, 8);
    char out[65];
    for (int k = 0; k < 8; k++) snprintf(out + 8 * k, 9, "%08x", h[k]);
    return std::string(out, 64);
  }

 private:
  uint32_t h[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a,
                   0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  unsigned char block[64];
  size_t fill = 0;
  uint64_t nbytes = 0;

  void compress()
  {
    uint32_t w[64];
    for (int t = 0; t < 16; t++)
      w[t] = (uint32_t) block[4 * t] << 24 | (uint32_t) block[4 * t + 1] << 16 |
          (uint32_t) block[4 * t + 2] << 8 | (uint32_t) block[4 * t + 3];
    for (int t = 16; t < 64; t++) {
      const uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
      const uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
      w[t] = w[t - 16] + s0 + w[t - 7] + s1;
    }
    uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
    for (int t = 0; t < 64; t++) {
      const uint32_t t1 =
          hh + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + K[t] + w[t];
      const uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      hh = g;
      g = f;
      f = e;
      e = d + t1;
      d = c;
      c = b;
      b = a;
      a = t1 + t2;
    }
    h[0] += a;
    h[1] += b;
    h[2] += c;
    h[3] += d;
    h[4] += e;
    h[5] += f;
    h[6] += g;
    h[7] += hh;
  }
};

std::string base_name(const std::string &path)
{
  const size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

}    // namespace

std::string SaltDEM::sha256_bytes(const std::string &bytes)
{
  Sha256 s;
  s.add(reinterpret_cast<const unsigned char *>(bytes.data()), bytes.size());
  return s.hex();
}

std::string SaltDEM::sha256_file(const std::string &path)
{
  FILE *fp = fopen(path.c_str(), "rb");
  if (!fp) return "";
  Sha256 s;
  unsigned char buf[1 << 16];
  size_t n;
  while ((n = fread(buf, 1, sizeof(buf), fp)) > 0) s.add(buf, n);
  const bool bad = ferror(fp);
  fclose(fp);
  return bad ? "" : s.hex();
}

bool SaltDEM::write_checksum(const std::string &file, const std::string &digest)
{
  const std::string path = checksum_path(file), tmp = path + ".tmp";
  FILE *fp = fopen(tmp.c_str(), "w");
  if (!fp) return false;
  const bool wrote = fprintf(fp, "%s  %s\n", digest.c_str(), base_name(file).c_str()) > 0;
  if ((fclose(fp) != 0) || !wrote) {
    remove(tmp.c_str());
    return false;
  }
  return rename(tmp.c_str(), path.c_str()) == 0;
}

std::string SaltDEM::read_checksum(const std::string &file)
{
  FILE *fp = fopen(checksum_path(file).c_str(), "r");
  if (!fp) return "";
  char line[512] = {0};
  const bool got = fgets(line, sizeof(line), fp) != nullptr;
  fclose(fp);
  if (!got || strlen(line) < 66 || line[64] != ' ') return "?";
  for (int k = 0; k < 64; k++)
    if (!strchr("0123456789abcdef", line[k])) return "?";
  return std::string(line, 64);
}
