// api.js — the server's JSON API (docs/serve.md): plain requests and streamed jobs (one JSON
// object per line, read as they arrive).

// Posts `body` as JSON; calls onLine(obj, times) for every line of a streamed answer, times
// {received, parsed, bytes} (performance.now() when the line was complete and when it was parsed,
// and its length).
// Resolves with the last line; an HTTP error before the stream resolves with its JSON and `status`.
export async function postStream(path, body, onLine, signal) {
  const res = await fetch(path, {
    method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body), signal,
  });
  if (!res.ok) return {type: 'error', status: res.status, ...(await res.json())};
  const reader = res.body.getReader();
  const decoder = new TextDecoder();
  let buffered = '';
  let last = null;
  for (;;) {
    const {value, done} = await reader.read();
    if (done) break;
    buffered += decoder.decode(value, {stream: true});
    let newline;
    while ((newline = buffered.indexOf('\n')) >= 0) {
      const line = buffered.slice(0, newline);
      buffered = buffered.slice(newline + 1);
      if (!line) continue;
      const received = performance.now();
      last = JSON.parse(line);
      onLine(last, {received, parsed: performance.now(), bytes: line.length});
    }
  }
  return last ?? {type: 'error', status: 0, error: 'the server closed the answer early'};
}

export async function getJson(path) {
  const res = await fetch(path);
  return res.json();
}

// A download: POST, then save the answer under the server's file name.
export async function download(body) {
  const res = await fetch('/api/download', {
    method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body),
  });
  if (!res.ok) throw new Error((await res.json()).error);
  const name = /filename="([^"]+)"/.exec(res.headers.get('Content-Disposition') ?? '')?.[1] ?? 'knit-download';
  const url = URL.createObjectURL(await res.blob());
  const a = document.createElement('a');
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10000);
  return name;
}

export async function uploadMesh(file) {
  const res = await fetch('/api/mesh?name=' + encodeURIComponent(file.name), {
    method: 'POST', headers: {'Content-Type': 'application/octet-stream'}, body: file,
  });
  const json = await res.json();
  if (!res.ok) throw new Error(json.error);
  return json;
}
