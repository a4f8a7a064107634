#include "qv/seismic/ResponseSolver.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "BoucWenUpdate.h"
#include "qv/core/NumberFormat.h"

namespace qv::seismic {
namespace {

// The relative-velocity response spectrum of a record at 5 % damping on a geometric grid of periods
// (kSpectrumFirstPeriodS × kSpectrumRatio^j), by Newmark's average acceleration with steps of at most
// T/10 on the record padded as in the solver (samples at t = k·dt from k = 0). Only batching uses it.
constexpr double kSpectrumFirstPeriodS = 0.04;
constexpr double kSpectrumRatio = 1.1;
constexpr std::size_t kSpectrumPeriods = 64;  // to 0.04 · 1.1^63 = 16 s

void velocitySpectrum(const std::vector<double>& padded, double dt, std::vector<double>& out) {
  out.assign(kSpectrumPeriods, 0.0);
  for (std::size_t j = 0; j < kSpectrumPeriods; ++j) {
    const double period = kSpectrumFirstPeriodS * std::pow(kSpectrumRatio, static_cast<double>(j));
    const double omega = 6.283185307179586 / period;
    const double c = 2.0 * 0.05 * omega;
    const double k = omega * omega;
    const int steps = static_cast<int>(std::ceil(dt / (period / 10.0) - 1e-9));
    const double h = dt / steps;
    const double denominator = 1.0 + 0.5 * h * c + 0.25 * h * h * k;
    double u = 0.0;
    double v = 0.0;
    double a = 0.0;
    double peak = 0.0;
    for (std::size_t s = 1; s < padded.size(); ++s) {
      for (int m = 1; m <= steps; ++m) {
        const double fraction = static_cast<double>(m) / steps;
        const double ground = padded[s - 1] + fraction * (padded[s] - padded[s - 1]);
        const double uStar = u + h * v + 0.25 * h * h * a;
        const double vStar = v + 0.5 * h * a;
        a = (-ground - c * vStar - k * uStar) / denominator;
        u = uStar + 0.25 * h * h * a;
        v = vStar + 0.5 * h * a;
        peak = std::max(peak, std::fabs(v));
      }
    }
    out[j] = peak;
  }
}

// The spectrum at a period, linear in log(period) between grid points, clamped to the grid (0 for a
// period that is not positive).
double spectrumAt(const std::vector<double>& spectrum, double periodS) {
  if (!(periodS > 0.0) || spectrum.size() != kSpectrumPeriods) return 0.0;
  const double position = std::clamp(std::log(periodS / kSpectrumFirstPeriodS) / std::log(kSpectrumRatio), 0.0,
                                     static_cast<double>(kSpectrumPeriods - 1));
  const auto j = std::min(static_cast<std::size_t>(position), kSpectrumPeriods - 2);
  const double fraction = position - static_cast<double>(j);
  return spectrum[j] + fraction * (spectrum[j + 1] - spectrum[j]);
}

// One building direction to solve.
struct SystemRef {
  std::size_t building = 0;
  int direction = 0;  // 0 = X, 1 = Y
  const ShearBuilding* model = nullptr;
  const GroundMotion* motion = nullptr;
  double scale = 1.0;
  double delay = 0.0;
  int substeps = 1;
  std::size_t storeys = 0;
  double inverseRecordStep = 0.0;  // 1 / the motion's step
  const double* padded = nullptr;  // 0, samples 1..N, 0, 0
  double lastPosition = 0.0;       // N + 1: the trailing zero
  bool squareRootUpdate = false;   // some storey has n = 2 (the n = 1 update needs no square root)
  bool curvedUnloading = false;    // some storey has γ̂ < β̂: backward Euler there (batching key)
  int refinementClass = 0;         // a priori levels of accuracy splitting (batching key, see solve())
};

// Explicit SIMD with the GCC/Clang vector extensions: generic 16-byte vectors (4 floats or 2
// doubles: one SSE2 register; scalars in WebAssembly without SIMD), or 32-byte vectors (one AVX2
// register) when CMake's QUAKEVIEW_WIDE_SIMD compiles this file with -mavx2 -mfma. Comparisons give
// integer masks of -1/0 and the vector ?: selects lane by lane (GCC 12, clang 14 and em++ 3.1.6 all
// accept it).
#if defined(QUAKEVIEW_WIDE_SIMD) && defined(__AVX2__)
constexpr std::size_t kVectorBytes = 32;
#else
constexpr std::size_t kVectorBytes = 16;
#endif
template <typename T>
struct Simd;
template <>
struct Simd<float> {
  typedef float V __attribute__((vector_size(kVectorBytes)));
  typedef std::int32_t M __attribute__((vector_size(kVectorBytes)));
  static constexpr std::size_t kLanes = kVectorBytes / 4;
  static constexpr std::int32_t kAbsMask = 0x7fffffff;
  // Convergence: the residual below 1e-3 of the size of its terms, or a correction at the level of
  // rounding. 1e-3 keeps float histories within about 6e-4 of the double reference (relative to the
  // peak, same steps) at ~1.2 solves per step; 3e-4 costs 11 % more for 2e-4.
  static constexpr float kResidual = 1e-3f;
  static constexpr float kCorrection = 2e-6f;
  // oneMinusExpNegative: 1.5·2^23 rounds to an integer in the low mantissa bits; IEEE exponent
  // field; Taylor terms of e^r - 1 for float (truncation below 2e-8 relative on |r| <= ln2/2).
  static constexpr float kRoundMagic = 12582912.0f;
  static constexpr std::int32_t kExponentBias = 127;
  static constexpr int kMantissaBits = 23;
  static constexpr int kExpTerms = 7;
};
template <>
struct Simd<double> {
  typedef double V __attribute__((vector_size(kVectorBytes)));
  typedef std::int64_t M __attribute__((vector_size(kVectorBytes)));
  static constexpr std::size_t kLanes = kVectorBytes / 8;
  static constexpr std::int64_t kAbsMask = 0x7fffffffffffffff;
  static constexpr double kResidual = 1e-10;
  static constexpr double kCorrection = 1e-14;
  static constexpr double kRoundMagic = 6755399441055744.0;  // 1.5·2^52
  static constexpr std::int64_t kExponentBias = 1023;
  static constexpr int kMantissaBits = 52;
  static constexpr int kExpTerms = 14;
};

template <typename T>
struct VectorMath {
  using V = typename Simd<T>::V;
  using M = typename Simd<T>::M;
  static constexpr std::size_t W = Simd<T>::kLanes;
  static V splat(T x) { return V{} + x; }
  static V abs(V x) { return __builtin_bit_cast(V, __builtin_bit_cast(M, x) & Simd<T>::kAbsMask); }
  /// ±1 with the sign bit of x (+1 for +0).
  static V signOf(V x) {
    return __builtin_bit_cast(V, (__builtin_bit_cast(M, x) & ~Simd<T>::kAbsMask) | __builtin_bit_cast(M, splat(T(1))));
  }
  /// Lane-wise maximum (maxps/maxpd).
  static V max(V a, V b) { return a > b ? a : b; }
  static V sqrt(V x) {
    V r = x;
    for (std::size_t l = 0; l < W; ++l) r[l] = std::sqrt(x[l]);
    return r;
  }
  /// The closed-form Bouc–Wen update of BoucWenUpdate.h on all lanes (the same operations; the sign
  /// of N = ẑ₀ + x taken from its sign bit). `oneMinusN` = 1 - [n = 2], `fourN` = 4 [n = 2].
  static void boucWen(V zPrevious, V x, V nIsTwo, V oneMinusN, V fourN, V cUnload, V& z, V& slope) {
    const V one = splat(T(1));
    const V total = zPrevious + x;
    const V sign = signOf(total);
    const V xs = x * sign;
    const V c = xs >= T(0) ? one : cUnload;
    const V cx = c * xs;
    const V b = one + oneMinusN * cx;
    const V s = sqrt(b * b + fourN * cx * (total * sign));
    z = T(2) * total / (b + s);
    const V absZ = z * sign;
    const V power = absZ * (nIsTwo * absZ + oneMinusN);
    slope = (one - c * power) / s;
  }
  /// oneMinusExpNegative of BoucWenUpdate.h on all lanes (y >= 0): 1 - e^(-y) from + - * / and an
  /// exact power of two, no library exp (the same bits wherever a·b + c is not fused; the AVX2 build
  /// fuses, as in the rest of the kernel). k = round(y / ln2) by the magic-number
  /// addition (round to nearest), 2^(-k) built in the exponent field (k <= 116: a normal number).
  static V oneMinusExpNegative(V y) {
    const V one = splat(T(1));
    const V limit = splat(T(80));
    y = y < limit ? y : limit;
    const V magic = splat(Simd<T>::kRoundMagic);
    const V rounded = y * T(1.4426950408889634074) + magic;
    const V k = rounded - magic;
    const M kInteger = __builtin_bit_cast(M, rounded) - __builtin_bit_cast(M, magic);
    const V r = (k * T(6.93147180369123816490e-01) - y) + k * T(1.90821492927058770002e-10);
    V p = splat(static_cast<T>(1.0 / detail::kFactorials[Simd<T>::kExpTerms]));
    for (int j = Simd<T>::kExpTerms - 1; j >= 1; --j) p = static_cast<T>(1.0 / detail::kFactorials[j]) + r * p;
    const V m = r * p;
    const V scale = __builtin_bit_cast(V, (Simd<T>::kExponentBias - kInteger) << Simd<T>::kMantissaBits);
    return (one - scale) - scale * m;
  }
  /// The exact update of BoucWenUpdate.h (boucWenExact: n in {1, 2}, γ̂ = β̂) on all lanes.
  static void boucWenExact(V zPrevious, V x, V nIsTwo, V oneMinusN, V& z, V& slope) {
    const V one = splat(T(1));
    const V zero = splat(T(0));
    const V sign = signOf(x);
    const V w0 = zPrevious * sign;
    const V s = x * sign;
    const V minusW0 = zero - w0;
    const V room = minusW0 > zero ? minusW0 : zero;
    const V unload = s < room ? s : room;
    const V w = w0 + unload;
    const V e = oneMinusExpNegative((s - unload) * (one + nIsTwo));
    const V numerator = e * (one - w) * (one + nIsTwo * w);
    const V denominator = one + nIsTwo * ((one - e) + w * e);
    const V end = w + numerator / denominator;
    z = end * sign;
    const V loading = end > zero ? end : zero;
    slope = one - loading * (nIsTwo * loading + oneMinusN);
  }
  /// The same when every lane has n = 1: no division.
  static void boucWenExactLinearExponent(V zPrevious, V x, V& z, V& slope) {
    const V one = splat(T(1));
    const V zero = splat(T(0));
    const V sign = signOf(x);
    const V w0 = zPrevious * sign;
    const V s = x * sign;
    const V minusW0 = zero - w0;
    const V room = minusW0 > zero ? minusW0 : zero;
    const V unload = s < room ? s : room;
    const V w = w0 + unload;
    const V end = w + (one - w) * oneMinusExpNegative(s - unload);
    z = end * sign;
    slope = one - (end > zero ? end : zero);
  }
  /// The backward-Euler update when every lane has n = 1: S = B, so one division and no square root.
  static void boucWenLinearExponent(V zPrevious, V x, V cUnload, V& z, V& slope) {
    const V one = splat(T(1));
    const V total = zPrevious + x;
    const V sign = signOf(total);
    const V xs = x * sign;
    const V c = xs >= T(0) ? one : cUnload;
    const V inverse = one / (one + c * xs);
    z = total * inverse;
    slope = (one - c * (z * sign)) * inverse;
  }
};

// Everything about one storey row across the lanes (structure of arrays). Floor i and storey i
// share a row: the floor above the storey.
template <typename T>
struct alignas(kVectorBytes) Row {
  using V = typename Simd<T>::V;
  // Model (per batch).
  V mass, load, elastic, hysteretic, hystereticStiffness, inverseYield, nIsTwo, oneMinusN, fourN, cUnload;
  V inverseHeight, massDamping, stiffnessDamping, diagonalBase, offBase;
  V isFloor;        // 1 for a floor of the lane's building, 0 for padding
  V backwardEuler;  // 1 for a Bouc–Wen storey on the backward-Euler update, 0 for the exact one (and others)
  // State at the start of the step.
  V u, v, a, z, drift;
  // Newton trial values.
  V aNew, vNew, du, dDrift, zTrial, force, tangent, storeyForce;
  // Linear solve.
  V rhs, inversePivot, offDiagonal;
  // Peaks.
  V peakDrift;
  V peakAcceleration;  // absolute acceleration of the floor above the storey
};

// The batch: K groups of vector lanes solved together. The recurrences of the Thomas algorithm are
// latency-bound (a division per storey), so the sweeps advance both groups storey by storey; the
// Bouc–Wen evaluation, which has enough independent work, runs group by group (fewer live registers).
template <typename T>
class BatchKernel {
 public:
  using V = typename Simd<T>::V;
  using M = typename Simd<T>::M;
  using Math = VectorMath<T>;
  static constexpr std::size_t kVectorLanes = Simd<T>::kLanes;
  static constexpr std::size_t K = 2;
  static constexpr std::size_t W = kVectorLanes * K;

  struct Lane {
    const SystemRef* system = nullptr;
    DirectionResponse* out = nullptr;
    std::uint32_t* nonConverged = nullptr;
    float* worstResidual = nullptr;  // largest relative residual of the lane's unconverged steps
  };
  struct Settings {
    double dt = 0.01;
    std::size_t frames = 0;
    int substeps = 1;
    bool keepDisplacements = true;
    bool keepDrifts = false;
    int maxIterations = 10;
    int maxSplits = 4;                // levels of halving a step (Newton failure or accuracy)
    double maxHystereticError = 1.0;  // >= 1: off (see ResponseOptions)
    bool exactUpdate = false;         // boucWenExact for storeys with γ̂ = β̂ (n in {1, 2}), else backward Euler
  };

  void run(const std::array<Lane, W>& lanes, std::size_t storeys, const Settings& requested, SolverStats& stats) {
    const std::size_t n = storeys;
    if (rows_.size() < (n + 1) * K) rows_.resize((n + 1) * K);
    setUp(lanes, n, requested);
    squareRoot_ = false;
    for (std::size_t l = 0; l < W; ++l)
      squareRoot_ = squareRoot_ || (lanes[l].system != nullptr && lanes[l].system->squareRootUpdate);
    // The hysteretic bound concerns backward-Euler storeys only: off for a batch without any.
    Settings settings = requested;
    if (!anyBackwardEuler_) settings.maxHystereticError = 1.0;

    const double h = settings.dt / settings.substeps;
    preparedStep_ = 0.0;
    startLevel_ = 0;

    double earliest = 1e300;
    active_ = 0;
    for (std::size_t l = 0; l < W; ++l) {
      unconverged_[l] = 0;
      worstResidual_[l] = 0.0f;
      if (lanes[l].system == nullptr) continue;
      earliest = std::fmin(earliest, lanes[l].system->delay);
      ++active_;
    }
    for (std::size_t f = 1; f < settings.frames; ++f) {
      // Before the earliest arrival every lane is at rest: the outputs stay zero.
      if (static_cast<double>(f) * settings.dt <= earliest) continue;
      for (int s = 0; s < settings.substeps; ++s) {
        const double t0 = static_cast<double>(f - 1) * settings.dt + static_cast<double>(s) * h;
        // With the hysteretic bound, a sub-step starts at the level of splitting the previous one
        // ended at (one level coarser when every piece would have passed at twice its length), so
        // a yield excursion does not pay a rejected coarse attempt at every sub-step.
        deepestCommitted_ = 0;
        largestCommittedRatio_ = 0.0;
        const int pieces = 1 << startLevel_;
        const double piece = h / static_cast<double>(pieces);
        for (int p = 0; p < pieces; ++p)
          advance(lanes, n, t0 + static_cast<double>(p) * piece, piece, startLevel_, settings, stats);
        if (settings.maxHystereticError < 1.0) {
          startLevel_ = deepestCommitted_;
          if (startLevel_ > 0 && largestCommittedRatio_ <= 0.5) --startLevel_;
        }
      }
      writeFrame(lanes, f, settings);
    }
    finish(lanes);
    for (std::size_t l = 0; l < W; ++l) {
      if (lanes[l].system == nullptr) continue;
      *lanes[l].nonConverged += unconverged_[l];
      *lanes[l].worstResidual = std::max(*lanes[l].worstResidual, worstResidual_[l]);
      stats.nonConvergedSteps += unconverged_[l];
    }
  }

 private:
  Row<T>& row(std::size_t i, std::size_t k) { return rows_[i * K + k]; }

  // Advances every lane from t0 by h. When some lane's Newton iterations do not converge, the step is
  // not committed and is taken as two halves instead, recursively up to settings.maxSplits levels; at
  // that depth it is accepted and each unconverged lane's step and relative residual are recorded.
  // When the step converged but some lane's hysteretic update has an estimated error above the bound
  // (hystereticErrorRatio), it is taken at once as the 2^L equal pieces the estimate asks for (it is
  // proportional to the step: the smallest L with error / 2^L <= bound, within the levels left), each
  // checked again, instead of halving and retrying level by level.
  void advance(const std::array<Lane, W>& lanes, std::size_t n, double t0, double h, int depth,
               const Settings& settings, SolverStats& stats) {
    if (h != preparedStep_) {
      prepareMatrix(n, static_cast<T>(0.5 * h));
      preparedStep_ = h;
    }
    const T step = static_cast<T>(h);
    const T halfStep = static_cast<T>(0.5 * h);
    const T quarterStepSquared = static_cast<T>(0.25 * h * h);
    const double t = t0 + h;
    for (std::size_t l = 0; l < W; ++l) {
      ground_[l / kVectorLanes][l % kVectorLanes] = static_cast<T>(groundAcceleration(lanes[l].system, t));
    }
    std::array<M, K> ok;
    std::array<V, K> residualRatio;
    const int solves = solveStep(n, step, halfStep, quarterStepSquared, settings.maxIterations, ok, residualRatio);
    stats.newtonIterations += static_cast<std::size_t>(solves) * active_;
    bool converged = true;
    for (std::size_t k = 0; k < K; ++k) converged = converged && allSet(ok[k]);
    const bool lastLevel = depth >= settings.maxSplits;
    int levels = 0;      // accuracy levels asked for
    double ratio = 1.0;  // estimated error / bound (1 when not estimated)
    if (converged && settings.maxHystereticError < 1.0) {
      ratio = hystereticErrorRatio(n) / settings.maxHystereticError;
      while (levels < settings.maxSplits - depth && ratio > static_cast<double>(1 << levels)) ++levels;
    }
    if (lastLevel || (converged && levels == 0)) {
      deepestCommitted_ = std::max(deepestCommitted_, depth);
      largestCommittedRatio_ = std::max(largestCommittedRatio_, ratio);
      if (!converged) {
        for (std::size_t l = 0; l < W; ++l) {
          if (lanes[l].system == nullptr || ok[l / kVectorLanes][l % kVectorLanes] != 0) continue;
          ++unconverged_[l];
          worstResidual_[l] =
              std::max(worstResidual_[l], static_cast<float>(residualRatio[l / kVectorLanes][l % kVectorLanes]));
        }
      }
      commit(n);
      stats.steps += active_;
      return;
    }
    restoreForces(n);
    if (!converged) {
      ++stats.splitSteps;
      advance(lanes, n, t0, 0.5 * h, depth + 1, settings, stats);
      advance(lanes, n, t0 + 0.5 * h, 0.5 * h, depth + 1, settings, stats);
      return;
    }
    ++stats.refinedSteps;
    const int pieces = 1 << levels;
    const double piece = h / static_cast<double>(pieces);
    for (int p = 0; p < pieces; ++p)
      advance(lanes, n, t0 + static_cast<double>(p) * piece, piece, depth + levels, settings, stats);
  }

  // The largest estimated local error of the backward-Euler Bouc–Wen update, per unit change of ẑ,
  // over the storeys and lanes of the batch: ½ |x| ψ n |ẑ|^(n−1) with x = Δδ/dy and ψ = 1 when
  // loading, γ̂ − β̂ when unloading (the estimate of ReferenceSolver.cpp; linear and padding rows have
  // 1/dy = 0). It is proportional to the step.
  double hystereticErrorRatio(std::size_t n) {
    const V one = Math::splat(T(1));
    V worst = Math::splat(T(0));
    for (std::size_t k = 0; k < K; ++k) {
      for (std::size_t i = 0; i < n; ++i) {
        const Row<T>& r = row(i, k);
        const V x = r.dDrift * r.inverseYield * r.backwardEuler;  // exact storeys: no error to estimate
        const V psi = x * r.zTrial >= T(0) ? one : Math::abs(r.cUnload);
        const V power = r.oneMinusN + r.nIsTwo * (T(2) * Math::abs(r.zTrial));
        worst = Math::max(worst, Math::abs(x) * psi * power);
      }
    }
    T largest = T(0);
    for (std::size_t v = 0; v < kVectorLanes; ++v) largest = std::max(largest, worst[v]);
    return 0.5 * static_cast<double>(largest);
  }

  // After a rejected attempt: the storey forces of the committed state (the next attempt's first
  // iteration linearises about them; the trial tangents are kept as its estimate).
  void restoreForces(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        r.force = r.elastic * r.drift + r.hysteretic * r.z;
      }
    }
  }

  static bool allSet(M m) {
    typedef std::uint64_t Words __attribute__((vector_size(kVectorBytes)));
    const Words w = __builtin_bit_cast(Words, m);
    std::uint64_t all = ~std::uint64_t{0};
    for (std::size_t i = 0; i < kVectorBytes / 8; ++i) all &= w[i];
    return all == ~std::uint64_t{0};
  }

  // scale · a(t - delay) under the time convention of GroundMotion.h, branch-free on the record padded
  // with its leading zero and two trailing zeros (positions clamped to [0, N + 1]).
  static double groundAcceleration(const SystemRef* sys, double t) {
    if (sys == nullptr) return 0.0;
    double position = (t - sys->delay) * sys->inverseRecordStep;
    position = position > 0.0 ? position : 0.0;
    position = position < sys->lastPosition ? position : sys->lastPosition;
    const auto k = static_cast<std::size_t>(position);
    const double fraction = position - static_cast<double>(k);
    const double left = sys->padded[k];
    return sys->scale * (left + fraction * (sys->padded[k + 1] - left));
  }

  void setUp(const std::array<Lane, W>& lanes, std::size_t n, const Settings& settings) {
    const V zero = Math::splat(T(0));
    for (std::size_t i = 0; i < (n + 1) * K; ++i) {
      Row<T>& r = rows_[i];
      // Padding: a unit mass without load, springs or dampers, which stays at rest.
      r.mass = r.oneMinusN = Math::splat(T(1));
      r.load = r.elastic = r.hysteretic = r.hystereticStiffness = r.inverseYield = r.nIsTwo = r.fourN = zero;
      r.cUnload = r.inverseHeight = r.massDamping = r.stiffnessDamping = r.isFloor = r.backwardEuler = zero;
      r.u = r.v = r.a = r.z = r.drift = zero;
      r.aNew = r.vNew = r.du = r.dDrift = r.zTrial = r.force = r.tangent = r.storeyForce = zero;
      r.rhs = r.inversePivot = r.offDiagonal = r.peakDrift = r.peakAcceleration = zero;
    }
    for (std::size_t k = 0; k < K; ++k) peakRoof_[k] = peakAcceleration_[k] = peakBase_[k] = ground_[k] = zero;
    sharedRoof_ = true;
    anyExact_ = anyBackwardEuler_ = false;
    for (std::size_t l = 0; l < W; ++l) {
      roofIndex_[l] = 0;
      const Lane& lane = lanes[l];
      if (lane.system == nullptr) continue;
      const std::size_t k = l / kVectorLanes;
      const std::size_t v = l % kVectorLanes;
      const ShearBuilding& b = *lane.system->model;
      const std::size_t storeys = b.storeys();
      roofIndex_[l] = storeys - 1;
      sharedRoof_ = sharedRoof_ && storeys == n;
      const double a0 = b.damping.massCoefficient;
      const double a1 = b.damping.stiffnessCoefficient;
      for (std::size_t i = 0; i < storeys; ++i) {
        Row<T>& r = row(i, k);
        const double m = b.floorMassKg[i];
        const double stiffness = b.storeyStiffnessNPerM[i];
        r.mass[v] = static_cast<T>(m);
        r.load[v] = static_cast<T>(m);
        r.isFloor[v] = T(1);
        r.massDamping[v] = static_cast<T>(m * a0);
        r.stiffnessDamping[v] = static_cast<T>(stiffness * a1);
        r.elastic[v] = static_cast<T>(stiffness);
        r.tangent[v] = static_cast<T>(stiffness);  // at rest: dẑ/dx = 1
        if (!b.hysteresis.empty() && std::isfinite(b.hysteresis[i].yieldDisplacementM)) {
          const BoucWenStorey& hw = b.hysteresis[i];
          r.elastic[v] = static_cast<T>(hw.alpha * stiffness);
          r.hysteretic[v] = static_cast<T>((1.0 - hw.alpha) * stiffness * hw.yieldDisplacementM);
          r.hystereticStiffness[v] = static_cast<T>((1.0 - hw.alpha) * stiffness);
          r.inverseYield[v] = static_cast<T>(1.0 / hw.yieldDisplacementM);
          r.nIsTwo[v] = hw.exponent == 2.0 ? T(1) : T(0);
          r.oneMinusN[v] = T(1) - r.nIsTwo[v];
          r.fourN[v] = T(4) * r.nIsTwo[v];
          r.cUnload[v] = static_cast<T>(2.0 * hw.gammaShare - 1.0);
          const bool exact = settings.exactUpdate && hw.gammaShare == 0.5;
          r.backwardEuler[v] = exact ? T(0) : T(1);
          anyExact_ = anyExact_ || exact;
          anyBackwardEuler_ = anyBackwardEuler_ || !exact;
        }
        if (!b.storeyHeightM.empty()) r.inverseHeight[v] = static_cast<T>(1.0 / b.storeyHeightM[i]);
      }
      DirectionResponse& out = *lane.out;
      const std::size_t count = settings.frames * storeys;
      if (settings.keepDisplacements) {
        out.floorDisplacementM.assign(count, 0.0f);
      } else {
        out.floorDisplacementM.clear();
      }
      if (settings.keepDrifts && !b.storeyHeightM.empty()) {
        out.driftRatio.assign(count, 0.0f);
      } else {
        out.driftRatio.clear();
      }
    }
  }

  // The parts of the effective matrix M + (h/2) C + (h²/4) K_t that do not depend on the state.
  void prepareMatrix(std::size_t n, T halfStep) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        const Row<T>& above = row(i + 1, k);
        r.diagonalBase = r.mass + halfStep * (r.massDamping + r.stiffnessDamping + above.stiffnessDamping);
        r.offBase = halfStep * above.stiffnessDamping;
      }
    }
  }

  // Newton iterations on the floor accelerations at the end of the step; returns the linear solves.
  // The first iteration is linearised about the end of the previous step (its storey forces and
  // tangents) from the constant-acceleration predictor, so a step that stays nearly linear costs
  // one solve and one evaluation of the storeys; later iterations use the consistent tangent.
  // `ok` flags the converged lanes; `residualRatio` holds each lane's residual over the size of its
  // force terms at the last evaluation.
  int solveStep(std::size_t n, T step, T halfStep, T quarterStepSquared, int maxIterations, std::array<M, K>& ok,
                std::array<V, K>& residualRatio) {
    linearizedForwardSweep(n, step, quarterStepSquared);
    std::array<M, K> stagnated;
    backSubstitute(n, stagnated);
    int solves = 1;
    for (int iteration = 1;; ++iteration) {
      bool all = true;
      for (std::size_t k = 0; k < K; ++k) {
        V residualMax;
        V scaleMax;
        evaluateWithResidual(n, k, step, halfStep, quarterStepSquared, residualMax, scaleMax);
        ok[k] = (residualMax <= Simd<T>::kResidual * scaleMax) | stagnated[k];
        all = all && allSet(ok[k]);
        if (iteration >= maxIterations) residualRatio[k] = residualMax / (scaleMax + T(1e-30));
      }
      if (all || iteration >= maxIterations) break;
      forwardSweep(n, quarterStepSquared);
      backSubstitute(n, stagnated);
      ++solves;
    }
    return solves;
  }

  // First iteration: the residual at the predictor aNew = a with storey forces f + K_t Δδ from the
  // previous step's forces and tangents, and at once the forward sweep of the Thomas algorithm.
  void linearizedForwardSweep(std::size_t n, T step, T quarterStepSquared) {
    const V zero = Math::splat(T(0));
    std::array<V, K> duBelow;
    std::array<V, K> vBelow;
    std::array<V, K> current;  // linearised storey force (with its damper) of row i
    std::array<V, K> offBelow;
    std::array<V, K> inversePivotBelow;
    std::array<V, K> rhsBelow;
    auto storeyForce = [&](Row<T>& r, std::size_t k) {
      const V vNew = r.v + step * r.a;
      const V du = step * r.v + (T(2) * quarterStepSquared) * r.a;
      const V total = r.force + r.tangent * (du - duBelow[k]) + r.stiffnessDamping * (vNew - vBelow[k]);
      r.aNew = r.a;
      r.vNew = vNew;
      duBelow[k] = du;
      vBelow[k] = vNew;
      return total;
    };
    for (std::size_t k = 0; k < K; ++k) {
      duBelow[k] = vBelow[k] = offBelow[k] = inversePivotBelow[k] = rhsBelow[k] = zero;
      current[k] = n > 0 ? storeyForce(row(0, k), k) : zero;
    }
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        const Row<T>& aboveRow = row(i + 1, k);
        const V above = i + 1 < n ? storeyForce(row(i + 1, k), k) : zero;
        const V residual = above - current[k] - r.load * ground_[k] - r.mass * r.aNew - r.massDamping * r.vNew;
        current[k] = above;
        const V diagonal = r.diagonalBase + quarterStepSquared * (r.tangent + aboveRow.tangent);
        const V off = -(r.offBase + quarterStepSquared * aboveRow.tangent);
        const V multiplier = offBelow[k] * inversePivotBelow[k];
        const V inversePivot = T(1) / (diagonal - multiplier * offBelow[k]);
        const V rhs = residual - multiplier * rhsBelow[k];
        r.offDiagonal = off;
        r.inversePivot = inversePivot;
        r.rhs = rhs;
        offBelow[k] = off;
        inversePivotBelow[k] = inversePivot;
        rhsBelow[k] = rhs;
      }
    }
  }

  // Storey states of group k at the current accelerations (implicit Bouc–Wen update, forces,
  // consistent tangents) and the residual R = -M 1 a_g - M a - C v - f_s into rhs, with its sizes.
  void evaluateWithResidual(std::size_t n, std::size_t k, T step, T halfStep, T quarterStepSquared, V& residualMax,
                            V& scaleMax) {
    const V zero = Math::splat(T(0));
    residualMax = scaleMax = zero;
    V duBelow = zero;
    V vBelow = zero;
    auto evaluateRow = [&](Row<T>& r) {
      const V sum = r.a + r.aNew;
      const V vNew = r.v + halfStep * sum;
      const V du = step * r.v + quarterStepSquared * sum;
      const V dDrift = du - duBelow;
      V z;
      V slope;
      const V x = dDrift * r.inverseYield;
      if (anyExact_ || !anyBackwardEuler_) {
        // (A batch without Bouc–Wen storeys has x = 0 everywhere: ẑ stays 0, dẑ/dx = 1.)
        if (squareRoot_) {
          Math::boucWenExact(r.z, x, r.nIsTwo, r.oneMinusN, z, slope);
        } else {
          Math::boucWenExactLinearExponent(r.z, x, z, slope);
        }
      }
      if (anyBackwardEuler_) {
        V zImplicit;
        V slopeImplicit;
        if (squareRoot_) {
          Math::boucWen(r.z, x, r.nIsTwo, r.oneMinusN, r.fourN, r.cUnload, zImplicit, slopeImplicit);
        } else {
          Math::boucWenLinearExponent(r.z, x, r.cUnload, zImplicit, slopeImplicit);
        }
        // A batch mixing both kinds of storey: each storey its own update.
        z = anyExact_ ? (r.backwardEuler > T(0) ? zImplicit : z) : zImplicit;
        slope = anyExact_ ? (r.backwardEuler > T(0) ? slopeImplicit : slope) : slopeImplicit;
      }
      const V force = r.elastic * (r.drift + dDrift) + r.hysteretic * z;
      r.vNew = vNew;
      r.du = du;
      r.dDrift = dDrift;
      r.zTrial = z;
      r.force = force;
      r.tangent = r.elastic + r.hystereticStiffness * slope;
      r.storeyForce = force + r.stiffnessDamping * (vNew - vBelow);
      duBelow = du;
      vBelow = vNew;
    };
    if (n > 0) evaluateRow(row(0, k));
    const V ground = ground_[k];
    for (std::size_t i = 0; i < n; ++i) {
      Row<T>& r = row(i, k);
      V aboveForce = zero;
      if (i + 1 < n) {
        Row<T>& above = row(i + 1, k);
        evaluateRow(above);
        aboveForce = above.storeyForce;
      }
      const V loadTerm = r.load * ground;
      const V inertia = r.mass * r.aNew;
      const V dampingTerm = r.massDamping * r.vNew;
      const V residual = aboveForce - r.storeyForce - loadTerm - inertia - dampingTerm;
      r.rhs = residual;
      const V terms = Math::abs(loadTerm) + Math::abs(inertia) + Math::abs(dampingTerm) + Math::abs(r.storeyForce);
      residualMax = Math::max(residualMax, Math::abs(residual));
      scaleMax = Math::max(scaleMax, terms);
    }
  }

  // Forward sweep of the Thomas algorithm on M + (h/2) C + (h²/4) K_t (symmetric positive definite,
  // no pivoting), in place on rhs.
  void forwardSweep(std::size_t n, T quarterStepSquared) {
    const V zero = Math::splat(T(0));
    std::array<V, K> offBelow;
    std::array<V, K> inversePivotBelow;
    std::array<V, K> rhsBelow;
    for (std::size_t k = 0; k < K; ++k) offBelow[k] = inversePivotBelow[k] = rhsBelow[k] = zero;
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        const V tangentAbove = i + 1 < n ? row(i + 1, k).tangent : zero;
        const V diagonal = r.diagonalBase + quarterStepSquared * (r.tangent + tangentAbove);
        const V off = -(r.offBase + quarterStepSquared * tangentAbove);
        const V multiplier = offBelow[k] * inversePivotBelow[k];
        const V inversePivot = T(1) / (diagonal - multiplier * offBelow[k]);
        const V rhs = r.rhs - multiplier * rhsBelow[k];
        r.offDiagonal = off;
        r.inversePivot = inversePivot;
        r.rhs = rhs;
        offBelow[k] = off;
        inversePivotBelow[k] = inversePivot;
        rhsBelow[k] = rhs;
      }
    }
  }

  // Back substitution; updates the accelerations and flags the lanes whose correction is at the
  // level of rounding.
  void backSubstitute(std::size_t n, std::array<M, K>& stagnated) {
    const V zero = Math::splat(T(0));
    std::array<V, K> next;
    std::array<V, K> correctionMax;
    std::array<V, K> accelerationMax;
    for (std::size_t k = 0; k < K; ++k) next[k] = correctionMax[k] = accelerationMax[k] = zero;
    for (std::size_t i = n; i-- > 0;) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        const V x = (r.rhs - r.offDiagonal * next[k]) * r.inversePivot;
        r.aNew += x;
        next[k] = x;
        correctionMax[k] = Math::max(correctionMax[k], Math::abs(x));
        accelerationMax[k] = Math::max(accelerationMax[k], Math::abs(r.aNew));
      }
    }
    for (std::size_t k = 0; k < K; ++k) {
      const V size = accelerationMax[k] + Math::abs(ground_[k]) + T(1e-30);
      stagnated[k] = correctionMax[k] <= Simd<T>::kCorrection * size;
    }
  }

  void commit(std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t k = 0; k < K; ++k) {
        Row<T>& r = row(i, k);
        r.u += r.du;
        r.v = r.vNew;
        r.a = r.aNew;
        r.drift += r.dDrift;
        r.z = r.zTrial;
        r.peakDrift = Math::max(r.peakDrift, Math::abs(r.drift));
        r.peakAcceleration = Math::max(r.peakAcceleration, r.isFloor * Math::abs(r.a + ground_[k]));
        peakAcceleration_[k] = Math::max(peakAcceleration_[k], r.peakAcceleration);
      }
    }
    for (std::size_t k = 0; k < K; ++k) {
      peakBase_[k] = Math::max(peakBase_[k], Math::abs(row(0, k).force));
      V roof;
      if (sharedRoof_) {
        roof = row(n - 1, k).u;
      } else {
        roof = peakRoof_[k];
        for (std::size_t v = 0; v < kVectorLanes; ++v) roof[v] = row(roofIndex_[k * kVectorLanes + v], k).u[v];
      }
      peakRoof_[k] = Math::max(peakRoof_[k], Math::abs(roof));
    }
  }

  void writeFrame(const std::array<Lane, W>& lanes, std::size_t frame, const Settings& settings) {
    if (!settings.keepDisplacements && !settings.keepDrifts) return;
    for (std::size_t l = 0; l < W; ++l) {
      const Lane& lane = lanes[l];
      if (lane.system == nullptr) continue;
      const std::size_t k = l / kVectorLanes;
      const std::size_t v = l % kVectorLanes;
      const std::size_t storeys = roofIndex_[l] + 1;
      DirectionResponse& out = *lane.out;
      if (!out.floorDisplacementM.empty()) {
        float* dst = out.floorDisplacementM.data() + frame * storeys;
        for (std::size_t i = 0; i < storeys; ++i) dst[i] = static_cast<float>(row(i, k).u[v]);
      }
      if (!out.driftRatio.empty()) {
        float* dst = out.driftRatio.data() + frame * storeys;
        for (std::size_t i = 0; i < storeys; ++i) {
          const Row<T>& r = row(i, k);
          dst[i] = static_cast<float>(r.drift[v] * r.inverseHeight[v]);
        }
      }
    }
  }

  void finish(const std::array<Lane, W>& lanes) {
    for (std::size_t l = 0; l < W; ++l) {
      const Lane& lane = lanes[l];
      if (lane.system == nullptr) continue;
      const std::size_t k = l / kVectorLanes;
      const std::size_t v = l % kVectorLanes;
      const std::size_t storeys = roofIndex_[l] + 1;
      const bool heights = !lane.system->model->storeyHeightM.empty();
      DirectionResponse& out = *lane.out;
      out.peakDriftM.resize(storeys);
      out.peakFloorAccelerationPerFloorMps2.resize(storeys);
      out.peakDriftRatio.resize(heights ? storeys : 0);
      out.residualDriftRatio.resize(heights ? storeys : 0);
      for (std::size_t i = 0; i < storeys; ++i) {
        const Row<T>& r = row(i, k);
        out.peakDriftM[i] = static_cast<float>(r.peakDrift[v]);
        out.peakFloorAccelerationPerFloorMps2[i] = static_cast<float>(r.peakAcceleration[v]);
        if (heights) {
          out.peakDriftRatio[i] = static_cast<float>(r.peakDrift[v] * r.inverseHeight[v]);
          out.residualDriftRatio[i] = static_cast<float>(r.drift[v] * r.inverseHeight[v]);
        }
      }
      out.peakRoofDisplacementM = static_cast<float>(peakRoof_[k][v]);
      out.residualRoofDisplacementM = static_cast<float>(row(storeys - 1, k).u[v]);
      out.peakFloorAccelerationMps2 = static_cast<float>(peakAcceleration_[k][v]);
      out.peakBaseShearN = static_cast<float>(peakBase_[k][v]);
    }
  }

  std::vector<Row<T>> rows_;  // [storey * K + group]
  std::array<V, K> ground_{};
  std::array<V, K> peakRoof_{};
  std::array<V, K> peakAcceleration_{};
  std::array<V, K> peakBase_{};
  std::size_t roofIndex_[W] = {};
  bool sharedRoof_ = true;
  bool squareRoot_ = true;              // some lane has n = 2 storeys
  bool anyExact_ = false;               // some storey of the batch on the exact update
  bool anyBackwardEuler_ = false;       // some storey of the batch on the backward-Euler update
  double preparedStep_ = 0.0;           // the step prepareMatrix last used
  int startLevel_ = 0;                  // levels of splitting a sub-step starts at (hysteretic bound)
  int deepestCommitted_ = 0;            // of the current sub-step: the deepest level committed
  double largestCommittedRatio_ = 0.0;  // and the largest error / bound committed
  std::size_t active_ = 0;              // lanes with a system
  std::array<std::uint32_t, W> unconverged_{};
  std::array<float, W> worstResidual_{};
};

constexpr std::size_t kFloatLanes = BatchKernel<float>::W;
constexpr std::size_t kDoubleLanes = BatchKernel<double>::W;

}  // namespace

struct ResponseSolver::Impl {
  ResponseOptions options;
  SolverStats stats;
  BatchKernel<float> floatKernel;
  BatchKernel<double> doubleKernel;
  std::vector<SystemRef> systems;
  std::vector<BuildingResponse> responses;     // one per building of the current batch, reused
  std::array<std::vector<double>, 2> padded;   // the X and Y records with their zeros
  std::array<std::vector<double>, 2> spectra;  // their velocity spectra (velocitySpectrum)

  template <typename Kernel, std::size_t W>
  void runBatches(Kernel& kernel, std::size_t frames, double dt, const ResponseSink& sink);
};

template <typename Kernel, std::size_t W>
void ResponseSolver::Impl::runBatches(Kernel& kernel, std::size_t frames, double dt, const ResponseSink& sink) {
  responses.resize(W);
  std::array<std::uint32_t, W> nonConverged{};
  std::array<float, W> worstResidual{};
  for (std::size_t start = 0; start < systems.size(); start += W) {
    const std::size_t end = std::min(systems.size(), start + W);
    std::array<typename Kernel::Lane, W> lanes{};
    std::array<std::size_t, W> buildingOfSlot{};
    std::size_t slots = 0;
    std::size_t storeys = 0;
    int substeps = 1;
    for (std::size_t k = start; k < end; ++k) {
      const SystemRef& sys = systems[k];
      // X and Y of a building are adjacent: reuse the slot of the previous lane for the Y direction.
      std::size_t slot = slots;
      if (sys.direction == 1 && slots > 0 && buildingOfSlot[slots - 1] == sys.building) slot = slots - 1;
      if (slot == slots) {
        buildingOfSlot[slots++] = sys.building;
        BuildingResponse& r = responses[slot];
        r.storeys = sys.storeys;
        r.frames = frames;
        r.timeStepS = dt;
        r.hasY = false;
        r.maxDriftRatio = 0.0f;
        r.damage = DamageState::None;
        nonConverged[slot] = 0;
        worstResidual[slot] = 0.0f;
      }
      BuildingResponse& r = responses[slot];
      if (sys.direction == 1) r.hasY = true;
      auto& lane = lanes[k - start];
      lane.system = &sys;
      lane.out = sys.direction == 0 ? &r.x : &r.y;
      lane.nonConverged = &nonConverged[slot];
      lane.worstResidual = &worstResidual[slot];
      storeys = std::max(storeys, sys.storeys);
      substeps = std::max(substeps, sys.substeps);
    }
    typename Kernel::Settings settings;
    settings.dt = dt;
    settings.frames = frames;
    settings.substeps = substeps;
    settings.keepDisplacements = options.floorDisplacements;
    settings.keepDrifts = options.driftRatios;
    settings.maxIterations = options.maxNewtonIterations;
    settings.maxSplits = options.maxSplits;
    // Automatic sub-steps: the exact update for storeys with γ̂ = β̂ (no error to bound), backward Euler
    // under the hysteretic bound for the others; fixed sub-steps: backward Euler, equal steps.
    settings.exactUpdate = options.fixedSubsteps == 0 && options.exactHystereticUpdate;
    settings.maxHystereticError = options.fixedSubsteps > 0 ? 1.0 : options.maxHystereticError;
    kernel.run(lanes, storeys, settings, stats);
    for (std::size_t slot = 0; slot < slots; ++slot) {
      BuildingResponse& r = responses[slot];
      float maxDrift = 0.0f;
      for (const float d : r.x.peakDriftRatio) maxDrift = std::max(maxDrift, d);
      if (r.hasY) {
        for (const float d : r.y.peakDriftRatio) maxDrift = std::max(maxDrift, d);
      }
      r.maxDriftRatio = maxDrift;
      const std::size_t b = buildingOfSlot[slot];
      const SystemRef* first = nullptr;
      for (std::size_t k = start; k < end && first == nullptr; ++k) {
        if (systems[k].building == b) first = &systems[k];
      }
      r.damage = first != nullptr ? classifyDamage(maxDrift, first->model->damageDriftThresholds) : DamageState::None;
      r.nonConvergedSteps = nonConverged[slot];
      r.worstResidualRatio = worstResidual[slot];
      sink(b, r);
    }
  }
}

ResponseSolver::ResponseSolver(const ResponseOptions& options) : impl_(std::make_unique<Impl>()) {
  impl_->options = options;
}
ResponseSolver::~ResponseSolver() = default;
ResponseSolver::ResponseSolver(ResponseSolver&&) noexcept = default;
ResponseSolver& ResponseSolver::operator=(ResponseSolver&&) noexcept = default;

const SolverStats& ResponseSolver::stats() const {
  return impl_->stats;
}
const ResponseOptions& ResponseSolver::options() const {
  return impl_->options;
}

Status ResponseSolver::solve(std::span<const ShearBuilding> buildings, std::span<const BuildingShaking> shaking,
                             const GroundMotion& motionX, const GroundMotion* motionY, const ResponseSink& sink,
                             std::span<const ShearBuilding> buildingsY) {
  const ResponseOptions& o = impl_->options;
  if (shaking.size() != buildings.size()) {
    return fail("response solver: " + std::to_string(buildings.size()) + " buildings but " +
                std::to_string(shaking.size()) + " shaking entries");
  }
  if (!buildingsY.empty() && buildingsY.size() != buildings.size()) {
    return fail("response solver: " + std::to_string(buildingsY.size()) + " Y models for " +
                std::to_string(buildings.size()) + " buildings");
  }
  for (const GroundMotion* m : {&motionX, motionY}) {
    if (m == nullptr) continue;
    if (!(m->timeStepS > 0.0) || m->size() == 0) return fail("response solver: motion '" + m->name + "' is empty");
  }
  if (o.maxNewtonIterations < 1 || o.maxNewtonIterations > 100 || o.maxSubsteps < 1 || o.maxSubsteps > 1000 ||
      o.fixedSubsteps < 0 || o.fixedSubsteps > 1000 || !(o.outputStepS >= 0.0 && o.outputStepS <= 10.0) ||
      o.maxSplits < 0 || o.maxSplits > 10 || !(o.maxHystereticError > 0.0)) {
    return fail(
        "response solver: options out of range (Newton iterations 1..100, sub-steps 1..1000, output "
        "step 0..10 s, splits 0..10, hysteretic error > 0)");
  }
  if (!sink) return fail("response solver: no sink for the results");
  const double dt = o.outputStepS > 0.0 ? o.outputStepS : motionX.timeStepS;

  auto check = [](const ShearBuilding& b, std::size_t index) -> Status {
    if (const Status s = validateShearBuilding(b); !s)
      return fail("building " + std::to_string(index) + ": " + s.error());
    if (b.damping.kind != DampingKind::Rayleigh) {
      return fail("building " + std::to_string(index) + ": the city solver needs Rayleigh damping");
    }
    for (const BoucWenStorey& h : b.hysteresis) {
      if (!(h.exponent == 1.0 || h.exponent == 2.0) || !h.unloadingStiff()) {
        return fail("building " + std::to_string(index) +
                    ": the city solver needs Bouc-Wen n = 1 or 2 and gamma <= beta (use the reference solver)");
      }
    }
    return {};
  };
  double maxDelay = 0.0;
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    if (const Status s = check(buildings[b], b); !s) return s;
    if (!buildingsY.empty()) {
      if (const Status s = check(buildingsY[b], b); !s) return s;
      if (buildingsY[b].storeys() != buildings[b].storeys()) {
        return fail("building " + std::to_string(b) + ": the Y model has a different storey count");
      }
    }
    const BuildingShaking& sh = shaking[b];
    if (!std::isfinite(sh.scale) || !std::isfinite(sh.scaleY) || !(sh.delaySeconds >= 0.0 && sh.delaySeconds <= 1e4)) {
      return fail("building " + std::to_string(b) + ": scale must be finite and delay in [0, 1e4] s, not " +
                  formatDouble(sh.scale) + ", " + formatDouble(sh.delaySeconds));
    }
    maxDelay = std::max(maxDelay, sh.delaySeconds);
  }
  double duration = motionX.durationS();
  if (motionY != nullptr) duration = std::max(duration, motionY->durationS());
  std::size_t frames = o.frameCount;
  if (frames == 0) {
    const double count = std::ceil((maxDelay + duration) / dt - 1e-9) + 1.0;
    if (count > 1e8) return fail("response solver: more than 1e8 frames");
    frames = static_cast<std::size_t>(count);
  }
  if (frames < 2) return fail("response solver: at least two frames are needed");

  // The records padded with the leading zero and trailing zeros of the time convention.
  for (int direction = 0; direction < 2; ++direction) {
    const GroundMotion* m = direction == 0 ? &motionX : motionY;
    std::vector<double>& p = impl_->padded[static_cast<std::size_t>(direction)];
    p.clear();
    if (m == nullptr) continue;
    p.reserve(m->size() + 3);
    p.push_back(0.0);
    p.insert(p.end(), m->accelerationMps2.begin(), m->accelerationMps2.end());
    p.push_back(0.0);
    p.push_back(0.0);
  }
  // Systems, with their sub-step needs from the periods of modes 1 and 2.
  auto& systems = impl_->systems;
  systems.clear();
  systems.reserve(buildings.size() * (motionY != nullptr ? 2 : 1));
  for (std::size_t b = 0; b < buildings.size(); ++b) {
    for (int direction = 0; direction < (motionY != nullptr ? 2 : 1); ++direction) {
      const ShearBuilding& model = direction == 1 && !buildingsY.empty() ? buildingsY[b] : buildings[b];
      SystemRef sys;
      sys.building = b;
      sys.direction = direction;
      sys.model = &model;
      sys.motion = direction == 0 ? &motionX : motionY;
      sys.scale = direction == 1 && shaking[b].scaleY > 0.0 ? shaking[b].scaleY : shaking[b].scale;
      sys.delay = shaking[b].delaySeconds;
      sys.inverseRecordStep = 1.0 / sys.motion->timeStepS;
      sys.padded = impl_->padded[static_cast<std::size_t>(direction)].data();
      sys.lastPosition = static_cast<double>(sys.motion->size() + 1);
      sys.storeys = model.storeys();
      for (const BoucWenStorey& h : model.hysteresis) {
        sys.squareRootUpdate = sys.squareRootUpdate || h.exponent == 2.0;
        sys.curvedUnloading = sys.curvedUnloading || h.gammaShare != 0.5;
      }
      if (o.fixedSubsteps > 0) {
        sys.substeps = o.fixedSubsteps;
      } else {
        auto modes = computeModes(model, false);
        if (!modes) return fail("building " + std::to_string(b) + ": " + modes.error());
        const double t2 = modes->periodsS.size() > 1 ? modes->periodsS[1] : 0.0;
        sys.substeps = automaticSubsteps(dt, modes->periodsS[0], t2, o.maxSubsteps);
      }
      systems.push_back(sys);
    }
  }
  // X and Y of a building share their kind of update, so the sort below keeps them adjacent.
  for (std::size_t k = 1; k < systems.size(); ++k) {
    if (systems[k].building != systems[k - 1].building) continue;
    systems[k].squareRootUpdate = systems[k - 1].squareRootUpdate =
        systems[k].squareRootUpdate || systems[k - 1].squareRootUpdate;
    systems[k].curvedUnloading = systems[k - 1].curvedUnloading =
        systems[k].curvedUnloading || systems[k - 1].curvedUnloading;
  }
  // A priori need of accuracy splitting, only to batch systems of similar need together (the batch
  // takes the step of its most demanding lane; the bound itself is checked step by step). A storey's
  // drift increment per step is estimated from the first mode: scale · Sv(T1) · Γ1 (φ_i − φ_(i−1)) · h
  // with Sv the record's relative-velocity spectrum at 5 % damping, so the error estimate's ½ x becomes
  // that over 2 dy_i; the class is log2 of its ratio to the bound in half levels. X and Y of a building
  // share the larger class, so they stay adjacent.
  // Only systems on the backward-Euler update are bounded (the exact update has no error to bound).
  const auto boundedSystem = [&](const SystemRef& sys) {
    return !sys.model->hysteresis.empty() && (!o.exactHystereticUpdate || sys.curvedUnloading);
  };
  const bool bounded =
      o.fixedSubsteps == 0 && o.maxHystereticError < 1.0 && std::any_of(systems.begin(), systems.end(), boundedSystem);
  if (bounded) {
    for (int direction = 0; direction < (motionY != nullptr ? 2 : 1); ++direction) {
      velocitySpectrum(impl_->padded[static_cast<std::size_t>(direction)],
                       (direction == 0 ? motionX : *motionY).timeStepS,
                       impl_->spectra[static_cast<std::size_t>(direction)]);
    }
    for (SystemRef& sys : systems) {
      const ShearBuilding& model = *sys.model;
      if (!boundedSystem(sys)) continue;
      auto modes = computeModes(model, true);
      if (!modes) return fail("building " + std::to_string(sys.building) + ": " + modes.error());
      const std::size_t n = model.storeys();
      double participation = 0.0;
      for (std::size_t i = 0; i < n; ++i) participation += modes->shapes[i] * model.floorMassKg[i];
      const double velocity = std::fabs(sys.scale) *
                              spectrumAt(impl_->spectra[static_cast<std::size_t>(sys.direction)], modes->periodsS[0]) *
                              std::fabs(participation);
      const double h = dt / static_cast<double>(sys.substeps);
      double ratio = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        const double dy = model.hysteresis[i].yieldDisplacementM;
        if (!std::isfinite(dy)) continue;
        const double shapeDrift = modes->shapes[i] - (i > 0 ? modes->shapes[i - 1] : 0.0);
        ratio = std::max(ratio, 0.5 * velocity * std::fabs(shapeDrift) * h / dy / o.maxHystereticError);
      }
      if (ratio > 1.0) sys.refinementClass = static_cast<int>(std::min(2.0 * std::log2(ratio), 40.0)) + 1;
    }
    for (std::size_t k = 1; k < systems.size(); ++k) {
      if (systems[k].building != systems[k - 1].building) continue;
      const int shared = std::max(systems[k].refinementClass, systems[k - 1].refinementClass);
      systems[k].refinementClass = systems[k - 1].refinementClass = shared;
    }
  }
  // Similar systems share a batch: by storeys (padding), then the kind of Bouc–Wen update (n = 2
  // anywhere, then γ̂ < β̂ anywhere: backward Euler), then the a priori need of accuracy splitting (with the
  // hysteretic bound), then delay (arrival skipping), keeping a building's X and Y adjacent so they land in
  // the same batch (the lane count is even; X and Y models share their storey laws' exponents).
  std::stable_sort(systems.begin(), systems.end(), [](const SystemRef& a, const SystemRef& b) {
    if (a.storeys != b.storeys) return a.storeys < b.storeys;
    if (a.squareRootUpdate != b.squareRootUpdate) return b.squareRootUpdate;
    if (a.curvedUnloading != b.curvedUnloading) return b.curvedUnloading;
    if (a.refinementClass != b.refinementClass) return a.refinementClass < b.refinementClass;
    if (a.delay != b.delay) return a.delay < b.delay;
    if (a.building != b.building) return a.building < b.building;
    return a.direction < b.direction;
  });
  if (o.precision == Precision::Float) {
    impl_->runBatches<BatchKernel<float>, kFloatLanes>(impl_->floatKernel, frames, dt, sink);
  } else {
    impl_->runBatches<BatchKernel<double>, kDoubleLanes>(impl_->doubleKernel, frames, dt, sink);
  }
  return {};
}

Result<std::vector<BuildingResponse>> solveResponses(std::span<const ShearBuilding> buildings,
                                                     std::span<const BuildingShaking> shaking,
                                                     const GroundMotion& motionX, const GroundMotion* motionY,
                                                     const ResponseOptions& options) {
  std::vector<BuildingResponse> out(buildings.size());
  ResponseSolver solver(options);
  const Status s = solver.solve(buildings, shaking, motionX, motionY,
                                [&](std::size_t index, const BuildingResponse& r) { out[index] = r; });
  if (!s) return Error{s.error()};
  return out;
}

}  // namespace qv::seismic
