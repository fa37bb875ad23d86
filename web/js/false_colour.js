// False colour on a run's surfaces: the quantities a frame can be coloured by (moisture, shrinkage,
// uncertainty, the skin's own colour, any other per-vertex field), their colour maps and units, and the
// legend that shows them.
//
// Shrinkage is measured here, per vertex, as the local surface area lost against the rest shape: a vertex's
// area is a third of the area of each triangle around it (the barycentric dual area), and its shrinkage is
// 100 (1 - A / A_rest) %. The rest shape is the frame's rest_positions (a volume frame: its positions minus
// the displacement field) or else the first frame of the series (a skin frame).

// Colour maps as stops in linear RGB, evenly spaced over [0, 1].
export const COLOUR_MAPS = {
  // Dry (brown) to wet (blue) through straw yellow.
  moisture: [[0.545, 0.145, 0.0], [0.941, 0.753, 0.314], [0.173, 0.498, 0.722]],
  // Diverging about no change (pale, the middle of a range symmetric about 0): stretched (blue) to shrunk (red).
  shrinkage: [[0.02, 0.19, 0.38], [0.26, 0.58, 0.76], [0.97, 0.97, 0.97], [0.96, 0.50, 0.38], [0.40, 0.0, 0.12]],
  // Viridis at five points: certain (dark blue) to uncertain (yellow).
  uncertainty: [[0.267, 0.005, 0.329], [0.231, 0.322, 0.545], [0.129, 0.569, 0.549], [0.369, 0.788, 0.384],
                [0.993, 0.906, 0.144]],
};

/// The colour of `x` in [0, 1] (clamped) on the map `stops`.
export function mapColour(stops, x) {
  const t = Math.min(1, Math.max(0, Number.isFinite(x) ? x : 0)) * (stops.length - 1);
  const i = Math.min(stops.length - 2, Math.floor(t)), f = t - i;
  return stops[i].map((c, k) => c + (stops[i + 1][k] - c) * f);
}

/// Per-vertex dual area (mm^2) of a surface: a third of each adjacent triangle's area.
export function vertexAreas(positions, triangles, vertexCount) {
  const area = new Float64Array(vertexCount);
  const p = positions;
  for (let t = 0; t < triangles.length; t += 3) {
    const a = 3 * triangles[t], b = 3 * triangles[t + 1], c = 3 * triangles[t + 2];
    const ux = p[b] - p[a], uy = p[b + 1] - p[a + 1], uz = p[b + 2] - p[a + 2];
    const vx = p[c] - p[a], vy = p[c + 1] - p[a + 1], vz = p[c + 2] - p[a + 2];
    const third = Math.hypot(uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx) / 6;
    area[triangles[t]] += third;
    area[triangles[t + 1]] += third;
    area[triangles[t + 2]] += third;
  }
  return area;
}

/// Shrinkage per vertex, % of the rest area lost (negative where the surface stretched).
export function shrinkagePercent(frame, restPositions) {
  const now = vertexAreas(frame.positions, frame.triangles, frame.vertex_count);
  const rest = vertexAreas(restPositions, frame.triangles, frame.vertex_count);
  const out = new Float64Array(frame.vertex_count);
  for (let v = 0; v < out.length; ++v) out[v] = rest[v] > 0 ? 100 * (1 - now[v] / rest[v]) : 0;
  return out;
}

// What a scalar field means, for its legend.
const FIELD_UNITS = {
  water_percent: ['water', '% of mass (wet basis)'],
  moisture: ['moisture', 'kg water / kg dry mass'],
  moisture_ratio: ['skin moisture', 'ratio to the fresh skin'],
  uncertainty: ['uncertainty', 'mm'],
};

/// The colour modes a frame offers, in menu order: {id, label, unit, map, values(frame, rest) -> array,
/// fixedRange?}. `id` is one of 'colour', 'moisture', 'shrinkage', 'uncertainty' or 'field:NAME'.
export function colourModes(frame) {
  const modes = [];
  const scalars = frame.scalars || {};
  if (frame.vectors && frame.vectors.colour) modes.push({ id: 'colour', label: 'skin colour', unit: '', map: null });
  const moistureField = ['water_percent', 'moisture_ratio', 'moisture'].find((f) => f in scalars);
  if (moistureField) {
    const [what, unit] = FIELD_UNITS[moistureField];
    modes.push({ id: 'moisture', label: `moisture (${what})`, unit, map: COLOUR_MAPS.moisture, field: moistureField,
                 values: (f) => f.scalars[moistureField] });
  }
  modes.push({ id: 'shrinkage', label: 'shrinkage (local area)', unit: '% of the rest area lost',
               map: COLOUR_MAPS.shrinkage, values: (f, rest) => shrinkagePercent(f, rest) });
  if ('uncertainty' in scalars) {
    modes.push({ id: 'uncertainty', label: 'uncertainty', unit: 'mm', map: COLOUR_MAPS.uncertainty,
                 field: 'uncertainty', values: (f) => f.scalars.uncertainty });
  }
  for (const name of Object.keys(scalars)) {
    if (modes.some((m) => m.field === name)) continue;
    const [, unit] = FIELD_UNITS[name] || [name, ''];
    modes.push({ id: 'field:' + name, label: name, unit, map: COLOUR_MAPS.moisture, field: name,
                 values: (f) => f.scalars[name] });
  }
  return modes;
}

/// Minimum and maximum of `values` (finite entries), or [0, 0].
export function rangeOf(values) {
  let lo = Infinity, hi = -Infinity;
  for (const v of values) {
    if (!Number.isFinite(v)) continue;
    if (v < lo) lo = v;
    if (v > hi) hi = v;
  }
  return lo <= hi ? [lo, hi] : [0, 0];
}

/// The range a mode is shown over in a series, from the ranges `a` and `b` of its first and last frames:
/// their union; for shrinkage symmetric about 0 (at least +-0.1 %), so no change sits in the map's pale middle.
export function seriesRange(modeId, a, b) {
  const r = [Math.min(a[0], b[0]), Math.max(a[1], b[1])];
  if (modeId !== 'shrinkage') return r;
  const m = Math.max(Math.abs(r[0]), Math.abs(r[1]), 0.1);
  return [-m, m];
}

/// Per-vertex linear RGB (Float32Array, 3 per vertex) of `values` mapped over `range` on `map`.
export function coloursOf(values, range, map, vertexCount) {
  const out = new Float32Array(3 * vertexCount);
  const span = range[1] - range[0];
  for (let v = 0; v < vertexCount; ++v) {
    out.set(mapColour(map, span > 0 ? (values[v] - range[0]) / span : 0.5), 3 * v);
  }
  return out;
}

function cssColour(rgb) {
  // Linear to sRGB, so the legend shows the colours the canvas (sRGB output) shows.
  const s = rgb.map((c) => Math.round(255 * (c <= 0.0031308 ? 12.92 * c : 1.055 * c ** (1 / 2.4) - 0.055)));
  return `rgb(${s.join(',')})`;
}

/// A legend: title with unit, the colour bar and its low, middle and high values. Returns {element, show}.
export function legend(parent) {
  const box = document.createElement('div');
  box.className = 'legend-box';
  box.innerHTML = '<div id="legend-title"></div><div class="legend" id="legend-bar"></div>' +
    '<div class="row muted legend-ticks"><span id="range-lo"></span><span id="range-mid"></span>' +
    '<span id="range-hi"></span></div>';
  parent.appendChild(box);
  const $ = (id) => box.querySelector('#' + id);
  const format = (x) => (Math.abs(x) >= 100 ? x.toFixed(0) : x.toPrecision(3));
  return {
    element: box,
    /// `mode` from colourModes; `range` [lo, hi] in its unit.
    show(mode, range) {
      $('legend-title').textContent = mode.unit ? `${mode.label}, ${mode.unit}` : mode.label;
      box.dataset.mode = mode.id;
      const ticks = box.querySelector('.legend-ticks');
      if (!mode.map) {
        $('legend-bar').style.background = 'none';
        ticks.style.visibility = 'hidden';
        return;
      }
      ticks.style.visibility = 'visible';
      const stops = mode.map.map((c, i) => `${cssColour(c)} ${(100 * i / (mode.map.length - 1)).toFixed(0)}%`);
      $('legend-bar').style.background = `linear-gradient(to right, ${stops.join(', ')})`;
      $('range-lo').textContent = format(range[0]);
      $('range-mid').textContent = format((range[0] + range[1]) / 2);
      $('range-hi').textContent = format(range[1]);
    },
  };
}
