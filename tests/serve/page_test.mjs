// The page of `knit serve` in headless Chromium (puppeteer-core), against a `knit serve --port 0`
// this script starts and stops: the page loads without console errors; typing a chart shows its
// yarns (the canvas is not blank and its data-yarns equals the server's yarn count for that
// chart); a chart error is underlined at its line and column; a garment loads; the GLB download
// passes the Khronos glTF validator. Prints the edit-to-yarns latency (docs/serve.md).
// Usage: node page_test.mjs --knit KNIT --chromium CHROMIUM --node-modules DIR --work DIR
//        [--screenshot PNG] [--latency-runs N]
// Exit 77 (skipped) when a tool is missing, unless CI=true.
import {spawn} from 'node:child_process';
import fs from 'node:fs';
import path from 'node:path';
import {createRequire} from 'node:module';
import readline from 'node:readline';

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const skip = (why) => {
  console.log(`serve_page: ${why}`);
  process.exit(process.env.CI === 'true' ? 1 : 77);
};
if (!args.chromium || !fs.existsSync(args.chromium)) skip('no Chromium (apt-get install chromium)');
const nodeModules = args['node-modules'];
for (const pkg of ['puppeteer-core', 'gltf-validator', 'three'])
  if (!fs.existsSync(path.join(nodeModules, pkg))) skip(`no ${pkg} in ${nodeModules} (cmake --build build --target ${pkg === 'three' ? 'three_js' : pkg.replace('-', '_')})`);
const require = createRequire(path.resolve(nodeModules, 'noop.js'));
const puppeteer = require('puppeteer-core');
const validator = require('gltf-validator');
fs.mkdirSync(args.work, {recursive: true});

let failures = 0;
const t0 = Date.now();
const check = (ok, what) => {
  console.log(`${ok ? 'ok  ' : 'FAIL'} ${what} [${((Date.now() - t0) / 1000).toFixed(1)} s]`);
  if (!ok) failures++;
};

// The server: its address from its first line.
const server = spawn(args.knit, ['serve', '--port', '0'], {stdio: ['ignore', 'pipe', 'inherit']});
const base = await new Promise((resolve, reject) => {
  readline.createInterface({input: server.stdout}).on('line', (line) => {
    const m = /(http:\/\/127\.0\.0\.1:\d+\/)/.exec(line);
    if (m) resolve(m[1]);
  });
  server.on('exit', (code) => reject(new Error(`knit serve exited with ${code}`)));
});

// The server's own answer for a chart, outside the page.
async function serverYarns(chart) {
  const res = await fetch(base + 'api/swatch', {
    method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify({session: 'test', chart}),
  });
  const lines = (await res.text()).trim().split('\n').map((l) => JSON.parse(l));
  return lines.at(-1).swatch.yarns;
}

const browser = await puppeteer.launch({
  executablePath: args.chromium, headless: true,
  args: ['--no-sandbox', '--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
});
try {
  const page = await browser.newPage();
  const errors = [];
  page.on('console', (m) => { if (m.type() === 'error') errors.push(m.text()); });
  page.on('pageerror', (e) => errors.push(e.message));
  await page.setViewport({width: 1280, height: 800});
  await page.goto(base, {waitUntil: 'load'});
  const yarnsShown = () => page.$eval('#view', (c) => Number(c.dataset.yarns));
  await page.waitForFunction(() => Number(document.getElementById('view').dataset.yarns) > 0, {timeout: 20000});
  check(errors.length === 0, `page loads without console errors ${errors.join(' | ')}`);

  // Typing a chart: its yarns appear, first relaxed at the preview's resolution, then at full
  // detail; the latencies from the last keystroke to each.
  const typeChart = async (text) => {
    await page.click('#chart', {clickCount: 3});
    await page.keyboard.down('Control');
    await page.keyboard.press('a');
    await page.keyboard.up('Control');
    await page.keyboard.press('Backspace');
    await page.evaluate(() => {
      const view = document.getElementById('view');
      view.dataset.yarns = '0';
      delete view.dataset.state;
      delete document.body.dataset.swatchYarns;
    });
    await page.type('#chart', text);
    const typed = Date.now();
    // Relaxed yarns on screen: the preview's or the full relaxation's (data-state).
    await page.waitForFunction(() => {
      const view = document.getElementById('view');
      return Number(view.dataset.yarns) > 0 && (view.dataset.state === 'preview' || view.dataset.state === 'relaxed');
    }, {timeout: 20000, polling: 'raf'});
    const relaxedState = await page.$eval('#view', (c) => c.dataset.state);
    await page.waitForFunction(() => Number(document.getElementById('view').dataset.yarns) > 0 &&
                                     document.getElementById('view').dataset.state === 'relaxed' &&
                                     document.body.dataset.swatchYarns === document.getElementById('view').dataset.yarns,
                               {timeout: 20000, polling: 'raf'});
    return {relaxedState, total: Date.now() - typed};
  };
  // Charts up to 4 x 4, each a new cell for the server (beyond twelve runs they come from memory):
  // knit and purl, a cable, a lace row and the built-in eyelet mesh (bench/serve_bench.cpp has
  // their relaxation CPU).
  const charts = ['k p\nk p', 'k k p p\nk k p p\np p k k\np p k k', 'k p k\np k p\nk p k', 'k p\np k',
                  'k k p p\np k k p\np p k k\nk p p k', 'k k k\np p p\nk p k', 'k p p\np k p\np p k',
                  'k k p p\nk k p p', 'k p k p\np k p k\nk k p p\np p k k', 'c2/2f\nk k k k\nk k k k\nk k k k',
                  'k yo k2tog k\nk k k k', 'k k k k\nk k k2tog yo\nk k k k\nk2tog yo k k'];
  const runs = Number(args['latency-runs'] ?? 1);
  const latencies = [];
  let lastBody = '';
  for (let k = 0; k < runs; k++) {
    const body = charts[k % charts.length];
    const chart = `# run ${k}\n` + body;
    lastBody = body;
    const {relaxedState} = await typeChart(chart);
    const t = await page.evaluate(() => ({...document.body.dataset}));
    console.log(`  ${body.split("\n").join(" / ")}: shown ${t.swatchStates}; first yarns ${t.editToFirstYarnsMs} ms, relaxed yarns (${relaxedState}) ` +
                `${t.editToRelaxedMs} ms, full relaxation ${t.editToYarnsMs} ms after the last edit ` +
                `(request to answer ${t.serverMs} ms)`);
    console.log(`    first relaxed yarns, ms: ${t.relaxedBreakdown}`);
    latencies.push([Number(t.editToFirstYarnsMs), Number(t.editToRelaxedMs), Number(t.editToYarnsMs)]);
    const shown = await yarnsShown();
    check(shown === await serverYarns(chart), `typed chart ${k}: data-yarns ${shown} equals the server's count`);
  }
  // A pause mid-typing: the partial chart (one row) relaxes fully and is drawn; the keystrokes after
  // it mark what is on screen as an older text's at once (data-state=edited), so its yarn count is
  // never read as the whole chart's (a CI run on 2026-11-27 read 59 for `k p / k p` that way).
  {
    await page.click('#chart', {clickCount: 3});
    await page.keyboard.down('Control');
    await page.keyboard.press('a');
    await page.keyboard.up('Control');
    await page.keyboard.press('Backspace');
    await page.type('#chart', '# paused\nk p k p');
    await page.waitForFunction(() => document.body.dataset.swatchYarns, {timeout: 20000, polling: 'raf'});
    const partial = await page.evaluate(() => ({yarns: document.body.dataset.swatchYarns,
                                                state: document.getElementById('view').dataset.state}));
    await page.type('#chart', '\np p k k');
    const after = await page.evaluate(() => ({swatchYarns: document.body.dataset.swatchYarns,
                                              state: document.getElementById('view').dataset.state}));
    check(partial.state === 'relaxed' && after.state === 'edited' && after.swatchYarns === undefined,
          `after a pause mid-typing the partial chart's yarns (${partial.yarns}, ${partial.state}) are marked ` +
          `as an older text's (${after.state}, swatch yarns ${after.swatchYarns})`);
    await page.waitForFunction(() => document.getElementById('view').dataset.state === 'relaxed' &&
                                     document.body.dataset.swatchYarns === document.getElementById('view').dataset.yarns,
                               {timeout: 20000, polling: 'raf'});
    const whole = await yarnsShown();
    const expected = await serverYarns('# paused\nk p k p\np p k k');
    check(whole === expected, `then the whole chart's yarns: data-yarns ${whole} equals the server's count ${expected}`);
    lastBody = 'k p k p\np p k k';  // the chart on the page now, recoloured below
  }
  console.log('edit-to-yarns latency (ms, last edit to first / relaxed (preview) / fully relaxed yarns drawn): ' +
              latencies.map((l) => l.join('/')).join(' '));
  // Not blank: the canvas has many pixels away from the background colour.
  const lit = await page.evaluate(() => {
    const c = document.getElementById('view');
    const copy = Object.assign(document.createElement('canvas'), {width: c.width, height: c.height});
    const g = copy.getContext('2d');
    g.drawImage(c, 0, 0);
    const d = g.getImageData(0, 0, copy.width, copy.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 0x20) + Math.abs(d[i + 1] - 0x24) + Math.abs(d[i + 2] - 0x2b) > 40) n++;
    return n / (d.length / 4);
  });
  check(lit > 0.05, `the canvas is not blank (${(100 * lit).toFixed(1)}% of pixels show yarn)`);
  // A chart error: underlined at its line and column, shown as LINE:COLUMN: message.
  await page.evaluate(() => { delete document.body.dataset.swatchYarns; });
  await page.click('#chart');
  await page.keyboard.type('\nk q');
  await page.waitForSelector('.error-mark', {timeout: 10000});
  const mark = await page.$eval('.error-mark', (m) => ({line: m.dataset.line, column: m.dataset.column, text: m.textContent}));
  const message = await page.$eval('#chart-error', (e) => e.textContent);
  const lines = (await page.$eval('#chart', (t) => t.value)).split('\n');
  check(mark.line === String(lines.length) && mark.column === '3' && mark.text === 'q',
        `the error is underlined at line ${mark.line}, column ${mark.column} ('${mark.text}')`);
  check(message.startsWith(`${lines.length}:3: unknown stitch 'q'`), `the message reads "${message}"`);
  for (let k = 0; k < 4; k++) await page.keyboard.press('Backspace');  // back to the valid chart
  await page.waitForFunction(() => !document.querySelector('.error-mark') && document.body.dataset.swatchYarns,
                             {timeout: 10000});

  // A colour-only edit of the same stitches is not relaxed again (the server keeps relaxations
  // by cell): its yarns come fully relaxed at once, with the new colour.
  const colourRows = lastBody.split('\n').map((row) => row.split(' ').map(() => 'A').join(' ')).join('\n');
  await page.evaluate((colours) => {
    for (const key of ['editToYarnsMs', 'swatchYarns', 'swatchStates']) delete document.body.dataset[key];
    const chart = document.getElementById('chart');
    chart.value = chart.value.replace(/^# run \d+\n/, '# recoloured\n') + `\n\n${colours}\nA=#c8553d\n`;
    chart.dispatchEvent(new Event('input'));
  }, colourRows);
  await page.waitForFunction(() => document.body.dataset.editToYarnsMs && document.body.dataset.swatchYarns,
                             {timeout: 20000, polling: 'raf'});
  const recoloured = await page.evaluate(() => ({...document.body.dataset}));
  check(recoloured.swatchStates === 'relaxed' && recoloured.swatchYarns === String(await yarnsShown()),
        `a colour-only edit shows only the fully relaxed yarns (shown: ${recoloured.swatchStates}), ` +
        `${recoloured.editToYarnsMs} ms after the edit`);

  // The garment: the drape with the chart, its yarn count as the server reported it.
  await page.click('input[name=mode][value=garment]');
  await page.waitForFunction(() => document.body.dataset.garmentYarns &&
                                   document.getElementById('view').dataset.yarns === document.body.dataset.garmentYarns,
                             {timeout: 60000});
  check(await yarnsShown() > 0, `the garment loads (${await yarnsShown()} yarn pieces)`);

  // The GLB download, as the page asks for it, through the glTF validator.
  const glb = await page.evaluate(async () => {
    const body = {session: 'dl', chart: document.getElementById('chart').value, mesh: 'plane', repeats: [6, 6], format: 'glb'};
    const res = await fetch('/api/download', {method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body)});
    return {status: res.status, disposition: res.headers.get('Content-Disposition'), bytes: Array.from(new Uint8Array(await res.arrayBuffer()))};
  });
  check(glb.status === 200 && /knit-garment\.glb/.test(glb.disposition), `the GLB download answers ${glb.status} ${glb.disposition}`);
  const file = path.join(args.work, 'download.glb');
  fs.writeFileSync(file, Buffer.from(glb.bytes));
  const report = await validator.validateBytes(new Uint8Array(glb.bytes));
  check(report.issues.numErrors === 0, `the downloaded GLB (${glb.bytes.length} bytes) passes the glTF validator: ` +
        `${report.issues.numErrors} errors, ${report.issues.numWarnings} warnings`);
  if (args.screenshot) {
    // For docs/serve.md: a striped rib, the page at 1280 x 800 saved at half scale (a small PNG).
    await page.click('input[name=mode][value=swatch]');
    await page.evaluate(() => {
      const chart = document.getElementById('chart');
      chart.value = '# 1x1 rib in two-row stripes\nk p\nk p\nk p\nk p\n\nB B\nB B\nA A\nA A\nA=#c8553d B=#2a6f97\n';
      delete document.body.dataset.swatchYarns;
      chart.dispatchEvent(new Event('input'));
    });
    await page.waitForFunction(() => document.body.dataset.swatchYarns, {timeout: 30000});
    await page.setViewport({width: 1280, height: 800, deviceScaleFactor: 0.5});
    await new Promise((r) => setTimeout(r, 500));
    await page.screenshot({path: args.screenshot});
    await page.setViewport({width: 1280, height: 800});
  }

  // The chart error's answer (422) is the one resource error Chromium may log.
  const unexpected = errors.filter((e) => !/status of 422/.test(e));
  check(unexpected.length === 0, `no other console errors in the whole session ${unexpected.join(' | ')}`);
} finally {
  await browser.close();
  server.kill('SIGINT');
}
const code = await new Promise((resolve) => server.on('exit', (c) => resolve(c)));
check(code === 0, `knit serve stopped cleanly on SIGINT (exit ${code})`);
process.exit(failures ? 1 : 0);
