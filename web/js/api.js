// The forensim serve JSON API (see src/server/api_server.hpp). Every call throws an ApiError with the
// server's message and the field at fault when the answer is not a success.

export class ApiError extends Error {
  constructor(status, message, field) {
    super(message);
    this.status = status;
    this.field = field || '';
  }
}

async function answer(response) {
  const type = response.headers.get('Content-Type') || '';
  const body = type.startsWith('application/json') ? await response.json() : await response.text();
  if (!response.ok) {
    const e = body && body.error ? body.error : { message: String(body) };
    throw new ApiError(response.status, e.message || response.statusText, e.field);
  }
  return body;
}

export async function getJson(path) {
  return answer(await fetch(path));
}

export async function postJson(path, body) {
  return answer(await fetch(path, {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  }));
}

export async function deleteJson(path) {
  return answer(await fetch(path, { method: 'DELETE' }));
}

/// URL of a file inside the served folder ('run/maps/x.png').
export function fileUrl(relative) {
  return '/api/files/' + relative.split('/').map(encodeURIComponent).join('/');
}

export const listRuns = () => getJson('/api/runs');
export const describeRun = (path) => getJson('/api/run?path=' + encodeURIComponent(path));
export const frameSurface = (path) => getJson('/api/frame?path=' + encodeURIComponent(path));
export const startJob = (request) => postJson('/api/jobs', request);
export const getJob = (id) => getJson('/api/jobs/' + encodeURIComponent(id));
export const cancelJob = (id) => postJson('/api/jobs/' + encodeURIComponent(id) + '/cancel', {});
export const listJobs = () => getJson('/api/jobs');

/// Polls a job until it ends; `onUpdate(job)` sees every description. Resolves with the last one.
export async function followJob(id, onUpdate, intervalMs = 400) {
  for (;;) {
    const job = await getJob(id);
    onUpdate(job);
    if (job.state !== 'running') return job;
    await new Promise((r) => setTimeout(r, intervalMs));
  }
}
