// The viewer's colours and HTML: the palettes and the colour buffers of each mode, next to
// the legend that explains them (so that the legend always matches the picture), the info
// panel and the selection panel.

// Triangle classes of `file.classes()`, in code order, with the colours of the LR paper's
// Fig. 1 as `lrmesh render` uses them.
export const CLASSES = [
  { name: 'T1 left', rgb: [255, 209, 153] },
  { name: 'T1 right', rgb: [250, 242, 214] },
  { name: 'T2', rgb: [51, 115, 255] },
  { name: 'T2 wart', rgb: [140, 64, 242] },
  { name: 'T0', rgb: [38, 191, 64] },
  { name: 'T0 wart', rgb: [242, 38, 38] },
];

export const GREY = [153, 153, 153]; // no data (NaN ring position, class 255)
export const SHADED = [205, 205, 205];
export const PICKED = [255, 255, 255];
export const STAR = [255, 0, 220];

// Ring position x in 0..1 to a colour: hue from 240° (blue) through cyan, green and yellow
// to 0° (red), slightly desaturated so that the shading reads on every hue (as `lrmesh
// render` does). Returns bytes.
export function ringColor(x, out = [0, 0, 0]) {
  if (Number.isNaN(x)) {
    out[0] = GREY[0];
    out[1] = GREY[1];
    out[2] = GREY[2];
    return out;
  }
  const h = 4 * (1 - Math.min(1, Math.max(0, x))); // in sixths of the hue circle
  const f = h - Math.floor(h);
  let r, g, b;
  switch (Math.floor(h)) {
    case 0: [r, g, b] = [1, f, 0]; break;
    case 1: [r, g, b] = [1 - f, 1, 0]; break;
    case 2: [r, g, b] = [0, 1, f]; break;
    case 3: [r, g, b] = [0, 1 - f, 1]; break;
    default: [r, g, b] = [0, 0, 1];
  }
  out[0] = Math.round(255 * (0.12 + 0.88 * r));
  out[1] = Math.round(255 * (0.12 + 0.88 * g));
  out[2] = Math.round(255 * (0.12 + 0.88 * b));
  return out;
}

// RGBA bytes per expanded vertex (4 per corner, 12 per triangle) for a colour mode. `mesh`
// has the per-triangle arrays (`count`, `rings`, `classes`); in attribute mode
// `cornerValues()` gives the attribute's values at every corner. Alpha stays 255 (gl.js reads
// alpha 0 as a highlight).
export function vertexColors(mode, mesh, cornerValues, attribute) {
  const n = mesh.count;
  const out = new Uint8Array(12 * n);
  const setTriangle = (i, rgb) => {
    for (let k = 0; k < 3; k++) {
      const o = 12 * i + 4 * k;
      out[o] = rgb[0];
      out[o + 1] = rgb[1];
      out[o + 2] = rgb[2];
      out[o + 3] = 255;
    }
  };
  if (mode === 'ring') {
    const rgb = [0, 0, 0];
    for (let i = 0; i < n; i++) setTriangle(i, ringColor(mesh.rings[i], rgb));
  } else if (mode === 'class') {
    for (let i = 0; i < n; i++) {
      const c = CLASSES[mesh.classes[i]];
      setTriangle(i, c ? c.rgb : GREY);
    }
  } else if (mode === 'attribute' && attribute) {
    attributeColors(attribute, cornerValues(), 3 * n, out);
  } else {
    for (let i = 0; i < n; i++) setTriangle(i, SHADED);
  }
  return out;
}

// Attribute values at every corner to colours, by the rules attributeRule() states.
function attributeColors(attribute, values, corners, out) {
  const m = attribute.components;
  const byte = (x) => (Number.isNaN(x) ? GREY[0] : Math.round(255 * Math.min(1, Math.max(0, x))));
  const isColor = /colou?r/i.test(attribute.name);
  let lo = Infinity;
  let hi = -Infinity;
  if (m === 1) {
    for (let j = 0; j < corners; j++) {
      if (values[j] < lo) lo = values[j];
      if (values[j] > hi) hi = values[j];
    }
  }
  const frac = (x) => x - Math.floor(x);
  const rgb = [0, 0, 0];
  for (let j = 0; j < corners; j++) {
    const o = 4 * j;
    const v = m * j;
    if (m === 1) {
      ringColor(hi > lo ? (values[v] - lo) / (hi - lo) : 0.5, rgb);
      out[o] = rgb[0];
      out[o + 1] = rgb[1];
      out[o + 2] = rgb[2];
    } else if (m === 2) {
      out[o] = byte(frac(values[v]));
      out[o + 1] = byte(frac(values[v + 1]));
      out[o + 2] = 128;
    } else {
      // Normals and other directions lie in -1..1; colours are shown as they are.
      for (let k = 0; k < 3; k++) out[o + k] = byte(isColor ? values[v + k] : 0.5 + 0.5 * values[v + k]);
    }
    out[o + 3] = 255;
  }
}

const css = (rgb) => `rgb(${rgb[0]}, ${rgb[1]}, ${rgb[2]})`;

const $ = (id) => document.getElementById(id);

function el(tag, props = {}, children = []) {
  const node = document.createElement(tag);
  for (const [key, value] of Object.entries(props)) {
    if (key === 'style') Object.assign(node.style, value);
    else if (key.startsWith('data-')) node.setAttribute(key, value);
    else node[key] = value;
  }
  for (const child of [].concat(children)) {
    node.append(child instanceof Node ? child : String(child));
  }
  return node;
}

export function setStatus(text) {
  $('status').textContent = text;
}

export function showError(message) {
  const box = $('error');
  box.textContent = message || '';
  box.hidden = !message;
}

const formatCount = (n) => (typeof n === 'number' ? n.toLocaleString('en-US') : '-');

// The first number under a key named like bits_per_triangle anywhere in the info object
// (breadth first), else under its short form `bpt` (as in `connectivity_bpt`), as
// [key path, value], or null.
function findBitsPerTriangle(info) {
  for (const pattern of [/bits_per_triangle$/, /(^|_)bpt$/]) {
    const queue = [[info, '']];
    while (queue.length) {
      const [node, path] = queue.shift();
      for (const [key, value] of Object.entries(node)) {
        if (pattern.test(key) && typeof value === 'number') return [path + key, value];
        if (value && typeof value === 'object') queue.push([value, `${path}${key}.`]);
      }
    }
  }
  return null;
}

// Fills the side panel from the file's `lrmesh info --json` object.
export function showInfo(kind, info) {
  $('info-kind').textContent = kind;
  $('info-vertices').textContent = formatCount(info.vertices);
  $('info-triangles').textContent = formatCount(info.triangles);
  $('info-bytes').textContent = formatCount(info.bytes);
  const bpt = findBitsPerTriangle(info);
  const bptCell = $('info-bpt');
  bptCell.textContent = bpt ? String(Math.round(bpt[1] * 100) / 100) : '-';
  bptCell.title = bpt ? `info key ${bpt[0]}` : 'no bits_per_triangle key in the info';
  // Say whose bits they are: `connectivity_bpt` counts the connectivity section only.
  const owner = bpt ? bpt[0].replace(/\.?_?(bits_per_triangle|bpt)$/, '').replace(/[._]/g, ' ') : '';
  $('info-bpt-label').textContent = owner ? `bits / triangle (${owner})` : 'bits / triangle';

  const body = $('sections').tBodies[0];
  body.replaceChildren();
  const total = info.bytes || 1;
  for (const section of info.sections || []) {
    body.append(
      el('tr', {}, [
        el('td', {}, section.tag),
        el('td', { className: 'num' }, formatCount(section.length)),
        el('td', { className: 'num' }, formatShare(section.length / total)),
      ]),
    );
  }
}

// A share of the file, with more digits for the small sections (metadata, headers).
function formatShare(x) {
  const percent = 100 * x;
  if (percent > 0 && percent < 0.01) return '< 0.01 %';
  return `${percent.toFixed(percent < 1 ? 2 : 1)} %`;
}

export function clearInfo() {
  for (const id of ['info-kind', 'info-vertices', 'info-triangles', 'info-bytes', 'info-bpt']) {
    $(id).textContent = '-';
  }
  $('sections').tBodies[0].replaceChildren();
}

// The legend of a colour mode; `attribute` is { name, components, perCorner } in attribute
// mode; `selected` adds the highlight colours.
export function showLegend(mode, attribute, selected) {
  const legend = $('legend');
  const parts = [];
  if (mode === 'ring') {
    const stops = [0, 0.25, 0.5, 0.75, 1].map((x) => `${css(ringColor(x))} ${x * 100}%`);
    parts.push(
      el('div', { className: 'legend-title' }, 'Ring order'),
      el('div', { className: 'ramp', style: { background: `linear-gradient(to right, ${stops.join(', ')})` } }),
      el('div', { className: 'ramp-labels' }, [el('span', {}, 'ring start'), el('span', {}, '…'), el('span', {}, 'ring end')]),
      el('div', { className: 'legend-note' }, [swatch(GREY), 'no ring position']),
    );
  } else if (mode === 'class') {
    parts.push(el('div', { className: 'legend-title' }, 'Triangle class'));
    const list = el('div', { className: 'swatches' });
    for (const c of CLASSES) list.append(el('span', { className: 'entry' }, [swatch(c.rgb), c.name]));
    parts.push(list);
  } else if (mode === 'attribute' && attribute) {
    const binding = attribute.perCorner ? 'per corner' : 'per vertex';
    parts.push(
      el('div', { className: 'legend-title' }, `Attribute ${attribute.name}`),
      el('div', { className: 'legend-note' },
        `${attribute.components} component${attribute.components === 1 ? '' : 's'}, ${binding}: ${attributeRule(attribute)}`),
    );
  } else {
    parts.push(
      el('div', { className: 'legend-title' }, 'Shaded'),
      el('div', { className: 'legend-note' }, 'uniform light grey, lit from the camera'),
    );
  }
  if (selected) {
    parts.push(el('div', { className: 'legend-note' }, [swatch(PICKED), 'picked triangle ', swatch(STAR), 'stars of its vertices']));
  }
  legend.replaceChildren(...parts);
}

// How attribute values become colours (viewer.js applies the same rules).
export function attributeRule(attribute) {
  const isColor = /colou?r/i.test(attribute.name);
  switch (attribute.components) {
    case 1: return 'value from its minimum (blue) to its maximum (red)';
    case 2: return 'rgb = (u mod 1, v mod 1, 0.5)';
    case 3: return isColor ? 'rgb = value' : 'rgb = 0.5 + 0.5 · value';
    default: return isColor ? 'rgb = the first three components' : 'rgb = 0.5 + 0.5 · the first three components';
  }
}

function swatch(rgb) {
  return el('span', { className: 'swatch', style: { background: css(rgb) } });
}

// The picked triangle, its corners and vertices and the triangles around each vertex.
export function showSelection(selection) {
  const box = $('selection');
  if (!selection) {
    box.replaceChildren(el('p', { className: 'hint' }, 'Click a triangle to pick it.'));
    return;
  }
  const rows = selection.corners.map((c, k) =>
    el('tr', {}, [
      el('td', { className: 'num' }, c),
      el('td', { className: 'num' }, selection.vertices[k]),
      el('td', { className: 'star' }, selection.stars[k].join(' ')),
    ]),
  );
  box.replaceChildren(
    el('p', {}, [
      'triangle ', el('strong', { 'data-testid': 'selected-triangle' }, selection.triangle),
      ` (index ${selection.index})`,
    ]),
    el('table', {}, [
      el('thead', {}, el('tr', {}, [el('th', {}, 'corner'), el('th', {}, 'vertex'), el('th', {}, 'star: triangles')])),
      el('tbody', {}, rows),
    ]),
  );
}
