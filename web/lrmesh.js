// lrmesh in the browser: the ES-module API of web/API.md over the WebAssembly build in pkg/
// (web/build.sh). Functions take and return typed arrays; ids are plain numbers.
import init, * as wasm from './pkg/lrmesh_wasm.js';

let loaded = null;

/** Instantiates the WebAssembly module (once); await it before anything else. */
export function ready() {
  loaded ??= init();
  return loaded;
}

/** Opens a container (Uint8Array) checked well formed; throws an Error naming what is wrong. */
export function open(bytes) {
  return wasm.open(bytes);
}

/** Opens a container after every validity rule (`lrmesh verify`). */
export function openVerified(bytes) {
  return wasm.openVerified(bytes);
}

/** Whether this build can encode. */
export function encoderAvailable() {
  return wasm.encoderAvailable();
}

/**
 * A `.lrm` (Uint8Array) of the mesh in `meshBytes`; `format` is obj, ply, off, stl, gltf, glb
 * or lrm; `options`: { connectivity, quantizePosition, level, keepOrder }, all optional.
 */
export function encode(meshBytes, format, options = {}) {
  if (!wasm.encoderAvailable()) throw new Error('this build of lrmesh decodes only');
  return wasm.encode(meshBytes, format, JSON.stringify(options));
}

/**
 * Median milliseconds, over `runs` runs, of a full decode of `bytes`: every rule checked, then
 * the whole mesh into arrays (as `lrmesh decode` does before writing).
 */
export function decodeBench(bytes, runs = 5) {
  wasm.decodeOnce(bytes); // warm up: compile and grow the memory once
  const times = [];
  for (let i = 0; i < runs; i++) {
    const start = performance.now();
    wasm.decodeOnce(bytes);
    times.push(performance.now() - start);
  }
  times.sort((a, b) => a - b);
  const h = times.length >> 1;
  return times.length % 2 ? times[h] : (times[h - 1] + times[h]) / 2;
}
