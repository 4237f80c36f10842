// WebGL2 renderer of the viewer: flat-shaded triangles, an orbit camera and picking.
//
// Vertices are expanded per triangle (3 per triangle, triangle i owns vertices 3i..3i+2) so
// that every triangle, even every corner, can have its own colour, and so that the picking
// pass can name a triangle by gl_VertexID / 3 without any extra buffer.

const VERTEX_SHADER = `#version 300 es
uniform mat4 uView;
uniform mat4 uProjection;
in vec3 aPosition;
in vec4 aColor;
out vec3 vView;
out vec4 vColor;
void main() {
  vec4 p = uView * vec4(aPosition, 1.0);
  vView = p.xyz;
  vColor = aColor;
  gl_Position = uProjection * p;
}`;

// The face normal comes from the screen-space derivatives of the view-space position: it is
// constant over a triangle (flat shading) and costs no normal buffer on a 1M-triangle mesh.
const FRAGMENT_SHADER = `#version 300 es
precision highp float;
in vec3 vView;
in vec4 vColor;
out vec4 outColor;
void main() {
  vec3 n = normalize(cross(dFdx(vView), dFdy(vView)));
  // Headlight: light from the eye; abs() lights back faces too (open meshes, mixed orientation).
  float lambert = abs(dot(n, normalize(-vView)));
  // Alpha 0 marks a highlighted triangle: mostly unlit, so that its colour reads at any angle
  // and is not mistaken for a shaded class colour.
  float ambient = mix(0.75, 0.35, vColor.a);
  outColor = vec4(vColor.rgb * (ambient + (1.0 - ambient) * lambert), 1.0);
}`;

// Picking pass: triangle index + 1 as four bytes (little end first), 0 left for background.
const PICK_VERTEX_SHADER = `#version 300 es
uniform mat4 uView;
uniform mat4 uProjection;
in vec3 aPosition;
flat out vec4 vId;
void main() {
  int id = gl_VertexID / 3 + 1;
  vId = vec4(ivec4(id & 255, (id >> 8) & 255, (id >> 16) & 255, (id >> 24) & 255)) / 255.0;
  gl_Position = uProjection * uView * vec4(aPosition, 1.0);
}`;

const PICK_FRAGMENT_SHADER = `#version 300 es
precision highp float;
flat in vec4 vId;
out vec4 outColor;
void main() { outColor = vId; }`;

const BACKGROUND = [0.17, 0.18, 0.21];
const FOV_Y = (40 * Math.PI) / 180;

export class Renderer {
  constructor(canvas) {
    this.canvas = canvas;
    // preserveDrawingBuffer: screenshots (and readPixels after compositing) see the frame.
    const gl = canvas.getContext('webgl2', { preserveDrawingBuffer: true, antialias: true });
    if (!gl) throw new Error('WebGL2 is not available in this browser');
    this.gl = gl;
    this.program = linkProgram(gl, VERTEX_SHADER, FRAGMENT_SHADER);
    this.pickProgram = linkProgram(gl, PICK_VERTEX_SHADER, PICK_FRAGMENT_SHADER);
    this.positionBuffer = gl.createBuffer();
    this.colorBuffer = gl.createBuffer();
    this.vao = this.makeVao(this.program, true);
    this.pickVao = this.makeVao(this.pickProgram, false);
    this.vertexCount = 0;
    this.base = null; // the mode's colours, kept to undo a highlight
    this.highlight = new Map(); // triangle index -> [r, g, b, 0] drawn over the mode
    this.pickTarget = null;
    this.camera = { yaw: 0.6, pitch: 0.45, distance: 3, target: [0, 0, 0], radius: 1 };
  }

  makeVao(program, withColor) {
    const gl = this.gl;
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    const position = gl.getAttribLocation(program, 'aPosition');
    gl.bindBuffer(gl.ARRAY_BUFFER, this.positionBuffer);
    gl.enableVertexAttribArray(position);
    gl.vertexAttribPointer(position, 3, gl.FLOAT, false, 0, 0);
    if (withColor) {
      const color = gl.getAttribLocation(program, 'aColor');
      gl.bindBuffer(gl.ARRAY_BUFFER, this.colorBuffer);
      gl.enableVertexAttribArray(color);
      gl.vertexAttribPointer(color, 4, gl.UNSIGNED_BYTE, true, 0, 0);
    }
    gl.bindVertexArray(null);
    return vao;
  }

  // positions: Float32Array of 9 floats per triangle, already centred on the bounding box's
  // centre (float precision stays where the mesh is); radius: half the box's diagonal.
  setMesh(positions, radius) {
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.positionBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, positions, gl.STATIC_DRAW);
    this.vertexCount = positions.length / 3;
    this.base = null;
    this.highlight = new Map();
    this.camera.radius = radius > 0 ? radius : 1;
    this.fit();
  }

  // colors: Uint8Array of RGBA per expanded vertex (12 bytes per triangle).
  setColors(colors) {
    const gl = this.gl;
    this.base = colors;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.colorBuffer);
    gl.bufferData(gl.ARRAY_BUFFER, colors, gl.STATIC_DRAW);
    for (const [index, rgba] of this.highlight) this.paintTriangle(index, rgba);
  }

  // Replaces the highlighted triangles: only those triangles' colours are rewritten, so a
  // pick on a 1M-triangle mesh does not upload the whole colour buffer again.
  setHighlight(highlight) {
    for (const index of this.highlight.keys()) {
      if (!highlight.has(index) && this.base) {
        this.writeTriangle(index, this.base.subarray(12 * index, 12 * index + 12));
      }
    }
    this.highlight = highlight;
    for (const [index, rgba] of highlight) this.paintTriangle(index, rgba);
  }

  paintTriangle(index, rgba) {
    const data = new Uint8Array(12);
    for (let k = 0; k < 3; k++) data.set(rgba, 4 * k);
    this.writeTriangle(index, data);
  }

  writeTriangle(index, data) {
    if (3 * index >= this.vertexCount) return;
    const gl = this.gl;
    gl.bindBuffer(gl.ARRAY_BUFFER, this.colorBuffer);
    gl.bufferSubData(gl.ARRAY_BUFFER, 12 * index, data);
  }

  // Places the camera so that the bounding sphere fills the view, whatever the aspect.
  fit() {
    const c = this.camera;
    c.target = [0, 0, 0];
    c.yaw = 0.6;
    c.pitch = 0.45;
    const aspect = this.aspect();
    const half = Math.min(FOV_Y / 2, Math.atan(Math.tan(FOV_Y / 2) * aspect));
    c.distance = c.radius / Math.sin(half); // the bounding sphere touches the view's edges
  }

  orbit(dx, dy) {
    const c = this.camera;
    c.yaw -= dx * 0.008;
    c.pitch = Math.max(-1.55, Math.min(1.55, c.pitch + dy * 0.008));
  }

  // Moves the target in the view plane so that the mesh follows the cursor.
  pan(dx, dy) {
    const c = this.camera;
    const { right, up } = this.basis();
    const perPixel = (2 * c.distance * Math.tan(FOV_Y / 2)) / Math.max(1, this.canvas.clientHeight);
    for (let i = 0; i < 3; i++) c.target[i] += (-dx * right[i] + dy * up[i]) * perPixel;
  }

  zoom(factor) {
    const c = this.camera;
    c.distance = Math.max(c.radius * 1e-3, Math.min(c.radius * 1e3, c.distance * factor));
  }

  basis() {
    const c = this.camera;
    const back = [
      Math.cos(c.pitch) * Math.sin(c.yaw),
      Math.sin(c.pitch),
      Math.cos(c.pitch) * Math.cos(c.yaw),
    ];
    const right = normalize(cross([0, 1, 0], back));
    const up = cross(back, right);
    return { back, right, up };
  }

  aspect() {
    return Math.max(1, this.canvas.clientWidth) / Math.max(1, this.canvas.clientHeight);
  }

  matrices() {
    const c = this.camera;
    const { back, right, up } = this.basis();
    const eye = c.target.map((t, i) => t + c.distance * back[i]);
    const view = lookAt(eye, right, up, back);
    // Depth range from the bounding sphere (centred at the origin) as seen from the eye:
    // tight, so that depth precision is not wasted.
    const d = Math.hypot(eye[0], eye[1], eye[2]);
    const near = Math.max((d - c.radius) * 0.9, c.radius * 1e-3);
    const far = (d + c.radius) * 1.1;
    return { view, projection: perspective(FOV_Y, this.aspect(), near, far) };
  }

  // Keeps the drawing buffer at the canvas's displayed size (in device pixels).
  resize() {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(this.canvas.clientWidth * dpr));
    const h = Math.max(1, Math.round(this.canvas.clientHeight * dpr));
    if (this.canvas.width !== w || this.canvas.height !== h) {
      this.canvas.width = w;
      this.canvas.height = h;
    }
  }

  draw() {
    this.resize();
    const gl = this.gl;
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.viewport(0, 0, this.canvas.width, this.canvas.height);
    gl.clearColor(BACKGROUND[0], BACKGROUND[1], BACKGROUND[2], 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    if (!this.vertexCount || !this.base) return;
    this.drawWith(this.program, this.vao);
  }

  drawWith(program, vao) {
    const gl = this.gl;
    const { view, projection } = this.matrices();
    gl.enable(gl.DEPTH_TEST);
    gl.disable(gl.CULL_FACE); // open meshes and either orientation show both sides
    gl.useProgram(program);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'uView'), false, view);
    gl.uniformMatrix4fv(gl.getUniformLocation(program, 'uProjection'), false, projection);
    gl.bindVertexArray(vao);
    gl.drawArrays(gl.TRIANGLES, 0, this.vertexCount);
    gl.bindVertexArray(null);
  }

  // Triangle index under the point (x, y) in CSS pixels from the canvas's top-left corner,
  // or -1: draws the indices into an offscreen framebuffer and reads one pixel.
  pick(x, y) {
    this.resize();
    if (!this.vertexCount) return -1;
    const gl = this.gl;
    const w = this.canvas.width;
    const h = this.canvas.height;
    const target = this.pickFramebuffer(w, h);
    gl.bindFramebuffer(gl.FRAMEBUFFER, target.framebuffer);
    gl.viewport(0, 0, w, h);
    gl.disable(gl.DITHER); // the bytes are an index, not a colour
    gl.clearColor(0, 0, 0, 0);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    this.drawWith(this.pickProgram, this.pickVao);
    const dpr = w / Math.max(1, this.canvas.clientWidth);
    const px = Math.floor(x * dpr);
    const py = h - 1 - Math.floor(y * dpr); // GL rows go up
    const pixel = new Uint8Array(4);
    if (px >= 0 && px < w && py >= 0 && py < h) {
      gl.readPixels(px, py, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    gl.enable(gl.DITHER);
    const id = (pixel[0] | (pixel[1] << 8) | (pixel[2] << 16) | (pixel[3] << 24)) >>> 0;
    return id === 0 ? -1 : id - 1;
  }

  pickFramebuffer(w, h) {
    const gl = this.gl;
    if (this.pickTarget && this.pickTarget.w === w && this.pickTarget.h === h) {
      return this.pickTarget;
    }
    if (this.pickTarget) {
      gl.deleteFramebuffer(this.pickTarget.framebuffer);
      gl.deleteRenderbuffer(this.pickTarget.color);
      gl.deleteRenderbuffer(this.pickTarget.depth);
    }
    const color = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, color);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.RGBA8, w, h);
    const depth = gl.createRenderbuffer();
    gl.bindRenderbuffer(gl.RENDERBUFFER, depth);
    gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT24, w, h);
    const framebuffer = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, framebuffer);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.RENDERBUFFER, color);
    gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, depth);
    const status = gl.checkFramebufferStatus(gl.FRAMEBUFFER);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    if (status !== gl.FRAMEBUFFER_COMPLETE) {
      throw new Error(`picking framebuffer incomplete (status 0x${status.toString(16)})`);
    }
    this.pickTarget = { w, h, framebuffer, color, depth };
    return this.pickTarget;
  }
}

function linkProgram(gl, vertexSource, fragmentSource) {
  const program = gl.createProgram();
  for (const [type, source] of [
    [gl.VERTEX_SHADER, vertexSource],
    [gl.FRAGMENT_SHADER, fragmentSource],
  ]) {
    const shader = gl.createShader(type);
    gl.shaderSource(shader, source);
    gl.compileShader(shader);
    if (!gl.getShaderParameter(shader, gl.COMPILE_STATUS)) {
      throw new Error(`shader compilation failed: ${gl.getShaderInfoLog(shader)}`);
    }
    gl.attachShader(program, shader);
  }
  gl.linkProgram(program);
  if (!gl.getProgramParameter(program, gl.LINK_STATUS)) {
    throw new Error(`shader link failed: ${gl.getProgramInfoLog(program)}`);
  }
  return program;
}

// Column-major 4×4 matrices, as uniformMatrix4fv expects them.

function lookAt(eye, right, up, back) {
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return new Float32Array([
    right[0], up[0], back[0], 0,
    right[1], up[1], back[1], 0,
    right[2], up[2], back[2], 0,
    -dot(right, eye), -dot(up, eye), -dot(back, eye), 1,
  ]);
}

function perspective(fovY, aspect, near, far) {
  const f = 1 / Math.tan(fovY / 2);
  const nf = 1 / (near - far);
  return new Float32Array([
    f / aspect, 0, 0, 0,
    0, f, 0, 0,
    0, 0, (far + near) * nf, -1,
    0, 0, 2 * far * near * nf, 0,
  ]);
}

function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

function normalize(a) {
  const n = Math.hypot(a[0], a[1], a[2]) || 1;
  return [a[0] / n, a[1] / n, a[2] / n];
}
