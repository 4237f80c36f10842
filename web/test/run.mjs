#!/usr/bin/env node
// Browser test of the lrmesh web viewer, driven with playwright-core in headless Chromium.
//
//   node web/test/run.mjs --url http://127.0.0.1:PORT/ --expect EXPECT.json --out OUTDIR
//
// EXPECT.json (written by web/test.sh):
//   { "meshes": [ { "path", "name", "info": {lrmesh info --json of the container shown},
//                   "screenshots": true } ],
//     "saveKinds": ["edgebreaker", ...],
//     "bench": [ { "url", "name", "nativeMs", "triangles" } ] }
//
// Prints one line per check (`ok - …` or `not ok - …: details`), then `N passed, M failed`;
// writes the same to OUTDIR/browser-results.json and exits 1 if any check failed.

import fs from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { asSet, buildCornerTable, sameSet } from './oracle.mjs';

const LOAD_TIMEOUT_MS = 300000; // a 1M-triangle mesh encoded in the page under SwiftShader
const SAVE_TIMEOUT_MS = 120000;
const BENCH_RUNS = 5;
// The speed the issue asked for (WebAssembly at least 0.5x native). Timing is measured and
// reported, never asserted: on a shared 2-core machine one slow minute would fail the suite.
const BENCH_TARGET_RATIO = 0.5;
const BACKGROUND = [43, 46, 54]; // gl.js's clear colour, in bytes (0.17, 0.18, 0.21)

function parseArgs(argv) {
  const args = {};
  for (let i = 0; i < argv.length; i++) {
    const flag = argv[i];
    if (!['--url', '--expect', '--out'].includes(flag) || i + 1 >= argv.length) {
      throw new Error(`usage: run.mjs --url URL --expect EXPECT.json --out OUTDIR (at ${flag})`);
    }
    args[flag.slice(2)] = argv[++i];
  }
  for (const key of ['url', 'expect', 'out']) {
    if (!args[key]) throw new Error(`missing --${key}`);
  }
  return args;
}

const checks = [];
const benchResults = [];

function check(name, ok, details = '') {
  checks.push({ name, ok: Boolean(ok), details: ok ? '' : String(details) });
  console.log(ok ? `ok - ${name}` : `not ok - ${name}: ${details}`);
  return Boolean(ok);
}

const num = (text) => Number(String(text).replace(/[^0-9.-]/g, ''));
const short = (list, n = 40) => (list.length > n ? `[${list.slice(0, n).join(' ')} … (${list.length})]` : `[${list.join(' ')}]`);

// ---------------------------------------------------------------------------------------

async function main() {
  let args;
  try {
    args = parseArgs(process.argv.slice(2));
  } catch (e) {
    console.error(e.message);
    console.log('0 passed, 1 failed');
    process.exit(2);
  }
  const out = path.resolve(args.out);
  fs.mkdirSync(out, { recursive: true });
  const expect = JSON.parse(fs.readFileSync(path.resolve(args.expect), 'utf8'));

  let browser = null;
  try {
    browser = await chromium.launch({
      executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
      args: ['--use-gl=angle', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox'],
    });
  } catch (e) {
    check('browser launches', false, e.message.split('\n')[0]);
  }
  if (browser) {
    try {
      await runPage(browser, args.url, expect, out);
    } catch (e) {
      check('test driver runs to the end', false, e.stack || e.message);
    } finally {
      await browser.close().catch(() => {});
    }
  }

  const passed = checks.filter((c) => c.ok).length;
  const failed = checks.length - passed;
  fs.writeFileSync(
    path.join(out, 'browser-results.json'),
    `${JSON.stringify({ passed, failed, checks, bench: benchResults }, null, 2)}\n`,
  );
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

async function runPage(browser, url, expect, out) {
  const context = await browser.newContext({ viewport: { width: 1200, height: 800 }, acceptDownloads: true });
  const page = await context.newPage();
  const problems = [];
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('console', (message) => {
    if (message.type() === 'error') problems.push(`console error: ${message.text()}`);
  });

  await page.goto(url);
  const start = await page.evaluate(async () => {
    // viewer.js is a module: wait for it to define window.viewer, then for lrmesh.ready().
    for (let i = 0; i < 600 && !window.viewer; i++) await new Promise((r) => setTimeout(r, 50));
    if (!window.viewer) return { error: 'window.viewer was never defined' };
    try {
      await window.viewer.ready;
    } catch (e) {
      return { error: String((e && e.message) || e) };
    }
    return {
      status: document.getElementById('status').textContent,
      lastError: window.viewer.lastError,
      module: typeof window.lrmesh === 'object' && typeof window.lrmesh.decodeBench === 'function',
    };
  });
  const started = check(
    'page starts: viewer.ready resolves, #status reads "ready"',
    !start.error && start.status === 'ready' && !start.lastError && start.module,
    start.error || `status "${start.status}", lastError ${start.lastError}, window.lrmesh ${start.module ? 'set' : 'missing'}`,
  );
  if (started) {
    for (const mesh of expect.meshes || []) {
      await testMesh(page, mesh, expect.saveKinds || [], out);
    }
    for (const entry of expect.bench || []) {
      await testBench(page, entry);
    }
  }
  check('no page errors or console errors', problems.length === 0, problems.join(' | '));
  await context.close();
}

// ---------------------------------------------------------------------------------------

async function testMesh(page, mesh, saveKinds, out) {
  const { name, info } = mesh;
  await page.evaluate(() => {
    window.__previousFile = window.viewer.file;
    window.viewer.lastError = null;
  });
  await page.setInputFiles('#file', mesh.path);
  const loaded = await page
    .waitForFunction(
      (expected) => {
        const v = window.viewer;
        if (v.lastError) return { error: v.lastError };
        const status = document.getElementById('status').textContent;
        return v.file && v.file !== window.__previousFile && status === `loaded ${expected}` ? { ok: true } : false;
      },
      name,
      { timeout: LOAD_TIMEOUT_MS, polling: 100 },
    )
    .then((handle) => handle.jsonValue())
    .catch((e) => ({ error: `timed out: ${e.message.split('\n')[0]}` }));
  if (!check(`${name}: loads through the file input, #status reads "loaded ${name}"`, loaded.ok, loaded.error)) return;

  const shown = await page.evaluate(() => {
    const text = (id) => document.querySelector(`[data-testid="${id}"]`).textContent.trim();
    return {
      kind: text('kind'),
      vertices: text('vertices'),
      triangles: text('triangles'),
      tags: [...document.querySelectorAll('#sections tbody tr')].map((row) => row.cells[0].textContent),
    };
  });
  check(`${name}: kind is ${info.connectivity}`, shown.kind === info.connectivity, `page shows "${shown.kind}"`);
  check(`${name}: ${info.vertices} vertices`, num(shown.vertices) === info.vertices, `page shows "${shown.vertices}"`);
  check(`${name}: ${info.triangles} triangles`, num(shown.triangles) === info.triangles, `page shows "${shown.triangles}"`);
  const tags = (info.sections || []).map((s) => s.tag);
  check(`${name}: sections table lists ${tags.join(' ')}`, shown.tags.join(' ') === tags.join(' '), `page lists ${shown.tags.join(' ')}`);

  await testModes(page, mesh, out);
  await testPick(page, mesh, out);
  for (const kind of saveKinds) await testSave(page, mesh, kind, out);
}

// Share of canvas pixels that differ from the background, and distinct colours among them.
async function canvasCoverage(page) {
  return page.evaluate((background) => {
    const canvas = document.getElementById('view');
    const copy = document.createElement('canvas');
    copy.width = canvas.width;
    copy.height = canvas.height;
    const context = copy.getContext('2d');
    context.drawImage(canvas, 0, 0);
    const data = context.getImageData(0, 0, copy.width, copy.height).data;
    let covered = 0;
    const colours = new Set();
    for (let i = 0; i < data.length; i += 4) {
      const d = Math.abs(data[i] - background[0]) + Math.abs(data[i + 1] - background[1]) + Math.abs(data[i + 2] - background[2]);
      if (d > 12) {
        covered++;
        // Hue-ish key: shading scales the colour, so compare proportions.
        const s = data[i] + data[i + 1] + data[i + 2] || 1;
        colours.add(`${Math.round((8 * data[i]) / s)},${Math.round((8 * data[i + 1]) / s)}`);
      }
    }
    return { share: covered / (data.length / 4), colours: colours.size };
  }, BACKGROUND);
}

async function testModes(page, mesh, out) {
  const { name, info } = mesh;
  const hasRings = ['lr', 'lr-compact', 'zipper'].includes(info.connectivity);
  const expected = {
    shaded: true,
    ring: hasRings,
    class: hasRings,
    attribute: (info.attributes || []).length > 0,
  };
  const legendRules = {
    shaded: (t) => /shaded/i.test(t),
    ring: (t) => t.includes('ring start') && t.includes('ring end'),
    class: (t) => ['T1 left', 'T1 right', 'T2', 'T2 wart', 'T0', 'T0 wart'].every((c) => t.includes(c)),
    attribute: (t) => /attribute/i.test(t),
  };
  for (const mode of Object.keys(expected)) {
    const enabled = await page.$eval(`#color-mode option[value="${mode}"]`, (o) => !o.disabled);
    check(`${name}: colour mode ${mode} ${expected[mode] ? 'enabled' : 'disabled'}`, enabled === expected[mode], `it is ${enabled ? 'enabled' : 'disabled'}`);
    if (!enabled || !mesh.screenshots) continue;
    await page.selectOption('#color-mode', mode);
    const state = await page.evaluate(() => ({
      mode: window.viewer.mode,
      legend: document.getElementById('legend').textContent,
      lastError: window.viewer.lastError,
    }));
    check(`${name}: legend matches mode ${mode}`, state.mode === mode && legendRules[mode](state.legend) && !state.lastError,
      `mode ${state.mode}, legend "${state.legend}", error ${state.lastError}`);
    const coverage = await canvasCoverage(page);
    // Ring and class modes draw several colours; shaded one (its shades have one proportion).
    const enoughColours = mode === 'ring' || mode === 'class' ? coverage.colours >= 2 : true;
    check(`${name}: canvas shows the mesh in mode ${mode}`, coverage.share > 0.002 && enoughColours,
      `${(100 * coverage.share).toFixed(2)}% of pixels drawn, ${coverage.colours} colours`);
    await page.screenshot({ path: path.join(out, `${name}-${mode}.png`), fullPage: true });
  }
}

async function testPick(page, mesh, out) {
  const { name } = mesh;
  await page.evaluate(() => {
    window.viewer.selection = undefined; // a click sets it to a selection or null
  });
  const box = await page.locator('#view').boundingBox();
  await page.mouse.click(box.x + box.width / 2, box.y + box.height / 2);
  let selection = await page.evaluate(() => window.viewer.selection);
  check(`${name}: a click on the canvas picks (selection set, or null on background)`, selection !== undefined, 'viewer.selection untouched by the click');
  let where = 'click at the canvas centre';
  if (!selection) {
    // The centre may be a hole (a torus): try points around it.
    search: for (const r of [0.08, 0.15, 0.25, 0.35]) {
      for (let a = 0; a < 8; a++) {
        const x = box.width / 2 + r * box.width * Math.cos((a * Math.PI) / 4);
        const y = box.height / 2 + r * box.height * Math.sin((a * Math.PI) / 4);
        selection = await page.evaluate(([px, py]) => window.viewer.pickAt(px, py), [x, y]);
        if (selection) {
          where = `viewer.pickAt(${Math.round(x)}, ${Math.round(y)})`;
          break search;
        }
      }
    }
  }
  if (!check(`${name}: picks a triangle (${where})`, selection, 'background everywhere tried')) return;

  const data = await page.evaluate(() => {
    const file = window.viewer.file;
    const s = window.viewer.selection;
    return {
      triangles: Array.from(file.triangles()),
      ids: Array.from(file.triangleIds()),
      opposites: s.corners.map((c) => {
        const o = Number(file.opposite(c));
        return o < 0 ? null : { corner: o, triangle: Number(file.triangleOf(o)), vertex: Number(file.vertex(o)) };
      }),
      text: document.getElementById('selection').textContent,
    };
  });
  const table = buildCornerTable(data.triangles, data.ids);
  const i = selection.index;
  check(`${name}: picked triangle ${selection.triangle} is triangleIds()[${i}]`, data.ids[i] === selection.triangle, `triangleIds()[${i}] = ${data.ids[i]}`);
  const listed = [0, 1, 2].map((k) => table.vertexOf(3 * i + k));
  check(`${name}: picked vertices ${selection.vertices.join(' ')} are those of triangles()`,
    listed.every((v, k) => v === selection.vertices[k]), `triangles() gives ${listed.join(' ')}`);
  check(`${name}: #selection shows triangle ${selection.triangle}`, data.text.includes(String(selection.triangle)), data.text);
  for (let k = 0; k < 3; k++) {
    const v = selection.vertices[k];
    const oracle = table.starTriangleIds(v);
    check(`${name}: star of vertex ${v} matches the oracle (${oracle.length} triangles)`, sameSet(selection.stars[k], oracle),
      `page ${short(asSet(selection.stars[k]))}, oracle ${short(oracle)}`);
  }
  for (let k = 0; k < 3; k++) {
    const c = selection.corners[k];
    const oc = table.opposite(3 * i + k);
    const want = oc < 0 ? -1 : table.triangleIdOf(oc);
    const got = data.opposites[k];
    const ok = oc < 0 ? got === null : got !== null && got.triangle === want && got.vertex === table.vertexOf(oc);
    check(`${name}: opposite of corner ${c} is in triangle ${want}`, ok,
      got ? `file.opposite gives corner ${got.corner} of triangle ${got.triangle}, vertex ${got.vertex}${oc >= 0 ? ` (oracle vertex ${table.vertexOf(oc)})` : ''}` : 'file.opposite gives -1');
  }
  if (mesh.screenshots) await page.screenshot({ path: path.join(out, `${name}-pick.png`), fullPage: true });
}

async function testSave(page, mesh, kind, out) {
  const { name, info } = mesh;
  const fileName = `${name}.${kind}.lrm`;
  const target = path.join(out, fileName);
  await page.selectOption('#save-kind', kind);
  await page.evaluate(() => {
    window.viewer.lastError = null;
  });
  let download;
  try {
    [download] = await Promise.all([
      page.waitForEvent('download', { timeout: SAVE_TIMEOUT_MS }),
      page.click('#save'),
    ]);
    await download.saveAs(target);
  } catch (e) {
    const lastError = await page.evaluate(() => window.viewer.lastError);
    check(`${name}: save ${kind} downloads ${fileName}`, false, lastError || e.message.split('\n')[0]);
    return;
  }
  const size = fs.existsSync(target) ? fs.statSync(target).size : 0;
  const suggested = download.suggestedFilename();
  if (!check(`${name}: save ${kind} downloads ${fileName} (${size} bytes)`, size > 0 && suggested === fileName,
    `suggested name ${suggested}, ${size} bytes`)) return;
  const reopened = await page.evaluate((base64) => {
    const binary = atob(base64);
    const bytes = new Uint8Array(binary.length);
    for (let j = 0; j < binary.length; j++) bytes[j] = binary.charCodeAt(j);
    try {
      const file = window.lrmesh.open(bytes);
      const fileInfo = JSON.parse(file.infoJson());
      const result = { kind: file.kind(), triangles: fileInfo.triangles, vertices: fileInfo.vertices };
      file.free();
      return result;
    } catch (e) {
      return { error: String((e && e.message) || e) };
    }
  }, fs.readFileSync(target).toString('base64'));
  check(`${name}: ${fileName} opens as ${kind} with ${info.triangles} triangles and ${info.vertices} vertices`,
    !reopened.error && reopened.kind === kind && reopened.triangles === info.triangles && reopened.vertices === info.vertices,
    reopened.error || `${reopened.kind}, ${reopened.triangles} triangles, ${reopened.vertices} vertices`);
}

async function testBench(page, entry) {
  const result = await page.evaluate(
    async ({ url, runs }) => {
      try {
        const response = await fetch(url);
        if (!response.ok) return { error: `fetch ${url}: HTTP ${response.status}` };
        const bytes = new Uint8Array(await response.arrayBuffer());
        const ms = Number(window.lrmesh.decodeBench(bytes, runs));
        const file = window.lrmesh.open(bytes);
        const triangles = file.triangleCount();
        file.free();
        return { ms, triangles };
      } catch (e) {
        return { error: String((e && e.message) || e) };
      }
    },
    { url: entry.url, runs: BENCH_RUNS },
  );
  if (result.error) {
    check(`bench ${entry.name}`, false, result.error);
    return;
  }
  const ratio = entry.nativeMs / result.ms;
  benchResults.push({ name: entry.name, wasmMs: result.ms, nativeMs: entry.nativeMs, ratio });
  const verdict = ratio >= BENCH_TARGET_RATIO ? 'target met' : 'below target';
  console.log(
    `# bench ${entry.name}: wasm ${result.ms.toFixed(1)} ms, native ${entry.nativeMs.toFixed(1)} ms, ` +
      `ratio ${ratio.toFixed(2)} (target at least ${BENCH_TARGET_RATIO}: ${verdict})`,
  );
  if (entry.triangles != null) {
    check(`bench ${entry.name}: ${entry.triangles} triangles`, result.triangles === entry.triangles, `the file has ${result.triangles}`);
  }
}

main().catch((e) => {
  console.error(e);
  console.log(`${checks.filter((c) => c.ok).length} passed, ${checks.filter((c) => !c.ok).length + 1} failed`);
  process.exit(1);
});
