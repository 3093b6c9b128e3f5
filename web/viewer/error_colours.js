// Per-vertex colours for the distance between the mesh shown and the same
// level of the complete stream: grey where they agree, through yellow to
// red at `diagonalFraction` of the bounding-box diagonal and above (0.1 %,
// as `meshwave render --threshold` by default).
const GREY = [0.72, 0.72, 0.78], YELLOW = [1, 0.85, 0.2], RED = [0.9, 0.1, 0.1];

function ramp(t) {
  const [a, b, u] = t < 0.5 ? [GREY, YELLOW, t * 2] : [YELLOW, RED, t * 2 - 1];
  return [0, 1, 2].map((k) => a[k] + (b[k] - a[k]) * u);
}

export function errorColours(positions, reference, diagonalFraction = 0.001) {
  if (reference.length !== positions.length) return null;  // not the same vertices
  let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < reference.length; i += 3) {
    for (let a = 0; a < 3; ++a) {
      lo[a] = Math.min(lo[a], reference[i + a]);
      hi[a] = Math.max(hi[a], reference[i + a]);
    }
  }
  const scale = diagonalFraction * Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
  const colours = new Float32Array(positions.length);
  for (let i = 0; i < positions.length; i += 3) {
    const d = Math.hypot(positions[i] - reference[i], positions[i + 1] - reference[i + 1],
                         positions[i + 2] - reference[i + 2]);
    colours.set(ramp(Math.min(d / scale, 1)), i);
  }
  return colours;
}
