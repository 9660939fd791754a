// Calls to the viewer server's JSON endpoints; a refused request throws its error message.
// Requests that change anything carry the per-launch token of the page's URL (?token=...),
// which glint printed: the server refuses them without it (README "Viewer").
const token = new URLSearchParams(window.location.search).get('token') || '';

export async function getJson(path) {
  const response = await fetch(path, { cache: 'no-store' });
  return answer(response);
}

export async function postJson(path, body = {}) {
  const response = await fetch(path, {
    method: 'POST',
    headers: { 'Content-Type': 'application/json', 'X-Glint-Token': token },
    body: JSON.stringify(body),
  });
  return answer(response);
}

async function answer(response) {
  const body = await response.json().catch(() => ({}));
  if (!response.ok) throw new Error(body.error || `HTTP ${response.status}`);
  return body;
}
