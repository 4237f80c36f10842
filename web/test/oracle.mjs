// The browser test's oracle: a corner table built in plain JS from the triangle list alone,
// independent of the container and of the wasm module's operators.
//
// Corner 3i + k is the k-th corner of triangle i of the list (the order of `triangleIds()`
// and `triangleCorners`). The opposite of a corner is the corner facing the same edge in the
// triangle that uses that edge in the other direction; an edge used more than once in a
// direction (or whose reverse is used more than once) has no opposite, nor does a boundary.

export function buildCornerTable(triangles, triangleIds) {
  const n = triangleIds.length;
  if (triangles.length !== 3 * n) {
    throw new Error(`${triangles.length} triangle vertices for ${n} triangle ids`);
  }
  const next = (c) => (c % 3 === 2 ? c - 2 : c + 1);
  const prev = (c) => (c % 3 === 0 ? c + 2 : c - 1);

  // Directed edge (a, b) -> the corners facing it; the edge facing corner c runs from
  // c.n's vertex to c.p's vertex.
  const key = (a, b) => `${a},${b}`;
  const facing = new Map();
  for (let c = 0; c < 3 * n; c++) {
    const k = key(triangles[next(c)], triangles[prev(c)]);
    const list = facing.get(k);
    if (list) list.push(c);
    else facing.set(k, [c]);
  }

  const opposite = new Int32Array(3 * n).fill(-1);
  for (let c = 0; c < 3 * n; c++) {
    const a = triangles[next(c)];
    const b = triangles[prev(c)];
    const forward = facing.get(key(a, b));
    const reverse = facing.get(key(b, a));
    if (forward.length === 1 && reverse && reverse.length === 1) opposite[c] = reverse[0];
  }

  // Vertex -> ids of its triangles.
  const star = new Map();
  for (let i = 0; i < n; i++) {
    for (let k = 0; k < 3; k++) {
      const v = triangles[3 * i + k];
      const list = star.get(v);
      if (list) list.push(triangleIds[i]);
      else star.set(v, [triangleIds[i]]);
    }
  }

  return {
    triangleCount: n,
    vertexOf: (c) => triangles[c],
    triangleIdOf: (c) => triangleIds[Math.floor(c / 3)],
    next,
    prev,
    opposite: (c) => opposite[c],
    // Ids of the triangles around v, sorted.
    starTriangleIds: (v) => [...new Set(star.get(v) || [])].sort((x, y) => x - y),
  };
}

// Sorted distinct values, to compare two lists as sets.
export function asSet(list) {
  return [...new Set(list)].sort((x, y) => x - y);
}

export function sameSet(a, b) {
  const x = asSet(a);
  const y = asSet(b);
  return x.length === y.length && x.every((v, i) => v === y[i]);
}
