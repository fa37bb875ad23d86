// A timeline slider with play/pause and the time shown in real units, for the wound timeline (continuous
// time on a log scale) and desiccation frames (discrete steps). Each change asks the stage for a frame; while
// playing, every frame asks for the next.

import { formatInjuryTime, sliderToTime, timeToSlider } from './time_units.js';

function el(tag, props = {}, children = []) {
  const e = document.createElement(tag);
  Object.assign(e, props);
  for (const c of children) e.appendChild(c);
  return e;
}

/// Continuous time from t0 to t1 (s). `onTime(t)` is called on every change; returns {setTime, playing}.
export function continuousTimeline(parent, stage, { t0, t1, onTime, loopSeconds = 12 }) {
  const box = el('div', { className: 'timeline' });
  box.appendChild(el('h2', { textContent: 'Time after injury' }));
  const slider = el('input', { type: 'range', min: 0, max: 1000, value: 0, id: 'time-slider' });
  const label = el('div', { id: 'time-label' });
  const play = el('button', { textContent: 'Play', id: 'play' });
  box.append(slider, label, play);
  parent.appendChild(box);
  let playing = false, last = 0;
  const apply = (x) => {
    const t = sliderToTime(x, t0, t1);
    label.textContent = formatInjuryTime(t);
    onTime(t);
    stage.requestRender();
  };
  slider.oninput = () => apply(slider.value / 1000);
  play.onclick = () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    play.classList.toggle('on', playing);
    last = performance.now();
    stage.requestRender();
  };
  const previous = stage.onFrame;
  stage.onFrame = (now) => {
    if (previous) previous(now);
    if (!playing) return;
    stage.requestRender();
    let x = slider.value / 1000 + (now - last) / 1000 / loopSeconds;
    last = now;
    if (x > 1) x -= 1;
    slider.value = Math.round(x * 1000);
    apply(x);
  };
  apply(0);
  return {
    setTime(t) {
      slider.value = Math.round(timeToSlider(t, t0, t1) * 1000);
      apply(slider.value / 1000);
    },
    get playing() { return playing; },
  };
}

/// Discrete steps 0..count-1 with `labelOf(i)`; `onStep(i)` may return a promise (a frame to load).
export function steppedTimeline(parent, stage, { count, labelOf, onStep, stepSeconds = 0.8 }) {
  const box = el('div', { className: 'timeline' });
  box.appendChild(el('h2', { textContent: 'Frames' }));
  const slider = el('input', { type: 'range', min: 0, max: Math.max(0, count - 1), value: 0, id: 'frame-slider' });
  const label = el('div', { id: 'frame-label' });
  const prev = el('button', { textContent: '\u25c0', id: 'prev-frame', title: 'previous frame' });
  const play = el('button', { textContent: 'Play', id: 'play' });
  const next = el('button', { textContent: '\u25b6', id: 'next-frame', title: 'next frame' });
  box.append(slider, label, el('div', { className: 'row' }, [prev, play, next]));
  parent.appendChild(box);
  let index = 0, playing = false, busy = false, last = 0;
  const go = async (i) => {
    index = Math.max(0, Math.min(Number(slider.max), i));
    slider.value = index;
    label.textContent = labelOf(index);
    busy = true;
    try {
      await onStep(index);
    } finally {
      busy = false;
      stage.requestRender();
    }
  };
  slider.oninput = () => go(Number(slider.value));
  prev.onclick = () => go(index - 1);
  next.onclick = () => go(index + 1);
  play.onclick = () => {
    playing = !playing;
    play.textContent = playing ? 'Pause' : 'Play';
    play.classList.toggle('on', playing);
    stage.requestRender();
  };
  const previous = stage.onFrame;
  stage.onFrame = (now) => {
    if (previous) previous(now);
    if (playing) stage.requestRender();  // to look at the clock again
    if (!playing || busy || now - last < stepSeconds * 1000) return;
    last = now;
    go(index + 1 > Number(slider.max) ? 0 : index + 1);
  };
  return {
    go,
    setCount(n) {
      slider.max = Math.max(0, n - 1);
    },
    get index() { return index; },
  };
}
