// The skull editor's small pure helpers (no three.js, so node tests them): the server's base64 mesh arrays
// (src/server/mesh_arrays.hpp) as typed arrays, the landmark confidence colour, the blend of an expression
// played over the neutral face, and the median of measured times.

/// The bytes of a base64 string as an ArrayBuffer.
export function base64Bytes(text) {
  const binary = atob(text);
  const bytes = new Uint8Array(binary.length);
  for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
  return bytes.buffer;
}

/// Little-endian float32 positions (3 per vertex) from the server's "positions_f32".
export const float32Array = (text) => new Float32Array(base64Bytes(text));
/// Little-endian uint32 triangle indices from the server's "triangles_u32".
export const uint32Array = (text) => new Uint32Array(base64Bytes(text));

/// Linear RGB in [0, 1] for a landmark's confidence in [0, 1]: red (0) through amber (0.5) to green (1).
export function confidenceColour(confidence) {
  const c = Math.min(1, Math.max(0, Number(confidence) || 0));
  return c < 0.5 ? [0.9, 0.15 + 1.3 * c, 0.1] : [0.9 - 1.5 * (c - 0.5), 0.8, 0.1 + 0.2 * (c - 0.5)];
}

/// Weight of an expression at `t` seconds into a play of `duration` seconds: up in the first 40 %, held for
/// 20 %, back down (smoothstep ramps), 0 outside.
export function playWeight(t, duration) {
  if (!(t > 0) || t >= duration) return 0;
  const x = t / duration;
  const s = (u) => u * u * (3 - 2 * u);
  if (x < 0.4) return s(x / 0.4);
  if (x < 0.6) return 1;
  return s((1 - x) / 0.4);
}

/// out = neutral + w (pose - neutral), element by element.
export function blendPositions(out, neutral, pose, w) {
  for (let i = 0; i < out.length; ++i) out[i] = neutral[i] + w * (pose[i] - neutral[i]);
  return out;
}

/// Median of a list of numbers (NaN for none).
export function median(values) {
  if (!values.length) return NaN;
  const s = [...values].sort((a, b) => a - b);
  const m = s.length >> 1;
  return s.length % 2 ? s[m] : (s[m - 1] + s[m]) / 2;
}
