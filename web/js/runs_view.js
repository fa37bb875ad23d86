// The runs in the served folder and the server's jobs, with links to the view of each.

import { cancelJob, listJobs, listRuns } from './api.js';
import { escapeHtml, html } from './util.js';

export function viewLink(run) {
  const p = encodeURIComponent(run.path);
  if (run.command === 'mummify') return `#/desiccation?path=${p}`;
  return `#/run?path=${p}`;
}

export async function showRuns(ctx) {
  const [{ runs, skipped }, { jobs }] = await Promise.all([listRuns(), listJobs()]);
  const rows = runs.map((r) => `<tr><td><a href="${viewLink(r)}" data-run="${escapeHtml(r.path)}">` +
    `${escapeHtml(r.path || '(served folder)')}</a></td><td>${escapeHtml(r.command)}</td>` +
    `<td class="muted">${escapeHtml(r.started_utc || '')}</td></tr>`).join('');
  html(ctx.panel, `<h2>Runs</h2><table id="runs">${rows || '<tr><td class="muted">no runs yet</td></tr>'}</table>` +
    (skipped.length ? `<div class="muted">${skipped.length} folder(s) with an unreadable run.json</div>` : ''));
  const jobBox = html(ctx.panel, '<h2>Jobs</h2>');
  if (!jobs.length) jobBox.appendChild(Object.assign(document.createElement('div'), { className: 'muted', textContent: 'none' }));
  for (const j of jobs) {
    const row = document.createElement('div');
    row.textContent = `${j.id} ${j.kind} \u2192 ${j.output}: ${j.state} ${(100 * (j.progress.fraction || 0)).toFixed(0)} %`;
    if (j.state === 'running') {
      const b = document.createElement('button');
      b.textContent = 'Cancel';
      b.onclick = async () => { await cancelJob(j.id); location.reload(); };
      row.appendChild(b);
    }
    jobBox.appendChild(row);
  }
  ctx.overlay.textContent = '';
  ctx.ready();
}
