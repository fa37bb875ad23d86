// Times after injury in real units, as forensim prints them (wound/duration.hpp): seconds, minutes, hours,
// days, weeks.

/// "45 s", "12 min", "36.0 h", "5.0 days", "3.0 weeks".
export function formatInjuryTime(seconds) {
  const s = Math.max(0, seconds);
  if (s < 60) return `${s.toFixed(0)} s`;
  if (s < 3600) return `${(s / 60).toFixed(s < 600 ? 1 : 0)} min`;
  if (s < 2 * 86400) return `${(s / 3600).toFixed(1)} h`;
  if (s < 14 * 86400) return `${(s / 86400).toFixed(1)} days`;
  return `${(s / (7 * 86400)).toFixed(1)} weeks`;
}

/// "day 12.5" for a desiccation frame time in days.
export function formatDays(days) {
  return `day ${days.toFixed(days < 10 ? 1 : 0)}`;
}

/// A slider position in [0, 1] to a time in [t0, t1] on a logarithmic scale (healing spans minutes to
/// weeks), with `offset` seconds so that t0 = 0 works; and back.
export function sliderToTime(x, t0, t1, offset = 600) {
  const a = Math.log(t0 + offset), b = Math.log(t1 + offset);
  return Math.min(t1, Math.max(t0, Math.exp(a + (b - a) * x) - offset));
}

export function timeToSlider(t, t0, t1, offset = 600) {
  const a = Math.log(t0 + offset), b = Math.log(t1 + offset);
  return b > a ? (Math.log(t + offset) - a) / (b - a) : 0;
}
