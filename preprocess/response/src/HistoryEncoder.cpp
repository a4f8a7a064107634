#include "qv/prep/HistoryEncoder.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <vector>

namespace qv::prep {
namespace {

using Matrix = Eigen::MatrixXd;

// Catmull-Rom weights at u in [0, 1), as sampleHistory uses them.
struct Weights {
  double w0, w1, w2, w3;
};
Weights catmullRom(double u) {
  const double u2 = u * u, u3 = u2 * u;
  return {0.5 * (-u3 + 2.0 * u2 - u), 0.5 * (3.0 * u3 - 5.0 * u2 + 2.0), 0.5 * (-3.0 * u3 + 4.0 * u2 + u),
          0.5 * (u3 - u2)};
}

// One direction of one building, projected on its principal basis.
struct DirectionPlan {
  Matrix basis;            // storeys × storeys, columns by decreasing eigenvalue
  Eigen::VectorXd energy;  // eigenvalues, decreasing (over the sampled frames)
  Eigen::Index sampledFrames = 1;
  int modes = 0;                      // vectors kept
  Matrix q;                           // modes × frames, full-rate coordinates
  std::vector<double> shapeMax;       // max_i |Φ_ik| per mode
  std::vector<double> coordinateMax;  // max_t |q_k| per mode
};

void project(DirectionPlan& p, const Matrix& data, int modes) {
  p.modes = modes;
  p.q = p.basis.leftCols(modes).transpose() * data;
  p.shapeMax.clear();
  p.coordinateMax.clear();
  for (int k = 0; k < modes; ++k) {
    p.shapeMax.push_back(p.basis.col(k).cwiseAbs().maxCoeff());
    p.coordinateMax.push_back(p.q.row(k).cwiseAbs().maxCoeff());
  }
}

// The basis (eigenvectors of D Dᵀ over at most ~1000 evenly spaced frames: as good a basis, a
// fraction of the work) and the fewest vectors whose residual, estimated from the eigenvalues,
// is well inside `target` (the exact check comes later).
DirectionPlan planDirection(const Matrix& data, double target, int maxModes) {
  DirectionPlan p;
  const Eigen::Index n = data.rows(), m = data.cols();
  if (n == 0 || m == 0 || data.cwiseAbs().maxCoeff() <= target * 0.2) return p;  // no motion to store
  const Eigen::Index stride = std::max<Eigen::Index>(1, m / 1000);
  p.sampledFrames = (m + stride - 1) / stride;
  const Eigen::Map<const Matrix, 0, Eigen::OuterStride<>> sampled(data.data(), n, p.sampledFrames,
                                                                  Eigen::OuterStride<>(n * stride));
  const Eigen::SelfAdjointEigenSolver<Matrix> solver(sampled * sampled.transpose());
  p.basis = solver.eigenvectors().rowwise().reverse();  // Eigen sorts ascending
  p.energy = solver.eigenvalues().reverse().cwiseMax(0.0);
  const int limit = static_cast<int>(std::min<Eigen::Index>(n, maxModes));
  int modes = 1;
  // RMS over frames of the residual vector's length; a peak is typically ~3 times the RMS.
  while (modes < limit &&
         std::sqrt(p.energy.tail(n - modes).sum() / static_cast<double>(p.sampledFrames)) > target / 3.0) {
    ++modes;
  }
  project(p, data, modes);
  return p;
}

// Catmull-Rom resampling of coordinate series `row` from every `step`-th frame: estimate of the
// largest error, checked at the quarter, half and three-quarter points of each interval.
double interpolationErrorEstimate(const Eigen::Ref<const Eigen::RowVectorXd>& row, Eigen::Index step) {
  const Eigen::Index frames = row.size();
  if (step <= 1 || frames < 2) return 0.0;
  const Eigen::Index samples = (frames - 1 + step - 1) / step + 1;
  auto sample = [&](Eigen::Index j) { return row(std::min(std::min(j, samples - 1) * step, frames - 1)); };
  double worst = 0.0;
  const Eigen::Index offsets[3] = {std::max<Eigen::Index>(1, step / 4), step / 2, 3 * step / 4};
  const Weights w[3] = {catmullRom(static_cast<double>(offsets[0]) / static_cast<double>(step)),
                        catmullRom(static_cast<double>(offsets[1]) / static_cast<double>(step)),
                        catmullRom(static_cast<double>(offsets[2]) / static_cast<double>(step))};
  for (Eigen::Index i1 = 0; i1 + 1 < samples; ++i1) {
    const double p0 = sample(i1 > 0 ? i1 - 1 : 0), p1 = sample(i1), p2 = sample(i1 + 1), p3 = sample(i1 + 2);
    for (int o = 0; o < 3; ++o) {
      const Eigen::Index f = i1 * step + offsets[o];
      if (f >= frames) break;
      const double v = w[o].w0 * p0 + w[o].w1 * p1 + w[o].w2 * p2 + w[o].w3 * p3;
      worst = std::max(worst, std::abs(v - row(f)));
    }
  }
  return worst;
}

// Root-sum-square over modes of each mode's resampling error weighted by its largest shape entry.
double resamplingError(const DirectionPlan& p, Eigen::Index step) {
  double sum = 0.0;
  for (int k = 0; k < p.modes; ++k) {
    const double e = p.shapeMax[static_cast<std::size_t>(k)] * interpolationErrorEstimate(p.q.row(k), step);
    sum += e * e;
  }
  return std::sqrt(sum);
}

double quantizationError(const DirectionPlan& p, int bits) {
  const double levels = bits == 8 ? 127.0 : 32767.0;
  double sum = 0.0;
  for (int k = 0; k < p.modes; ++k) {
    const double e =
        p.shapeMax[static_cast<std::size_t>(k)] * p.coordinateMax[static_cast<std::size_t>(k)] / levels * 0.5;
    sum += e * e;
  }
  return std::sqrt(sum);
}

// Quantized samples into `out`, and the coordinates sampleHistory will reconstruct from them at
// every frame into `rebuilt` (modes × frames).
void fillDirection(HistoryDirection& out, const DirectionPlan& p, Eigen::Index storeys, Eigen::Index frames,
                   Eigen::Index step, std::uint32_t samples, int bits, Matrix& rebuilt) {
  out.modes = static_cast<std::uint8_t>(p.modes);
  out.shapes.assign(static_cast<std::size_t>(storeys * p.modes), 0.0f);
  out.scales.assign(static_cast<std::size_t>(p.modes), 0.0f);
  out.coordinates.assign(static_cast<std::size_t>(p.modes) * samples, 0);
  rebuilt.resize(p.modes, frames);
  const double levels = bits == 8 ? 127.0 : 32767.0;
  std::vector<double> quantized(samples);
  for (int k = 0; k < p.modes; ++k) {
    for (Eigen::Index i = 0; i < storeys; ++i) {
      out.shapes[static_cast<std::size_t>(i * p.modes + k)] = static_cast<float>(p.basis(i, k));
    }
    auto at = [&](std::uint32_t s) {
      return p.q(k, std::min<Eigen::Index>(static_cast<Eigen::Index>(s) * step, frames - 1));
    };
    double peak = 0.0;
    for (std::uint32_t s = 0; s < samples; ++s) peak = std::max(peak, std::abs(at(s)));
    const auto scale = static_cast<float>(peak > 0.0 ? peak / levels : 1.0);
    out.scales[static_cast<std::size_t>(k)] = scale;
    for (std::uint32_t s = 0; s < samples; ++s) {
      const auto v = static_cast<std::int16_t>(
          std::clamp(std::lround(at(s) / scale), -static_cast<long>(levels), static_cast<long>(levels)));
      out.coordinates[static_cast<std::size_t>(k) * samples + s] = v;
      quantized[s] = static_cast<double>(v) * scale;
    }
    for (Eigen::Index f = 0; f < frames; ++f) {
      const Eigen::Index i1 = f / step;
      const auto j = static_cast<std::uint32_t>(i1);
      const Weights w = catmullRom(static_cast<double>(f - i1 * step) / static_cast<double>(step));
      const std::uint32_t last = samples - 1;
      rebuilt(k, f) = w.w0 * quantized[j > 0 ? j - 1 : 0] + w.w1 * quantized[std::min(j, last)] +
                      w.w2 * quantized[std::min(j + 1, last)] + w.w3 * quantized[std::min(j + 2, last)];
    }
  }
}

}  // namespace

double historyMaxError(const BuildingHistory& h, std::span<const float> x, std::span<const float> y,
                       std::size_t storeys, std::size_t frames, double dt) {
  std::vector<float> fx(storeys + 1), fy(storeys + 1);
  double worst = 0.0;
  for (std::size_t f = 0; f < frames; ++f) {
    sampleHistory(h, static_cast<double>(f) * dt, fx, fy);
    for (std::size_t i = 0; i < storeys; ++i) {
      worst = std::max(worst, std::abs(static_cast<double>(fx[i + 1]) - x[f * storeys + i]));
      const double yv = y.empty() ? 0.0 : static_cast<double>(y[f * storeys + i]);
      worst = std::max(worst, std::abs(static_cast<double>(fy[i + 1]) - yv));
    }
  }
  return worst;
}

EncodedHistory encodeHistory(std::span<const float> x, std::span<const float> y, std::size_t storeys,
                             std::size_t frames, double dt, const HistoryEncodingOptions& options) {
  EncodedHistory out;
  BuildingHistory& h = out.history;
  if (storeys == 0 || frames == 0 || x.size() != storeys * frames || (!y.empty() && y.size() != x.size()) ||
      !(dt > 0.0)) {
    return out;
  }
  const auto n = static_cast<Eigen::Index>(storeys);
  for (std::size_t f = 0; f < frames; ++f) {
    const double rx = x[f * storeys + storeys - 1];
    const double ry = y.empty() ? 0.0 : y[f * storeys + storeys - 1];
    out.peakRoofM = std::max(out.peakRoofM, std::hypot(rx, ry));
  }
  // A building that does not move (or only by a micrometre) still gets a history of zeros.
  const double budget = options.toleranceFraction * std::max(out.peakRoofM, 1e-6);
  h.floors = static_cast<std::uint16_t>(storeys);

  // Frames before the first motion (the shaking's arrival) need no samples: start one frame before.
  std::size_t first = frames;
  for (std::size_t f = 0; f < frames && first == frames; ++f) {
    for (std::size_t i = 0; i < storeys; ++i) {
      if (x[f * storeys + i] != 0.0f || (!y.empty() && y[f * storeys + i] != 0.0f)) {
        first = f;
        break;
      }
    }
  }
  first = first == frames ? 0 : (first > 0 ? first - 1 : 0);
  const auto active = static_cast<Eigen::Index>(frames - first);
  h.startSeconds = static_cast<float>(static_cast<double>(first) * dt);
  // D as storeys × frames (the input is frame-major, i.e. column-major storeys × frames).
  const Matrix dx = Eigen::Map<const Eigen::MatrixXf>(x.data() + first * storeys, n, active).cast<double>();
  const Matrix dy =
      y.empty() ? Matrix(n, 0)
                : Matrix(Eigen::Map<const Eigen::MatrixXf>(y.data() + first * storeys, n, active).cast<double>());

  // Split of the budget between the basis, resampling and rounding (estimates; the exact error is
  // measured below and the encoding refined until it fits).
  DirectionPlan px = planDirection(dx, 0.6 * budget, options.maxModes);
  DirectionPlan py = planDirection(dy, 0.6 * budget, options.maxModes);

  const double fullRate = 1.0 / dt;
  const auto maxStep = static_cast<Eigen::Index>(std::max(1.0, std::floor(fullRate / options.minRateHz)));
  auto resamplingFits = [&](Eigen::Index s) {
    return std::max(resamplingError(px, s), resamplingError(py, s)) <= 0.5 * budget;
  };
  Eigen::Index step = 1;
  if (resamplingFits(maxStep)) {
    step = maxStep;
  } else {
    Eigen::Index lo = 1, hi = maxStep;  // fits(lo), !fits(hi): the error grows with the step
    while (hi - lo > 1) {
      const Eigen::Index mid = (lo + hi) / 2;
      (resamplingFits(mid) ? lo : hi) = mid;
    }
    step = lo;
  }
  int bits = std::max(quantizationError(px, 8), quantizationError(py, 8)) <= 0.3 * budget ? 8 : 16;

  Matrix rebuiltX, rebuiltY;
  for (int attempt = 0; attempt < 24; ++attempt) {
    const auto samples = static_cast<std::uint32_t>((active - 1 + step - 1) / step + 1);
    h.sampleRateHz = static_cast<float>(fullRate / static_cast<double>(step));
    h.sampleCount = samples;
    h.bits = static_cast<std::uint8_t>(bits);
    fillDirection(h.x, px, n, active, step, samples, bits, rebuiltX);
    fillDirection(h.y, py, n, active, step, samples, bits, rebuiltY);
    // The exact error at every floor and frame (the frames before `first` are exact zeros).
    double error = 0.0;
    const std::pair<const DirectionPlan*, const Matrix*> dirs[] = {{&px, &dx}, {&py, &dy}};
    const Matrix* rebuilt[] = {&rebuiltX, &rebuiltY};
    for (int d = 0; d < 2; ++d) {
      const auto [plan, data] = dirs[d];
      if (data->cols() == 0) continue;
      if (plan->modes == 0) {
        error = std::max(error, data->cwiseAbs().maxCoeff());
      } else {
        error = std::max(error, (*data - plan->basis.leftCols(plan->modes) * *rebuilt[d]).cwiseAbs().maxCoeff());
      }
    }
    out.maxErrorM = error;
    out.attempts = attempt + 1;
    if (error <= budget) return out;
    // Refine: a finer rate while it is coarse, then more precision, then another basis vector.
    if (step > 1 && attempt % 3 != 2) {
      step = std::max<Eigen::Index>(1, step * 4 / 5);
    } else if (bits == 8) {
      bits = 16;
    } else {
      bool grown = false;
      for (auto [plan, data] : {std::pair{&px, &dx}, std::pair{&py, &dy}}) {
        if (data->cols() > 0 && plan->modes > 0 && plan->modes < n) {
          project(*plan, *data, plan->modes + 1);
          grown = true;
        } else if (data->cols() > 0 && plan->modes == 0 && data->cwiseAbs().maxCoeff() > 0.0) {
          // A direction first judged motionless after all needs its basis.
          *plan = planDirection(*data, 0.0, 1);
          grown = plan->modes > 0;
        }
      }
      if (!grown && step == 1) return out;  // every mode, full rate, 16 bits: as good as it gets
    }
  }
  return out;
}

}  // namespace qv::prep
