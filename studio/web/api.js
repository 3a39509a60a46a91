// The studio's HTTP API (docs/studio.md, "HTTP API"): one function per route.
// Every failure becomes an ApiError carrying the status and the server's message.

export class ApiError extends Error {
  constructor(status, message, body) {
    super(message);
    this.status = status;
    this.body = body || {};
  }
}

async function request(method, url, body) {
  const init = { method, headers: {} };
  if (body !== undefined) {
    init.headers['Content-Type'] = 'application/json';
    init.body = JSON.stringify(body);
  }
  let response;
  try {
    response = await fetch(url, init);
  } catch (e) {
    throw new ApiError(0, `the studio server does not answer (${e.message})`);
  }
  const text = await response.text();
  let json = {};
  try {
    json = text ? JSON.parse(text) : {};
  } catch (e) {
    if (response.ok) throw new ApiError(response.status, `bad JSON from ${url}`);
  }
  if (!response.ok) {
    const message = json.error || `${method} ${url}: HTTP ${response.status}`;
    throw new ApiError(response.status, message, json);
  }
  return json;
}

const film = (id) => `/api/films/${encodeURIComponent(id)}`;

export const api = {
  films: () => request('GET', '/api/films'),
  film: (id) => request('GET', film(id)),
  curves: (id, from, to, points) =>
    request('GET', `${film(id)}/curves?from=${from.toFixed(4)}&to=${to.toFixed(4)}&points=${points}`),
  track: (id, from, to) =>
    request('GET', `${film(id)}/track?from=${from.toFixed(4)}&to=${to.toFixed(4)}`),
  edits: (id) => request('GET', `${film(id)}/edits`),
  saveEdits: (id, edits) => request('PUT', `${film(id)}/edits`, edits),
  exportFilm: (id, kind) => request('POST', `${film(id)}/export`, { kind }),
  job: (jobId) => request('GET', `/api/jobs/${encodeURIComponent(jobId)}`),
};

// The video URL answers 202 {progress, eta_s} while the server makes an H.264
// proxy; null when the video is ready to play.
export async function videoPending(url) {
  const response = await fetch(url, { headers: { Range: 'bytes=0-0' } });
  if (response.status !== 202) return null;
  try {
    return await response.json();
  } catch (e) {
    return { progress: 0 };
  }
}
