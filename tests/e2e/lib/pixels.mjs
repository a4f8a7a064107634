// Pixel checks on screenshots (PNG decoded with pngjs): is the canvas blank, what colour is a
// region, how different are two frames.
import { PNG } from 'pngjs';

export function decodePng(buffer) {
  const png = PNG.sync.read(buffer);
  return { width: png.width, height: png.height, data: png.data };
}

/// Mean and variance of luminance over the whole image (or a rectangle).
export function luminanceStats(image, rect = null) {
  const { width, data } = image;
  const x0 = rect ? rect.x : 0;
  const y0 = rect ? rect.y : 0;
  const x1 = rect ? rect.x + rect.width : image.width;
  const y1 = rect ? rect.y + rect.height : image.height;
  let n = 0;
  let sum = 0;
  let sumSq = 0;
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const i = (y * width + x) * 4;
      const l = 0.2126 * data[i] + 0.7152 * data[i + 1] + 0.0722 * data[i + 2];
      sum += l;
      sumSq += l * l;
      ++n;
    }
  }
  const mean = sum / n;
  return { mean, variance: sumSq / n - mean * mean };
}

/// Average colour [r, g, b] of a (2r+1)² square around (x, y).
export function colourAt(image, x, y, r = 2) {
  const { width, height, data } = image;
  const acc = [0, 0, 0];
  let n = 0;
  for (let yy = Math.max(0, Math.round(y) - r); yy <= Math.min(height - 1, Math.round(y) + r); ++yy) {
    for (let xx = Math.max(0, Math.round(x) - r); xx <= Math.min(width - 1, Math.round(x) + r); ++xx) {
      const i = (yy * width + xx) * 4;
      acc[0] += data[i];
      acc[1] += data[i + 1];
      acc[2] += data[i + 2];
      ++n;
    }
  }
  return acc.map((v) => v / n);
}

export function colourDistance(a, b) {
  return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

/// Fraction of pixels (in an optional rectangle) whose colour differs by more than `threshold`.
export function changedFraction(a, b, threshold = 24, rect = null) {
  if (a.width !== b.width || a.height !== b.height) return 1;
  const x0 = rect ? rect.x : 0;
  const y0 = rect ? rect.y : 0;
  const x1 = rect ? rect.x + rect.width : a.width;
  const y1 = rect ? rect.y + rect.height : a.height;
  let changed = 0;
  let n = 0;
  for (let y = y0; y < y1; ++y) {
    for (let x = x0; x < x1; ++x) {
      const i = (y * a.width + x) * 4;
      const d = Math.abs(a.data[i] - b.data[i]) + Math.abs(a.data[i + 1] - b.data[i + 1]) + Math.abs(a.data[i + 2] - b.data[i + 2]);
      if (d > threshold) ++changed;
      ++n;
    }
  }
  return changed / n;
}
