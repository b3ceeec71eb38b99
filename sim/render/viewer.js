// rmot offline 3D viewer: WebGL 1, no external files. The scene comes from the JSON block
// with id "rmot-data" that rmot.sim.render.html writes into the page.
(function () {
  "use strict";
  var data = JSON.parse(document.getElementById("rmot-data").textContent);
  var canvas = document.getElementById("view");
  var gl = canvas.getContext("webgl", { antialias: true });
  if (!gl) { document.getElementById("status").textContent = "WebGL is not available in this browser."; return; }

  function f32(b64) {  // base64 -> Float32Array (little-endian, as numpy writes it)
    var bin = atob(b64), bytes = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    return new Float32Array(bytes.buffer);
  }

  // ---- small matrix helpers (column-major 4x4, as WebGL expects)
  function perspective(fovy, aspect, near, far) {
    var t = 1 / Math.tan(fovy / 2), m = new Float32Array(16);
    m[0] = t / aspect; m[5] = t; m[10] = (far + near) / (near - far); m[11] = -1;
    m[14] = 2 * far * near / (near - far); return m;
  }
  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function norm(a) { var l = Math.hypot(a[0], a[1], a[2]) || 1; return [a[0] / l, a[1] / l, a[2] / l]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function lookAt(eye, center, up) {  // world -> eye
    var f = norm(sub(center, eye)), s = norm(cross(f, up)), u = cross(s, f), m = new Float32Array(16);
    m[0] = s[0]; m[4] = s[1]; m[8] = s[2];
    m[1] = u[0]; m[5] = u[1]; m[9] = u[2];
    m[2] = -f[0]; m[6] = -f[1]; m[10] = -f[2];
    m[12] = -dot(s, eye); m[13] = -dot(u, eye); m[14] = dot(f, eye); m[15] = 1; return m;
  }

  // ---- shaders: per-pixel Blinn-Phong with two directional lights, two-sided
  var VS = "attribute vec3 p; attribute vec3 n; uniform mat4 model, view, proj;" +
    "varying vec3 wp; varying vec3 wn;" +
    "void main(){ vec4 w = model * vec4(p,1.0); wp = w.xyz; wn = mat3(model) * n; gl_Position = proj * view * w; }";
  var FS = "precision mediump float; varying vec3 wp; varying vec3 wn; uniform vec3 color, eye, hl, contact; uniform float lit, mark, radius;" +
    "void main(){ if (lit < 0.5) { gl_FragColor = vec4(color,1.0); return; }" +
    " vec3 base = color; if (mark > 1.5 && distance(wp, contact) > radius) base = mix(color, hl, 0.4); else if (mark > 0.5) base = hl;" +
    " vec3 nn = normalize(wn); vec3 v = normalize(eye - wp); if (dot(nn,v) < 0.0) nn = -nn;" +
    " vec3 l1 = normalize(vec3(0.35,-0.55,0.76)); vec3 l2 = normalize(vec3(-0.6,0.5,0.3));" +
    " float d = 0.85*max(dot(nn,l1),0.0) + 0.3*max(dot(nn,l2),0.0);" +
    " float s = dot(nn,l1) > 0.0 ? 0.85*pow(max(dot(nn,normalize(l1+v)),0.0),24.0) : 0.0;" +
    " gl_FragColor = vec4(min(base*(0.28+0.72*d) + 0.22*s, 1.0), 1.0); }";
  function compile(type, src) {
    var s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  var prog = gl.createProgram();
  gl.attachShader(prog, compile(gl.VERTEX_SHADER, VS)); gl.attachShader(prog, compile(gl.FRAGMENT_SHADER, FS));
  gl.linkProgram(prog); gl.useProgram(prog);
  var loc = {};
  ["model", "view", "proj", "color", "eye", "lit", "hl", "contact", "mark", "radius"].forEach(function (k) { loc[k] = gl.getUniformLocation(prog, k); });
  var aP = gl.getAttribLocation(prog, "p"), aN = gl.getAttribLocation(prog, "n");

  function buffer(array) { var b = gl.createBuffer(); gl.bindBuffer(gl.ARRAY_BUFFER, b); gl.bufferData(gl.ARRAY_BUFFER, array, gl.STATIC_DRAW); return b; }
  function drawable(verts, normals, color) { return { p: buffer(verts), n: buffer(normals), count: verts.length / 3, color: color }; }

  var bodies = data.bodies.map(function (b) { return drawable(f32(b.vertices), f32(b.normals), b.color); });
  var floors = data.floor.map(function (f) { return drawable(f32(f.vertices), f32(f.normals), f.color); });
  var paths = data.paths.map(function (p) { var v = f32(p); return { p: buffer(v), n: buffer(new Float32Array(v.length)), count: v.length / 3 }; });
  var poses = f32(data.poses), times = data.times, nBodies = bodies.length;
  var findings = data.findings || [], names = data.bodies.map(function (b) { return b.name; });
  var identity = new Float32Array([1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]);

  function modelAt(frame, i) {  // rows of a 3x4 pose -> column-major 4x4
    var o = (frame * nBodies + i) * 12, m = new Float32Array(16);
    for (var r = 0; r < 3; r++) { for (var c = 0; c < 4; c++) m[c * 4 + r] = poses[o + r * 4 + c]; }
    m[15] = 1; return m;
  }

  // ---- orbit camera around the centre of interest
  var cam = data.camera, center = cam.center.slice(), offset = sub(cam.eye, cam.center);
  var dist = Math.hypot(offset[0], offset[1], offset[2]);
  var yaw = Math.atan2(offset[1], offset[0]), pitch = Math.asin(offset[2] / dist);
  function eyePoint() { return [center[0] + dist * Math.cos(pitch) * Math.cos(yaw), center[1] + dist * Math.cos(pitch) * Math.sin(yaw), center[2] + dist * Math.sin(pitch)]; }
  var dragging = false, lastX = 0, lastY = 0, panning = false;
  canvas.addEventListener("mousedown", function (e) { dragging = true; panning = e.shiftKey || e.button === 2; lastX = e.clientX; lastY = e.clientY; e.preventDefault(); });
  canvas.addEventListener("contextmenu", function (e) { e.preventDefault(); });
  window.addEventListener("mouseup", function () { dragging = false; });
  window.addEventListener("mousemove", function (e) {
    if (!dragging) return;
    var dx = e.clientX - lastX, dy = e.clientY - lastY; lastX = e.clientX; lastY = e.clientY;
    if (panning) {
      var eye = eyePoint(), f = norm(sub(center, eye)), s = norm(cross(f, [0, 0, 1])), u = cross(s, f), k = dist * 0.0015;
      for (var i = 0; i < 3; i++) center[i] += -dx * k * s[i] + dy * k * u[i];
    } else { yaw -= dx * 0.008; pitch = Math.max(-1.5, Math.min(1.5, pitch + dy * 0.008)); }
  });
  canvas.addEventListener("wheel", function (e) { dist *= Math.exp(e.deltaY * 0.001); e.preventDefault(); }, { passive: false });

  // ---- playback
  var slider = document.getElementById("time"), label = document.getElementById("label"), button = document.getElementById("play");
  var duration = times.length ? times[times.length - 1] : 0, playing = times.length > 1, t0 = performance.now(), tShown = 0;
  slider.max = String(Math.max(times.length - 1, 0));
  button.addEventListener("click", function () { playing = !playing; t0 = performance.now() - tShown * 1000; button.textContent = playing ? "pause" : "play"; });
  slider.addEventListener("input", function () { playing = false; button.textContent = "play"; tShown = times[+slider.value] || 0; });
  // ---- findings: a list that jumps to each one's worst instant; bodies red around their interval
  var panel = document.getElementById("findings"), items = [];
  if (findings.length) {
    var head = document.createElement("h2"); head.textContent = findings.length + " finding" + (findings.length > 1 ? "s" : "");
    panel.appendChild(head);
  }
  findings.forEach(function (f, k) {
    var b = document.createElement("button"); b.className = "finding"; b.textContent = f.caption;
    b.addEventListener("click", function () { jumpTo(f.worst); });
    panel.appendChild(b); items.push(b);
  });
  function jumpTo(t) {
    playing = false; button.textContent = "play"; tShown = Math.max(0, Math.min(t, duration));
    slider.value = String(frameAt(tShown));
  }
  window.rmotJump = jumpTo;  // the report page's links call this
  function activeAt(t) {
    var marked = {};
    findings.forEach(function (f, k) {
      var on = t >= f.t0 - data.window - 1e-9 && t <= f.t1 + data.window + 1e-9;
      items[k].className = on ? "finding on" : "finding";
      if (on) f.bodies.forEach(function (i) {  // fixtures: the contact region strong, the rest tinted
        var region = f.contact && data.bodies[i].kind === "fixture";
        if (!marked[i] || !region) marked[i] = region ? { contact: f.contact, radius: f.radius } : { contact: null };
      });
    });
    return marked;
  }

  // ---- body names on hover: each body drawn in an id colour into an offscreen buffer
  var pick = gl.createFramebuffer(), pickTex = gl.createTexture(), pickDepth = gl.createRenderbuffer(), pickW = 0, pickH = 0;
  var hover = document.getElementById("hover"), mouse = null;
  canvas.addEventListener("mousemove", function (e) { var r = canvas.getBoundingClientRect(); mouse = [e.clientX - r.left, e.clientY - r.top, e.clientX, e.clientY]; });
  canvas.addEventListener("mouseleave", function () { mouse = null; hover.style.display = "none"; });
  function pickAt(frame, x, y, w, h) {
    if (pickW !== w || pickH !== h) {
      gl.bindTexture(gl.TEXTURE_2D, pickTex); gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA, w, h, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.bindRenderbuffer(gl.RENDERBUFFER, pickDepth); gl.renderbufferStorage(gl.RENDERBUFFER, gl.DEPTH_COMPONENT16, w, h);
      gl.bindFramebuffer(gl.FRAMEBUFFER, pick);
      gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, pickTex, 0);
      gl.framebufferRenderbuffer(gl.FRAMEBUFFER, gl.DEPTH_ATTACHMENT, gl.RENDERBUFFER, pickDepth);
      pickW = w; pickH = h;
    }
    gl.bindFramebuffer(gl.FRAMEBUFFER, pick);
    gl.clearColor(0, 0, 0, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    floors.forEach(function (d) { drawOne(d, identity, [0, 0, 0], 0, gl.TRIANGLES); });
    bodies.forEach(function (d, i) { drawOne(d, modelAt(frame, i), [((i + 1) & 255) / 255, (((i + 1) >> 8) & 255) / 255, 0], 0, gl.TRIANGLES); });
    var px = new Uint8Array(4); gl.readPixels(Math.floor(x), Math.floor(h - 1 - y), 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return px[0] + 256 * px[1] - 1;
  }
  var start = data.start;
  if (typeof start !== "number") { var m = /[#&]t=([0-9.]+)/.exec(window.location.hash); if (m) start = parseFloat(m[1]); }
  if (typeof start === "number" && isFinite(start)) { playing = false; button.textContent = "play"; tShown = Math.max(0, Math.min(start, duration)); }

  function frameAt(t) { var i = 0; while (i + 1 < times.length && times[i + 1] <= t + 1e-9) i++; return i; }

  function drawOne(d, model, color, lit, mode) {
    gl.uniformMatrix4fv(loc.model, false, model); gl.uniform3fv(loc.color, color); gl.uniform1f(loc.lit, lit);
    gl.bindBuffer(gl.ARRAY_BUFFER, d.p); gl.vertexAttribPointer(aP, 3, gl.FLOAT, false, 0, 0); gl.enableVertexAttribArray(aP);
    gl.bindBuffer(gl.ARRAY_BUFFER, d.n); gl.vertexAttribPointer(aN, 3, gl.FLOAT, false, 0, 0); gl.enableVertexAttribArray(aN);
    gl.drawArrays(mode, 0, d.count);
  }
  function render(now) {
    if (playing && duration > 0) tShown = ((now - t0) / 1000) % duration;
    var frame = frameAt(tShown); slider.value = String(frame);
    label.textContent = "t = " + tShown.toFixed(2) + " s / " + duration.toFixed(2) + " s";
    var w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, w, h); gl.clearColor(0.92, 0.93, 0.95, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    var eye = eyePoint();
    gl.uniformMatrix4fv(loc.proj, false, perspective(cam.fov * Math.PI / 180, w / h, dist * 0.01, dist * 20));
    gl.uniformMatrix4fv(loc.view, false, lookAt(eye, center, [0, 0, 1])); gl.uniform3fv(loc.eye, eye);
    var marked = activeAt(tShown);
    if (mouse) {
      var hit = pickAt(frame, mouse[0], mouse[1], w, h);
      if (hit >= 0 && hit < nBodies) {
        hover.textContent = names[hit]; hover.style.display = "block";
        hover.style.left = (mouse[2] + 12) + "px"; hover.style.top = (mouse[3] + 12) + "px";
      } else { hover.style.display = "none"; }
    }
    gl.clearColor(0.92, 0.93, 0.95, 1); gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    floors.forEach(function (d) { drawOne(d, identity, d.color, 1, gl.TRIANGLES); });
    gl.uniform3fv(loc.hl, data.highlight);
    bodies.forEach(function (d, i) {
      var m = marked[i];
      gl.uniform1f(loc.mark, m ? (m.contact ? 2 : 1) : 0);
      if (m && m.contact) { gl.uniform3fv(loc.contact, m.contact); gl.uniform1f(loc.radius, m.radius); }
      drawOne(d, modelAt(frame, i), d.color, 1, gl.TRIANGLES);
    });
    gl.uniform1f(loc.mark, 0);
    paths.forEach(function (d) { drawOne(d, identity, data.pathColor, 0, gl.LINE_STRIP); });
    requestAnimationFrame(render);
  }
  requestAnimationFrame(render);
})();
