#include "qv/prep/Simplify.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "qv/prep/DouglasPeucker.h"

namespace qv::prep {
namespace {

double cross(glm::dvec2 o, glm::dvec2 a, glm::dvec2 b) {
  return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
}

bool segmentsIntersect(glm::dvec2 p1, glm::dvec2 p2, glm::dvec2 q1, glm::dvec2 q2) {
  const double d1 = cross(q1, q2, p1), d2 = cross(q1, q2, p2);
  const double d3 = cross(p1, p2, q1), d4 = cross(p1, p2, q2);
  return ((d1 > 0) != (d2 > 0)) && ((d3 > 0) != (d4 > 0)) && d1 != 0 && d2 != 0 && d3 != 0 && d4 != 0;
}

std::vector<glm::dvec2> convexHull(std::span<const glm::dvec2> points) {
  std::vector<glm::dvec2> p(points.begin(), points.end());
  std::sort(p.begin(), p.end(), [](glm::dvec2 a, glm::dvec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return {};
  // Andrew's monotone chain.
  std::vector<glm::dvec2> hull(2 * p.size());
  std::size_t k = 0;
  for (const glm::dvec2& q : p) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], q) <= 0) --k;
    hull[k++] = q;
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  hull.resize(k - 1);
  return hull;
}

}  // namespace

double signedArea(std::span<const glm::dvec2> ring) {
  double a = 0.0;
  for (std::size_t i = 0, n = ring.size(); i < n; ++i) {
    const glm::dvec2& p = ring[i];
    const glm::dvec2& q = ring[(i + 1) % n];
    a += p.x * q.y - q.x * p.y;
  }
  return 0.5 * a;
}

bool isSimpleRing(std::span<const glm::dvec2> ring) {
  const std::size_t n = ring.size();
  if (n < 3) return false;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segmentsIntersect(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) return false;
    }
  }
  return true;
}

std::vector<glm::dvec2> simplifyRing(std::span<const glm::dvec2> ring, double tol) {
  const std::size_t n = ring.size();
  if (n <= 4) return {ring.begin(), ring.end()};
  // Anchor on the point farthest from the first one, and simplify both halves.
  std::size_t far = 0;
  double farDistance = -1.0;
  for (std::size_t i = 1; i < n; ++i) {
    const double d =
        (ring[i].x - ring[0].x) * (ring[i].x - ring[0].x) + (ring[i].y - ring[0].y) * (ring[i].y - ring[0].y);
    if (d > farDistance) {
      farDistance = d;
      far = i;
    }
  }
  std::vector<glm::dvec2> closed(ring.begin(), ring.end());
  closed.push_back(ring[0]);
  std::vector<bool> keep(closed.size(), false);
  keep[0] = keep[far] = keep[n] = true;
  douglasPeucker(closed, 0, far, tol, keep);
  douglasPeucker(closed, far, n, tol, keep);
  std::vector<glm::dvec2> out;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep[i]) out.push_back(closed[i]);
  }
  return out;
}

std::vector<glm::dvec2> orientedBoundingRectangle(std::span<const glm::dvec2> points) {
  const std::vector<glm::dvec2> hull = convexHull(points);
  if (hull.size() < 3) return {};
  double bestArea = std::numeric_limits<double>::max();
  std::vector<glm::dvec2> best;
  // The minimum-area rectangle has a side collinear with a hull edge (Freeman & Shapira 1975).
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::dvec2 e = hull[(i + 1) % hull.size()] - hull[i];
    const double len = std::hypot(e.x, e.y);
    if (len <= 0.0) continue;
    const glm::dvec2 u = e / len;
    const glm::dvec2 v(-u.y, u.x);
    double minU = std::numeric_limits<double>::max(), maxU = -minU, minV = minU, maxV = -minU;
    for (const glm::dvec2& p : hull) {
      const double pu = p.x * u.x + p.y * u.y;
      const double pv = p.x * v.x + p.y * v.y;
      minU = std::min(minU, pu);
      maxU = std::max(maxU, pu);
      minV = std::min(minV, pv);
      maxV = std::max(maxV, pv);
    }
    const double area = (maxU - minU) * (maxV - minV);
    if (area < bestArea) {
      bestArea = area;
      best = {u * minU + v * minV, u * maxU + v * minV, u * maxU + v * maxV, u * minU + v * maxV};
    }
  }
  return best;
}

std::vector<glm::dvec2> coarseOutline(std::span<const glm::dvec2> outerRing, double tol, double& errorM) {
  std::vector<glm::dvec2> simplified = simplifyRing(outerRing, tol);
  if (simplified.size() >= 3 && simplified.size() <= 12 && isSimpleRing(simplified) &&
      std::abs(signedArea(simplified)) > 1e-6) {
    if (signedArea(simplified) < 0) std::reverse(simplified.begin(), simplified.end());
    errorM = tol;
    return simplified;
  }
  std::vector<glm::dvec2> box = orientedBoundingRectangle(outerRing);
  // The rectangle exceeds the footprint by at most its area difference over its perimeter-ish;
  // bound it by the distance from any rectangle corner to the hull.
  const double area = std::abs(signedArea(outerRing));
  const double boxArea = box.empty() ? 0.0 : std::abs(signedArea(box));
  const double perimeter = box.empty() ? 1.0
                                       : 2.0 * (std::hypot(box[1].x - box[0].x, box[1].y - box[0].y) +
                                                std::hypot(box[2].x - box[1].x, box[2].y - box[1].y));
  errorM = std::max(tol, (boxArea - area) / std::max(perimeter, 1e-6) * 2.0);
  return box;
}

}  // namespace qv::prep
