// lrmesh web viewer: opens a .lrm (or encodes another mesh in the page), draws it with
// WebGL2, colours it by ring order, triangle class or an attribute, picks triangles and walks
// the stars of their vertices on the file's bytes, and saves the mesh re-encoded.
//
// Everything is read through `lrmesh.js` (see API.md). Per-triangle data stays in typed
// arrays so that a 1M-triangle mesh loads: no JS object per triangle.

import { Renderer } from './gl.js';
import * as ui from './ui.js';

const FORMATS = ['obj', 'ply', 'off', 'stl', 'gltf', 'glb'];
const MODES = ['shaded', 'ring', 'class', 'attribute'];
const DRAG_THRESHOLD = 4; // px: a press that moves less is a click (a pick)

const $ = (id) => document.getElementById(id);

let lrmesh = null;
let renderer = null;
// Per loaded file: typed arrays fetched once, and what the colour modes can show.
let mesh = null;

const viewer = {
  ready: null,
  file: null,
  name: null,
  selection: null,
  lastError: null,
  mode: 'shaded',
  setColorMode,
  pickAt,
  render,
  open: openFile, // a File or Blob with a name, as the picker gives it
};
window.viewer = viewer;

// ---------------------------------------------------------------------------------------
// Start-up

viewer.ready = (async () => {
  // A dynamic import, so that a missing or broken module is reported in the page.
  lrmesh = await import('./lrmesh.js');
  window.lrmesh = lrmesh;
  await lrmesh.ready();
  ui.setStatus('ready');
})();
// Handled here, so that a failed start is shown and is not an unhandled rejection.
viewer.ready.catch((e) => {
  report(e, 'could not start lrmesh');
  ui.setStatus('failed to start');
});

try {
  renderer = new Renderer($('view'));
} catch (e) {
  report(e, 'no renderer');
}

ui.clearInfo();
ui.showSelection(null);
ui.showLegend(viewer.mode, null, false);
bindControls();
render();

// ---------------------------------------------------------------------------------------
// Loading

function splitName(fileName) {
  const dot = fileName.lastIndexOf('.');
  if (dot <= 0) return { name: fileName, ext: '' };
  return { name: fileName.slice(0, dot), ext: fileName.slice(dot + 1).toLowerCase() };
}

// Lets the browser paint the status before a long synchronous encode or open.
function yieldToPaint() {
  return new Promise((resolve) => {
    const timer = setTimeout(resolve, 50); // requestAnimationFrame stalls in hidden tabs
    requestAnimationFrame(() => {
      clearTimeout(timer);
      setTimeout(resolve, 0);
    });
  });
}

async function openFile(blob) {
  const { name, ext } = splitName(blob.name || 'mesh.lrm');
  try {
    await viewer.ready;
    viewer.lastError = null;
    ui.showError('');
    ui.setStatus(`loading ${name}…`);
    const bytes = new Uint8Array(await blob.arrayBuffer());
    await yieldToPaint();
    let container = bytes;
    if (ext !== 'lrm') {
      if (!FORMATS.includes(ext)) {
        throw new Error(`cannot open .${ext || '(no extension)'}: expected .lrm or ${FORMATS.map((f) => `.${f}`).join(', ')}`);
      }
      if (!lrmesh.encoderAvailable()) {
        throw new Error(`this build of lrmesh has no encoder: open a .lrm, not a .${ext}`);
      }
      // Default options: a standard LR, what `lrmesh encode FILE -o X.lrm` writes.
      container = lrmesh.encode(bytes, ext, {});
    }
    show(lrmesh.open(container), name);
    ui.setStatus(`loaded ${name}`);
  } catch (e) {
    report(e, `could not open ${blob.name}`);
    ui.setStatus(`failed to load ${name}`);
  }
}

function show(file, name) {
  const info = JSON.parse(file.infoJson());
  const ids = file.triangleIds();
  const triangles = file.triangles();
  const positions = file.positions();
  const count = ids.length;

  // Bounding box of the vertices of triangles (unreferenced vertices do not move the camera).
  const min = [Infinity, Infinity, Infinity];
  const max = [-Infinity, -Infinity, -Infinity];
  for (let j = 0; j < triangles.length; j++) {
    const v = 3 * triangles[j];
    for (let k = 0; k < 3; k++) {
      const x = positions[v + k];
      if (x < min[k]) min[k] = x;
      if (x > max[k]) max[k] = x;
    }
  }
  const centre = count ? min.map((m, k) => (m + max[k]) / 2) : [0, 0, 0];
  const radius = count ? Math.hypot(max[0] - min[0], max[1] - min[1], max[2] - min[2]) / 2 : 1;

  // One vertex per corner, centred on the box, in triangleIds() order.
  const expanded = new Float32Array(9 * count);
  for (let j = 0; j < triangles.length; j++) {
    const v = 3 * triangles[j];
    expanded[3 * j] = positions[v] - centre[0];
    expanded[3 * j + 1] = positions[v + 1] - centre[1];
    expanded[3 * j + 2] = positions[v + 2] - centre[2];
  }

  // Triangle id -> index in triangleIds() (LR ids are sparse), -1 for none.
  let maxId = -1;
  for (let i = 0; i < count; i++) if (ids[i] > maxId) maxId = ids[i];
  const indexOfId = new Int32Array(maxId + 1).fill(-1);
  for (let i = 0; i < count; i++) indexOfId[ids[i]] = i;

  const classes = file.classes();
  const rings = file.ringPositions();
  const attributes = JSON.parse(file.attributesJson());
  const available = {
    shaded: true,
    ring: rings.some((x) => !Number.isNaN(x)),
    class: classes.some((c) => c !== 255),
    attribute: attributes.length > 0,
  };

  const previous = viewer.file;
  mesh = { ids, classes, rings, attributes, available, indexOfId, count };
  viewer.file = file;
  viewer.name = name;
  viewer.selection = null;
  if (previous && previous !== file) previous.free();

  ui.showInfo(file.kind(), info);
  ui.showSelection(null);
  updateModeControls();
  if (renderer) renderer.setMesh(expanded, radius);
  $('save').disabled = false;
  $('save-kind').disabled = false;
  $('fit').disabled = false;
  $('save-note').textContent = '';
  applyMode(available[viewer.mode] ? viewer.mode : 'shaded');
}

// Enables the modes the file has data for, and lists its attributes.
function updateModeControls() {
  const select = $('color-mode');
  for (const option of select.options) option.disabled = !mesh.available[option.value];
  const attributeSelect = $('attribute-select');
  attributeSelect.replaceChildren(
    ...mesh.attributes.map((a, i) => new Option(`${a.name} (${a.components})`, String(i))),
  );
  attributeSelect.disabled = mesh.attributes.length === 0;
}

// ---------------------------------------------------------------------------------------
// Colour modes

function setColorMode(mode) {
  if (!MODES.includes(mode)) throw new Error(`unknown colour mode ${mode}: expected ${MODES.join(', ')}`);
  if (mesh && !mesh.available[mode]) {
    throw new Error(`colour mode ${mode} has no data in this file (${viewer.file.kind()})`);
  }
  applyMode(mode);
}

function applyMode(mode) {
  viewer.mode = mode;
  $('color-mode').value = mode;
  const attribute = mode === 'attribute' && mesh ? mesh.attributes[attributeIndex()] : null;
  ui.showLegend(mode, attribute, Boolean(viewer.selection));
  if (mesh && renderer) {
    renderer.setColors(ui.vertexColors(mode, mesh, () => viewer.file.cornerValues(attributeIndex()), attribute));
  }
  render();
}

function attributeIndex() {
  return Number($('attribute-select').value) || 0;
}

// ---------------------------------------------------------------------------------------
// Drawing and picking

function render() {
  if (renderer) renderer.draw();
}

let frameRequested = false;
function scheduleRender() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => {
    frameRequested = false;
    render();
  });
}

// Picks at (x, y), CSS pixels from the canvas's top-left corner, as a click does; returns
// the selection, or null on background.
function pickAt(x, y) {
  if (!renderer || !mesh) return null;
  const index = renderer.pick(x, y);
  if (index < 0 || index >= mesh.count) select(-1);
  else select(index);
  render();
  return viewer.selection;
}

// Selects the triangle at `index` in triangleIds() (-1: none): corners, vertices and the
// star of each vertex, walked with the corner operators on the file's bytes.
function select(index) {
  const highlight = new Map();
  if (index < 0) {
    viewer.selection = null;
  } else {
    const file = viewer.file;
    const triangle = mesh.ids[index];
    const corners = Array.from(file.triangleCorners(triangle), Number);
    const vertices = corners.map((c) => Number(file.vertex(c)));
    const stars = vertices.map((v) => Array.from(file.star(v), (c) => Number(file.triangleOf(c))));
    viewer.selection = { triangle, index, corners, vertices, stars };
    const starColor = [...ui.STAR, 0]; // alpha 0: a highlight, drawn almost unlit (gl.js)
    for (const star of stars) {
      for (const t of star) {
        const i = t < mesh.indexOfId.length ? mesh.indexOfId[t] : -1;
        if (i >= 0) highlight.set(i, starColor);
      }
    }
    highlight.set(index, [...ui.PICKED, 0]); // the picked one wins over its stars
  }
  renderer.setHighlight(highlight);
  ui.showSelection(viewer.selection);
  const attribute = viewer.mode === 'attribute' ? mesh.attributes[attributeIndex()] : null;
  ui.showLegend(viewer.mode, attribute, Boolean(viewer.selection));
}

// ---------------------------------------------------------------------------------------
// Saving

function save() {
  try {
    const kind = $('save-kind').value;
    const bytes = viewer.file.reencode(kind);
    const fileName = `${viewer.name}.${kind}.lrm`;
    const url = URL.createObjectURL(new Blob([bytes], { type: 'application/octet-stream' }));
    const link = document.createElement('a');
    link.href = url;
    link.download = fileName;
    document.body.append(link);
    link.click();
    link.remove();
    // Revoked later: revoking at once can cancel the download in some browsers.
    setTimeout(() => URL.revokeObjectURL(url), 60000);
    $('save-note').textContent = `${fileName}: ${bytes.length.toLocaleString('en-US')} bytes`;
  } catch (e) {
    report(e, 'could not save');
  }
}

// ---------------------------------------------------------------------------------------
// Controls

function report(e, context) {
  const message = `${context}: ${e && e.message ? e.message : String(e)}`;
  viewer.lastError = message;
  ui.showError(message);
  console.warn(message); // a warning: the page handled it
}

// Runs an event handler, turning any exception into a reported error.
function guarded(context, handler) {
  return (event) => {
    try {
      handler(event);
    } catch (e) {
      report(e, context);
    }
  };
}

function bindControls() {
  const input = $('file');
  input.addEventListener('change', () => {
    const file = input.files && input.files[0];
    input.value = ''; // choosing the same file again fires `change` again
    if (file) openFile(file);
  });

  // Drag and drop anywhere on the window.
  window.addEventListener('dragover', (event) => {
    event.preventDefault();
    document.body.classList.add('dragging');
  });
  window.addEventListener('dragleave', (event) => {
    if (!event.relatedTarget) document.body.classList.remove('dragging');
  });
  window.addEventListener('drop', (event) => {
    event.preventDefault();
    document.body.classList.remove('dragging');
    const file = event.dataTransfer && event.dataTransfer.files[0];
    if (file) openFile(file);
  });

  $('color-mode').addEventListener('change', guarded('colour mode', (e) => setColorMode(e.target.value)));
  $('attribute-select').addEventListener('change', guarded('attribute', () => {
    if (viewer.mode === 'attribute') applyMode('attribute');
  }));
  $('save').addEventListener('click', save);
  $('fit').addEventListener('click', guarded('fit', () => {
    renderer.fit();
    render();
  }));

  const canvas = $('view');
  let press = null; // { x, y, button, pan, dragging }
  canvas.addEventListener('pointerdown', (event) => {
    press = {
      x: event.clientX,
      y: event.clientY,
      lastX: event.clientX,
      lastY: event.clientY,
      button: event.button,
      pan: event.button === 2 || event.shiftKey,
      dragging: false,
    };
    canvas.setPointerCapture(event.pointerId);
  });
  canvas.addEventListener('pointermove', guarded('camera', (event) => {
    if (!press || !renderer) return;
    if (!press.dragging) {
      if (Math.hypot(event.clientX - press.x, event.clientY - press.y) <= DRAG_THRESHOLD) return;
      press.dragging = true; // from here on the whole motion counts
    }
    const dx = event.clientX - press.lastX;
    const dy = event.clientY - press.lastY;
    press.lastX = event.clientX;
    press.lastY = event.clientY;
    if (press.pan) renderer.pan(dx, dy);
    else renderer.orbit(dx, dy);
    scheduleRender();
  }));
  canvas.addEventListener('pointerup', guarded('pick', (event) => {
    const p = press;
    press = null;
    if (!p || p.dragging || p.button !== 0) return;
    const rect = canvas.getBoundingClientRect();
    pickAt(event.clientX - rect.left, event.clientY - rect.top);
  }));
  canvas.addEventListener('pointercancel', () => {
    press = null;
  });
  canvas.addEventListener('contextmenu', (event) => event.preventDefault());
  canvas.addEventListener('wheel', guarded('zoom', (event) => {
    event.preventDefault();
    if (!renderer) return;
    const lines = event.deltaMode === 1 ? 16 : event.deltaMode === 2 ? 400 : 1;
    renderer.zoom(Math.exp(event.deltaY * lines * 0.0015));
    scheduleRender();
  }), { passive: false });

  new ResizeObserver(() => scheduleRender()).observe(canvas);
}
