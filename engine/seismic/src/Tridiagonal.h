// Symmetric tridiagonal eigenproblem: the implicit QL algorithm with Wilkinson-type shifts of
// EISPACK's tql2 (Bowdler, Martin, Reinsch & Wilkinson 1968), in the arrangement of the public-domain
// JAMA library. Private to engine::seismic.
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

namespace qv::seismic::detail {

/// On entry `d` holds the diagonal (n) and `e` the off-diagonal (e[i] couples i and i+1; e[n-1] is
/// ignored); `vectors`, when given, holds an n×n row-major matrix (normally the identity). On success
/// `d` holds the eigenvalues in ascending order and the columns of `vectors` the matching
/// orthonormal eigenvectors (multiplied by the initial matrix). Returns false if an eigenvalue needs
/// more than 60 iterations (not seen for the matrices of shear buildings).
inline bool symmetricTridiagonalEigen(std::vector<double>& d, std::vector<double>& e, std::vector<double>* vectors) {
  const std::size_t n = d.size();
  if (n == 0) return true;
  e.resize(n);
  e[n - 1] = 0.0;
  double f = 0.0;
  double tst1 = 0.0;
  const double eps = 0x1.0p-52;
  for (std::size_t l = 0; l < n; ++l) {
    tst1 = std::fmax(tst1, std::fabs(d[l]) + std::fabs(e[l]));
    std::size_t m = l;
    while (m < n - 1 && std::fabs(e[m]) > eps * tst1) ++m;
    if (m > l) {
      int iterations = 0;
      do {
        if (++iterations > 60) return false;
        double g = d[l];
        double p = (d[l + 1] - g) / (2.0 * e[l]);
        double r = std::hypot(p, 1.0);
        if (p < 0) r = -r;
        d[l] = e[l] / (p + r);
        d[l + 1] = e[l] * (p + r);
        const double dl1 = d[l + 1];
        double h = g - d[l];
        for (std::size_t i = l + 2; i < n; ++i) d[i] -= h;
        f += h;
        p = d[m];
        double c = 1.0;
        double c2 = c;
        double c3 = c;
        const double el1 = e[l + 1];
        double s = 0.0;
        double s2 = 0.0;
        for (std::size_t ii = m; ii-- > l;) {
          c3 = c2;
          c2 = c;
          s2 = s;
          g = c * e[ii];
          h = c * p;
          r = std::hypot(p, e[ii]);
          e[ii + 1] = s * r;
          s = e[ii] / r;
          c = p / r;
          p = c * d[ii] - s * g;
          d[ii + 1] = h + s * (c * g + s * d[ii]);
          if (vectors != nullptr) {
            std::vector<double>& v = *vectors;
            for (std::size_t k = 0; k < n; ++k) {
              h = v[k * n + ii + 1];
              v[k * n + ii + 1] = s * v[k * n + ii] + c * h;
              v[k * n + ii] = c * v[k * n + ii] - s * h;
            }
          }
        }
        p = -s * s2 * c3 * el1 * e[l] / dl1;
        e[l] = s * p;
        d[l] = c * p;
      } while (std::fabs(e[l]) > eps * tst1);
    }
    d[l] += f;
    e[l] = 0.0;
  }
  // Selection sort, ascending, swapping eigenvector columns along.
  for (std::size_t i = 0; i + 1 < n; ++i) {
    std::size_t k = i;
    for (std::size_t j = i + 1; j < n; ++j) {
      if (d[j] < d[k]) k = j;
    }
    if (k == i) continue;
    std::swap(d[i], d[k]);
    if (vectors != nullptr) {
      std::vector<double>& v = *vectors;
      for (std::size_t row = 0; row < n; ++row) std::swap(v[row * n + i], v[row * n + k]);
    }
  }
  return true;
}

}  // namespace qv::seismic::detail
