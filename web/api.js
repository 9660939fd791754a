// Calls to the viewer server's JSON endpoints; a refused request throws its error message.
export async function getJson(path) {
  const response = await fetch(path, { cache: 'no-store' });
  return answer(response);
}

export async function postJson(path, body = {}) {
  const response = await fetch(path, {
    method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(body),
  });
  return answer(response);
}

async function answer(response) {
  const body = await response.json().catch(() => ({}));
  if (!response.ok) throw new Error(body.error || `HTTP ${response.status}`);
  return body;
}
