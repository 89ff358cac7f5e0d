// A sketched stroke becomes the points of a template curve: the stroke is simplified with the
// Ramer-Douglas-Peucker algorithm (Douglas and Peucker 1973), with a tolerance that grows until
// at most `maxPoints` remain; the template's Catmull-Rom spline then passes through them.
// Points are [a, b] pairs in template units.

function distanceToSegment(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const len2 = dx * dx + dy * dy;
  const t = len2 > 0 ? Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2)) : 0;
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

/// The points of `points` that RDP keeps at `tolerance` (the first and last always).
export function simplify(points, tolerance) {
  if (points.length < 3) return points.slice();
  const keep = new Uint8Array(points.length);
  keep[0] = keep[points.length - 1] = 1;
  const stack = [[0, points.length - 1]];
  while (stack.length) {
    const [i, j] = stack.pop();
    let worst = -1, at = -1;
    for (let k = i + 1; k < j; ++k) {
      const d = distanceToSegment(points[k], points[i], points[j]);
      if (d > worst) { worst = d; at = k; }
    }
    if (worst > tolerance) {
      keep[at] = 1;
      stack.push([i, at], [at, j]);
    }
  }
  return points.filter((_, k) => keep[k]);
}

/// The curve points of a stroke: RDP at 1% of the stroke's size, coarsened until at most
/// `maxPoints` remain; at least `minPoints` (taken evenly from the stroke when RDP keeps fewer).
/// `closed`: a loop; its last point is dropped when it comes back near the first.
export function fitStroke(stroke, { closed = false, minPoints = 3, maxPoints = 24 } = {}) {
  let pts = stroke.filter((p, k) => k === 0 ||
    Math.hypot(p[0] - stroke[k - 1][0], p[1] - stroke[k - 1][1]) > 1e-9);
  if (pts.length < 2) return pts;
  const xs = pts.map((p) => p[0]), ys = pts.map((p) => p[1]);
  const size = Math.hypot(Math.max(...xs) - Math.min(...xs), Math.max(...ys) - Math.min(...ys));
  let tolerance = 0.01 * size;
  let fitted = simplify(pts, tolerance);
  while (fitted.length > maxPoints) {
    tolerance *= 1.5;
    fitted = simplify(pts, tolerance);
  }
  if (fitted.length < minPoints) {
    fitted = Array.from({ length: minPoints },
                        (_, k) => pts[Math.round(k * (pts.length - 1) / (minPoints - 1))]);
  }
  if (closed && fitted.length > 3) {
    const a = fitted[0], b = fitted[fitted.length - 1];
    if (Math.hypot(a[0] - b[0], a[1] - b[1]) < 0.08 * size) fitted.pop();
  }
  return fitted.map(([a, b]) => [Math.round(a * 100) / 100, Math.round(b * 100) / 100]);
}
