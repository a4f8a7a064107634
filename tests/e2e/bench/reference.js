// The benchmark's reference (tests/e2e/bench-viewer.mjs): a bare WebGL2 page drawing ?n= small
// triangles (about 4 x 7 pixels, flat colours, depth-tested, no antialiasing) in one draw call
// every frame, on a 1280 x 720 canvas. On a software renderer its frame rate is what this machine
// can draw at that moment: the viewer's rows are read beside it (this machine's speed varies).
// An external script: the test server's Content-Security-Policy forbids inline ones.
'use strict';
(function () {
  const n = Math.max(1, Number(new URLSearchParams(window.location.search).get('n')) || 100000);
  const canvas = document.getElementById('c');
  const gl = canvas.getContext('webgl2', { antialias: false });
  if (!gl) {
    document.title = 'error: no WebGL2';
    return;
  }
  const vertexSource = `#version 300 es
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_color;
out vec3 v_color;
void main() { v_color = a_color; gl_Position = vec4(a_position, 1.0); }`;
  const fragmentSource = `#version 300 es
precision mediump float;
in vec3 v_color;
out vec4 o_color;
void main() { o_color = vec4(v_color, 1.0); }`;
  function shader(kind, source) {
    const s = gl.createShader(kind);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  const program = gl.createProgram();
  gl.attachShader(program, shader(gl.VERTEX_SHADER, vertexSource));
  gl.attachShader(program, shader(gl.FRAGMENT_SHADER, fragmentSource));
  gl.linkProgram(program);
  gl.useProgram(program);
  // Triangles scattered over the canvas at random depths (a fixed seed: the same every run).
  const data = new Float32Array(n * 3 * 6);
  let seed = 1;
  const random = () => (seed = (seed * 16807) % 2147483647) / 2147483647;
  const w = 8 / canvas.width, h = 14 / canvas.height;  // 4 x 7 pixels
  for (let t = 0; t < n; ++t) {
    const x = random() * 2 - 1, y = random() * 2 - 1, z = random() * 2 - 1;
    const colour = [random(), random(), random()];
    const corners = [[x, y], [x + w, y], [x, y + h]];
    for (let k = 0; k < 3; ++k) data.set([corners[k][0], corners[k][1], z, ...colour], (t * 3 + k) * 6);
  }
  gl.bindBuffer(gl.ARRAY_BUFFER, gl.createBuffer());
  gl.bufferData(gl.ARRAY_BUFFER, data, gl.STATIC_DRAW);
  gl.enableVertexAttribArray(0);
  gl.vertexAttribPointer(0, 3, gl.FLOAT, false, 24, 0);
  gl.enableVertexAttribArray(1);
  gl.vertexAttribPointer(1, 3, gl.FLOAT, false, 24, 12);
  gl.enable(gl.DEPTH_TEST);
  function frame() {
    gl.clearColor(0.8, 0.85, 0.9, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.drawArrays(gl.TRIANGLES, 0, n * 3);
    window.requestAnimationFrame(frame);
  }
  document.title = `drawing ${n} triangles`;
  window.requestAnimationFrame(frame);
})();
