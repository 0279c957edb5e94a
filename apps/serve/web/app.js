// app.js — the page: the chart editor drives a debounced live swatch (the server relaxes the
// chart and streams the yarns); the garment view, palette, gauge, uploads and downloads.
import {postStream, getJson, download, uploadMesh} from './api.js';
import {ChartEditor} from './editor.js';
import {KnitView} from './view3d.js';

const $ = (id) => document.getElementById(id);
const session = 'p' + Math.random().toString(36).slice(2, 12);
const editor = new ChartEditor($('chart'), $('chart-marks'), $('chart-error'));
const view = new KnitView($('view'));
const status = (text) => { $('status').textContent = text; };
let mode = 'swatch';
let swatchRequest = null, garmentRequest = null;
let framed = false, garmentFramed = false;
let garmentTimer = 0;

function showWarnings(list) {
  $('warnings').replaceChildren(...(list ?? []).map((w) => Object.assign(document.createElement('li'), {textContent: w})));
}

function refreshPalette() {
  const box = $('palette');
  const colours = editor.palette();
  box.replaceChildren(...Object.entries(colours).map(([letter, hex]) => {
    const label = document.createElement('label');
    const input = Object.assign(document.createElement('input'), {type: 'color', value: hex.toLowerCase()});
    input.setAttribute('aria-label', `colour ${letter}`);
    input.addEventListener('change', () => { editor.setColour(letter, input.value); changed(); });
    label.append(letter, input);
    return label;
  }));
  $('add-colour').hidden = Object.keys(colours).length > 0;
}

// The swatch: relaxed on the server, intermediate cells shown as they arrive, then the preview
// (the chart relaxed at half the samples per stitch, at rest), then the full relaxation.
// canvas#view's data-state says which: relaxing, preview or relaxed; `edited` from a keystroke
// until the newer text's first yarns are drawn (what is on screen is an older text's).
async function updateSwatch() {
  swatchRequest?.abort();
  const controller = swatchRequest = new AbortController();
  const started = performance.now();
  const edited = lastEdit;
  const shown = {first: false, relaxed: false};
  const states = [];
  for (const key of ['editToFirstYarnsMs', 'editToRelaxedMs', 'editToYarnsMs', 'relaxedBreakdown']) delete document.body.dataset[key];
  // Measured on the page: the last edit to the animation frame that draws the yarns (view.draw()
  // renders in the next frame, before this callback; docs/serve.md).
  const stamp = (key, then) => requestAnimationFrame(() => {
    if (controller.signal.aborted) return;
    document.body.dataset[key] = String(Math.round(performance.now() - edited));
    then?.();
  });
  // Where the time to the first relaxed yarns went (ms): the debounce, the request to its line
  // complete on the page (the server's part of it in `server`), parsing it, building the tubes, and
  // the frame that draws them (relaxedBreakdown, printed by tests/serve/page_test.mjs): the wait for
  // that animation frame (long when the GPU thread still rasterises an earlier frame) and the render.
  const breakdown = (line, times, built) => {
    const ms = (a, b) => Math.round(b - a);
    const drawn = performance.now();
    const t = line.server_ms;
    const server = t ? ` (server ${t.total}: relax ${t.relax}, swatch ${t.swatch}; ${times.bytes} bytes)` : '';
    document.body.dataset.relaxedBreakdown =
        `debounce ${ms(edited, started)} request ${ms(started, times.received)}${server} ` +
        `parse ${ms(times.received, times.parsed)} build ${ms(times.parsed, built)} draw ${ms(built, drawn)}` +
        ` (frame ${ms(built, view.lastRender.start)} render ${ms(view.lastRender.start, view.lastRender.end)})`;
  };
  const show = (swatch, state, line, times) => {
    if (mode !== 'swatch') return;
    view.showSwatch(swatch, !framed);
    const built = performance.now();
    framed = true;
    $('view').dataset.state = state;
    if (states.at(-1) !== state) states.push(state);
    document.body.dataset.swatchStates = states.join(' ');
    if (!shown.first) { shown.first = true; stamp('editToFirstYarnsMs'); }
    if (state !== 'relaxing' && !shown.relaxed) {
      shown.relaxed = true;
      stamp('editToRelaxedMs', () => breakdown(line, times, built));
    }
  };
  status('relaxing…');
  try {
    let lastTimes = null;
    const last = await postStream('/api/swatch', {session, chart: editor.text}, (line, times) => {
      lastTimes = times;
      if (controller.signal.aborted) return;
      if (line.type === 'step') {
        status(line.stage === 'preview' ? `relaxing… iteration ${line.iteration}`
                                        : `preview shown; relaxing at full detail… iteration ${line.iteration}`);
        if (line.swatch) show(line.swatch, 'relaxing');
      } else if (line.type === 'preview') {
        editor.setError(null);
        showWarnings(line.warnings);
        show(line.swatch, 'preview', line, times);
        status(`preview: relaxed at ${line.stats.samples_per_stitch} samples per stitch in ` +
               `${line.stats.iterations} iterations; relaxing at full detail…`);
      }
    }, controller.signal);
    if (controller.signal.aborted) return;
    if (last.type === 'done') {
      editor.setError(null);
      showWarnings(last.warnings);
      show(last.swatch, 'relaxed', last, lastTimes);
      stamp('editToYarnsMs');
      await new Promise(requestAnimationFrame);
      if (controller.signal.aborted) return;  // edited while the frame was drawn
      document.body.dataset.serverMs = String(Math.round(performance.now() - started));
      document.body.dataset.swatchYarns = String(last.swatch.yarns);
      status(`${last.swatch.yarns} yarns, ${last.stats.width} × ${last.stats.height} stitches, ` +
             `${last.stats.iterations} iterations; shown ${Math.round(performance.now() - started)} ms after the request`);
      if (mode === 'garment') scheduleGarment(0);
    } else if (last.type === 'error') {
      if (last.line) editor.setError(last); else status(last.error);
    }
  } catch (e) {
    if (e.name !== 'AbortError') status(String(e));
  }
}

function garmentBody() {
  const body = {session, chart: editor.text, mesh: $('mesh').value};
  const gauge = $('gauge').value.trim();
  if (gauge) body.gauge = gauge;
  if (garmentFramed) body.view = view.view();
  return body;
}

async function updateGarment() {
  garmentRequest?.abort();
  const controller = garmentRequest = new AbortController();
  status('building the garment…');
  try {
    const last = await postStream('/api/garment', garmentBody(), (line) => {
      if (line.type === 'stage') status(`building the garment: ${line.stage}`);
    }, controller.signal);
    if (controller.signal.aborted) return;
    if (last.type === 'done') {
      await view.showGarment(last.result, last.yarns, garmentFramed ? null : last.camera);
      garmentFramed = true;
      document.body.dataset.garmentYarns = String(last.yarns);
      showWarnings(last.warnings);
      status(`garment: ${last.yarns} yarn pieces, ${(last.bytes / 1048576).toFixed(1)} MB, ` +
             `${last.culled_cells} of ${last.cells} cells culled for this view`);
    } else if (last.type === 'error') {
      if (last.line) editor.setError(last); else status(last.error);
    }
  } catch (e) {
    if (e.name !== 'AbortError') status(String(e));
  }
}

function scheduleGarment(delay) {
  clearTimeout(garmentTimer);
  garmentTimer = setTimeout(updateGarment, delay);
}

let editTimer = 0, lastEdit = 0;
function changed() {
  lastEdit = performance.now();
  // The older text's answer is dropped now, not when the debounce ends: its preview arriving in
  // between would be drawn (software WebGL holds the main thread) and delay the newer request.
  // Closing its stream also makes the server cancel its job at its next line.
  swatchRequest?.abort();
  // The yarns on screen are now an older text's: nothing may read them as this text's (the
  // count and data-state of a partial chart relaxed between two keystrokes did, 2026-11-27).
  if (mode === 'swatch') $('view').dataset.state = 'edited';
  delete document.body.dataset.swatchYarns;
  refreshPalette();
  clearTimeout(editTimer);
  editTimer = setTimeout(updateSwatch, 40);  // debounced: the newest text wins
}

async function start() {
  const info = await getJson('/api/info');
  const builtin = $('builtin');
  for (const c of info.charts) builtin.append(new Option(c.name.replace(/^chart:/, ''), c.text));
  for (const m of info.meshes) $('mesh').append(new Option(m, m));
  $('mesh').value = info.meshes.includes('drape') ? 'drape' : info.meshes[0];
  builtin.addEventListener('change', () => { editor.text = builtin.value; editor.setError(null); changed(); });
  $('chart').addEventListener('input', changed);
  $('add-colour').addEventListener('click', () => { if (editor.addColourLayer()) changed(); });
  $('light').addEventListener('change', () => view.setBackLight($('light').value === 'back'));
  $('gauge').addEventListener('change', () => { if (mode === 'garment') scheduleGarment(0); });
  $('mesh').addEventListener('change', () => { garmentFramed = false; if (mode === 'garment') scheduleGarment(0); });
  for (const radio of document.querySelectorAll('input[name=mode]')) {
    radio.addEventListener('change', () => {
      mode = radio.value;
      if (mode === 'garment') scheduleGarment(0); else { framed = false; updateSwatch(); }
    });
  }
  // The garment is rebuilt for the new camera once it stops moving (view-driven detail).
  view.controls.addEventListener('end', () => { if (mode === 'garment') scheduleGarment(600); });
  $('upload').addEventListener('change', async () => {
    const file = $('upload').files[0];
    if (!file) return;
    try {
      const m = await uploadMesh(file);
      $('mesh').append(new Option(`${m.name} (${m.triangles} triangles)`, m.mesh));
      $('mesh').value = m.mesh;
      garmentFramed = false;
      status(`uploaded ${m.name}: ${m.vertices} vertices, ${m.triangles} triangles`);
      if (mode === 'garment') scheduleGarment(0);
    } catch (e) {
      status(`upload refused: ${e.message}`);
    }
  });
  for (const button of document.querySelectorAll('[data-download]')) {
    button.addEventListener('click', async () => {
      try {
        status(`downloading .${button.dataset.download}…`);
        const body = garmentBody();
        body.format = button.dataset.download;
        status(`saved ${await download(body)}`);
      } catch (e) {
        status(`download refused: ${e.message}`);
      }
    });
  }
  editor.text = info.charts.find((c) => c.name === 'chart:stockinette')?.text ?? info.charts[0].text;
  builtin.value = editor.text;
  changed();
}

start();
