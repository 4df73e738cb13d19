/*
 * tumble's interactive page: plays a tumbling body from compact data (tumble.viz.page).
 *
 * The body's triangles are in the page once (tumble-data's "geometry", design frame about the
 * centre of mass, integer multiples of geometry.unit metres); each frame holds only the time,
 * the attitude quaternion of the drawn geometry (scalar last, [x, y, z, w], geometry frame to
 * world) and the world-frame omega (rad/s) and L (kg m^2/s). Every frame this script rotates the
 * vertices (x_world = R x) and moves the traces with Plotly.restyle.
 *
 * Order on the page: plotly.js, then (when live mode is on) splitting.js and live.js, then this
 * file. live.js therefore runs BEFORE the viewer exists: it must wait for the DOM event
 * "tumble:ready" on document (fired once the three plots are drawn), or find
 * window.tumbleViewer.ready already true.
 *
 * window.tumbleViewer:
 *   setRun(run)  replace the motion. run = {t: [n] s, quat: [[x, y, z, w]] principal -> world,
 *                omega: [[w1, w2, w3]] principal frame rad/s, moments: [I1, I2, I3] kg m^2,
 *                box: [a, b, c] half-sizes (m) along the principal axes, or null; optional:
 *                frames (most animation frames, default MAX_FRAMES; the omega(t) curves keep
 *                every sample), torqueFree (default true), extra (a tumbleExtra, below, for this
 *                run)}. With a box the
 *                drawn body becomes that uniform box (attitude = the principal attitude); without,
 *                the body's own geometry is kept and turned by the design attitude
 *                R_design = R_principal A^T (A = tumble-data's principal_axes, principal -> design).
 *                L = moments * omega. At most MAX_FRAMES evenly spread samples become frames.
 *   reset()      restore the page's own run.
 *   state()      {playing, frame, frames}.
 *   play(), pause(), show(frame) -> Promise, setSpeed(factor); ready (true once drawn).
 *
 * window.tumbleExtra (optional, set by a script inlined before this one: control.js on a
 * closed-loop run's page) adds traces to the page's own run (a setRun run brings its own as
 * run.extra: fitview.js on a fit's page):
 *   traces(view, size) -> [plotly traces] appended to the "ground" or "body" plot;
 *   omegaTraces() -> [plotly traces] appended to the omega(t) plot (optional);
 *   install(size) -> Promise    draws its own plots (once the page's run is installed);
 *   frame(k, M, t) -> {ground: [{x, y, z}], body: [{x, y, z}], done: Promise}: the new coordinates
 *                of its traces at frame k (time t, s), M the drawn geometry's -> world rotation
 *                matrix (rows);
 *   translucent (optional, default true): the body drawn translucent (arrows inside it show).
 *
 * window.tumbleFirstRun (optional, set by a script inlined before this one: fitview.js) -> a
 * setRun run: the run drawn first, in place of the page's own (reset() still restores the
 * page's own). Without it a fit's page drew its first flight twice on load, once plain and once
 * with the flight's extra (~40 % of its load in software WebGL).
 */
(function () {
  "use strict";

  var MAX_FRAMES = 2000;     // as tumble.viz.scene.MAX_FRAMES
  var MAX_CURVE = 4000;      // most points per omega(t) curve and in the omega path
  var FPS = 15;              // frames per second at speed x1
  var RED = "#d62728", BLUE = "#1f77b4", SOLID = "#9fb3c8", REMOVED = "#e8483f";
  var CURVE_COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c"];  // as the matplotlib figures
  var ROLES = ["minor", "intermediate", "major"];
  var LIGHT = {ambient: 0.45, diffuse: 0.75, specular: 0.35, roughness: 0.45, fresnel: 0.2};
  var LIGHTPOS = {x: 2e5, y: 1e5, z: 3e5};
  var CONFIG = {displaylogo: false, responsive: true, topojsonURL: ""};

  var data = JSON.parse(document.getElementById("tumble-data").textContent);
  var gd = {
    ground: document.getElementById("tumble-ground"),
    body: document.getElementById("tumble-body"),
    omega: document.getElementById("tumble-omega"),
  };
  var ui = {
    play: document.getElementById("tumble-play"),
    slider: document.getElementById("tumble-slider"),
    time: document.getElementById("tumble-time"),
    note: document.getElementById("tumble-note"),
    speeds: Array.prototype.slice.call(document.querySelectorAll(".tumble-speed")),
  };

  // ---- small vector algebra (quaternions scalar last, as scipy) ------------------------
  function matrix(q) {  // rotation matrix of a quaternion, rows
    var n = Math.hypot(q[0], q[1], q[2], q[3]), x = q[0] / n, y = q[1] / n, z = q[2] / n, w = q[3] / n;
    return [
      [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
      [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
      [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ];
  }
  function quatMul(a, b) {  // a * b: first b, then a
    return [
      a[3] * b[0] + a[0] * b[3] + a[1] * b[2] - a[2] * b[1],
      a[3] * b[1] - a[0] * b[2] + a[1] * b[3] + a[2] * b[0],
      a[3] * b[2] + a[0] * b[1] - a[1] * b[0] + a[2] * b[3],
      a[3] * b[3] - a[0] * b[0] - a[1] * b[1] - a[2] * b[2],
    ];
  }
  function apply(M, v) {
    return [M[0][0] * v[0] + M[0][1] * v[1] + M[0][2] * v[2],
            M[1][0] * v[0] + M[1][1] * v[1] + M[1][2] * v[2],
            M[2][0] * v[0] + M[2][1] * v[1] + M[2][2] * v[2]];
  }
  function applyT(M, v) {  // M^T v
    return [M[0][0] * v[0] + M[1][0] * v[1] + M[2][0] * v[2],
            M[0][1] * v[0] + M[1][1] * v[1] + M[2][1] * v[2],
            M[0][2] * v[0] + M[1][2] * v[1] + M[2][2] * v[2]];
  }
  function norm(v) { return Math.hypot(v[0], v[1], v[2]); }
  function scaled(v, s) { return [v[0] * s, v[1] * s, v[2] * s]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function fmt(x) { return Number(x.toPrecision(3)).toString(); }
  function evenly(n, most) {  // at most `most` indices of 0..n-1, first and last included
    if (n <= most) { return Array.from({length: n}, function (_, k) { return k; }); }
    var out = [];
    for (var k = 0; k < most; k++) { out.push(Math.round(k * (n - 1) / (most - 1))); }
    return out;
  }

  // ---- geometry ----------------------------------------------------------------------------
  function unpack(g, unit) {  // {v: flat ints, f: flat ints} -> {v: Float64Array (m), i, j, k}
    if (!g) { return null; }
    var v = Float64Array.from(g.v, function (x) { return x * unit; });
    var i = [], j = [], k = [];
    for (var n = 0; n < g.f.length; n += 3) { i.push(g.f[n]); j.push(g.f[n + 1]); k.push(g.f[n + 2]); }
    return {v: v, i: i, j: j, k: k};
  }
  function boxGeometry(h) {  // uniform box of half-sizes h along x, y, z: 6 faces, outward
    var v = [], f = [];
    for (var axis = 0; axis < 3; axis++) {
      var u = (axis + 1) % 3, w = (axis + 2) % 3;
      [-1, 1].forEach(function (sign) {
        var base = v.length / 3;
        [[-1, -1], [1, -1], [1, 1], [-1, 1]].forEach(function (c) {
          var p = [0, 0, 0];
          p[axis] = sign * h[axis]; p[u] = c[0] * h[u]; p[w] = c[1] * h[w];
          v.push(p[0], p[1], p[2]);
        });
        f.push.apply(f, sign > 0 ? [base, base + 1, base + 2, base, base + 2, base + 3]
                                 : [base, base + 2, base + 1, base, base + 3, base + 2]);
      });
    }
    return unpack({v: v, f: f}, 1.0);
  }
  function turned(g, M) {  // x, y, z arrays of the geometry's vertices after x -> M x
    var n = g.v.length / 3, x = new Float64Array(n), y = new Float64Array(n), z = new Float64Array(n), v = g.v;
    for (var a = 0; a < n; a++) {
      var p = v[3 * a], q = v[3 * a + 1], r = v[3 * a + 2];
      x[a] = M[0][0] * p + M[0][1] * q + M[0][2] * r;
      y[a] = M[1][0] * p + M[1][1] * q + M[1][2] * r;
      z[a] = M[2][0] * p + M[2][1] * q + M[2][2] * r;
    }
    return [x, y, z];
  }

  // ---- a motion: everything one animation needs ------------------------------------------
  var AXES = data.principal_axes;  // rows; columns are the principal axes in the design frame
  var AXES_T = [0, 1, 2].map(function (r) { return [0, 1, 2].map(function (c) { return AXES[c][r]; }); });
  var ORIGINAL = {
    solid: unpack(data.geometry.solid, data.geometry.unit),
    removed: unpack(data.geometry.removed, data.geometry.unit),
    size: data.size,
  };

  function curvesOf(t, omega, stride) {
    var idx = [];
    for (var k = 0; k < t.length; k += stride) { idx.push(k); }
    if (idx[idx.length - 1] !== t.length - 1) { idx.push(t.length - 1); }
    return {
      t: idx.map(function (k) { return t[k]; }),
      omega: [0, 1, 2].map(function (j) { return idx.map(function (k) { return omega[k][j]; }); }),
      stride: stride, samples: t.length,
    };
  }

  function originalMotion() {
    var f = data.frames, c = data.curves;
    return {
      t: f.t, q: f.q, w: f.w, L: f.L, torqueFree: data.torque_free,
      curves: {t: c.t, omega: c.omega, stride: c.stride, samples: c.samples},
      toGeometry: AXES,  // principal -> geometry (design) frame, for the omega path
      geometry: ORIGINAL, frameName: "design axes",
      title: data.title, extra: window.tumbleExtra || null,
    };
  }

  function checkRun(run) {
    var n = run && run.t ? run.t.length : 0;
    if (n < 2) { throw new Error("setRun: run.t must hold at least 2 times (s), got " + n); }
    ["quat", "omega"].forEach(function (name) {
      if (!run[name] || run[name].length !== n) {
        throw new Error("setRun: run." + name + " must hold " + n + " rows (one per time), got " +
                        (run[name] ? run[name].length : run[name]));
      }
    });
    if (!run.moments || run.moments.length !== 3 || !run.moments.every(function (m) { return m > 0; })) {
      throw new Error("setRun: run.moments must be three positive moments (kg m^2), got " + JSON.stringify(run.moments));
    }
    if (run.box != null && (run.box.length !== 3 || !run.box.every(function (h) { return h > 0; }))) {
      throw new Error("setRun: run.box must be null or three positive half-sizes (m), got " + JSON.stringify(run.box));
    }
  }

  function runMotion(run) {
    checkRun(run);
    var box = run.box != null;
    var axesQ = data.principal_axes_quat, inv = [-axesQ[0], -axesQ[1], -axesQ[2], axesQ[3]];
    var idx = evenly(run.t.length, Math.min(MAX_FRAMES, run.frames || MAX_FRAMES));
    var motion = {t: [], q: [], w: [], L: [], torqueFree: run.torqueFree !== false};
    idx.forEach(function (k) {
      var qp = run.quat[k], M = matrix(qp), om = run.omega[k];
      var h = run.momentum || [0, 0, 0];  // a rotor's momentum (principal frame): L = I w + h
      var Lb = [run.moments[0] * om[0] + h[0], run.moments[1] * om[1] + h[1], run.moments[2] * om[2] + h[2]];
      motion.t.push(run.t[k]);
      motion.q.push(box ? qp : quatMul(qp, inv));  // R_design = R_principal A^T
      motion.w.push(apply(M, om));
      motion.L.push(apply(M, Lb));
    });
    motion.curves = curvesOf(run.t, run.omega, Math.max(1, Math.ceil(run.t.length / MAX_CURVE)));
    motion.toGeometry = box ? [[1, 0, 0], [0, 1, 0], [0, 0, 1]] : AXES;
    motion.geometry = box ? {solid: boxGeometry(run.box), removed: null, size: norm(run.box)} : ORIGINAL;
    motion.frameName = box ? "principal axes" : "design axes";
    motion.title = run.title || (data.title + " (new run)");
    motion.extra = run.extra || null;
    return motion;
  }

  // ---- traces --------------------------------------------------------------------------------
  function peak(vectors) { return vectors.reduce(function (m, v) { return Math.max(m, norm(v)); }, 0); }

  function planeLines(m, size) {  // orientation grid: invariable plane (normal L) or the ground
    var L0 = m.L[0], n = [0, 0, 1], name = "ground grid (plane z = " + fmt(-0.9 * size) + " m)";
    if (m.torqueFree && norm(L0) > 0) {
      n = scaled(L0, 1 / norm(L0));
      name = "invariable plane direction (normal to L), drawn " + fmt(0.9 * size) + " m from the COM along -L";
    }
    var a = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    var u = cross(n, a); u = scaled(u, 1 / norm(u));
    var v = cross(n, u), half = 0.6 * size, x = [], y = [], z = [];
    for (var s = -4; s <= 4; s++) {
      var c = s / 4 * half;
      [[u, v], [v, u]].forEach(function (pair) {
        [-half, half].forEach(function (e) {
          var p = [0, 1, 2].map(function (i) { return -size * 0.9 * n[i] + c * pair[0][i] + e * pair[1][i]; });
          x.push(p[0]); y.push(p[1]); z.push(p[2]);
        });
        x.push(null); y.push(null); z.push(null);
      });
    }
    return {type: "scatter3d", mode: "lines", x: x, y: y, z: z, name: name, hoverinfo: "skip",
            line: {color: "#b0b0b0", width: 2}};
  }

  function meshTrace(g, removed, translucent) {
    return {type: "mesh3d", x: [], y: [], z: [], i: g.i, j: g.j, k: g.k, hoverinfo: "skip",
            name: removed ? "removed material" : "body", showlegend: true,
            color: removed ? REMOVED : SOLID, opacity: removed ? 0.45 : (translucent ? 0.6 : 1.0),
            flatshading: false, lighting: LIGHT, lightposition: LIGHTPOS};
  }

  function arrowTrace(color, name) {
    return {type: "scatter3d", mode: "lines+markers", x: [0, 0], y: [0, 0], z: [0, 0], name: name,
            hoverinfo: "skip", line: {color: color, width: 9},
            marker: {size: [0, 6], color: color, symbol: "diamond"}};
  }

  function sceneLayout(size, title, names) {
    var r = 1.25 * size, axis = function (label) {
      return {title: {text: label + " (m)"}, range: [-r, r], autorange: false, showbackground: true,
              backgroundcolor: "#f7f7f7", gridcolor: "#dddddd", zerolinecolor: "#cccccc"};
    };
    return {
      title: {text: title, font: {size: 15}}, margin: {l: 0, r: 0, t: 40, b: 0}, showlegend: true,
      modebar: {orientation: "v"},  // down the right edge: a toolbar along the top covered the title
      legend: {x: 0, y: 0.99, bgcolor: "rgba(255,255,255,0.7)", font: {size: 11}},
      uirevision: "keep",
      scene: {xaxis: axis(names[0]), yaxis: axis(names[1]), zaxis: axis(names[2]), aspectmode: "cube",
              camera: {eye: {x: 0.9, y: 0.9, z: 0.55}}},
    };
  }

  // ---- state and drawing ---------------------------------------------------------------------
  var state = {playing: false, frame: 0, speed: 1, pos: 0, last: null, busy: false, motion: null};
  var index = {};  // trace indices in the ground plot

  function install(m) {
    var g = m.geometry, size = g.size;
    m.sw = 0.9 * size / (peak(m.w) || 1);
    m.sL = 0.9 * size / (peak(m.L) || 1);
    var wName = "omega, red (rad/s): 1 rad/s drawn as " + fmt(m.sw) + " m";
    var LName = "L, blue (kg m^2/s): 1 kg m^2/s drawn as " + fmt(m.sL) + " m";
    // translucent with a hole to show, or with extras (a control run's torque arrow starts inside)
    var see = !!(m.extra && m.extra.translucent !== false);  // an extra's arrows start inside the body
    var ground = [meshTrace(g.solid, false, !!g.removed || see)];
    index = {solid: 0};
    if (g.removed) { index.removed = ground.length; ground.push(meshTrace(g.removed, true, false)); }
    index.w = ground.length; ground.push(arrowTrace(RED, wName));
    index.L = ground.length; ground.push(arrowTrace(BLUE, LName));
    ground.push(planeLines(m, size));
    if (m.extra) { index.xg = ground.length; ground.push.apply(ground, m.extra.traces("ground", size)); }

    var I = [[1, 0, 0], [0, 1, 0], [0, 0, 1]], still = turned(g.solid, I);
    var body = [Object.assign(meshTrace(g.solid, false, !!g.removed || see), {x: still[0], y: still[1], z: still[2]})];
    if (g.removed) {
      var hole = turned(g.removed, I);
      body.push(Object.assign(meshTrace(g.removed, true, false), {x: hole[0], y: hole[1], z: hole[2]}));
    }
    var path = {x: [], y: [], z: []}, c = m.curves;
    for (var k = 0; k < c.t.length; k++) {
      var p = apply(m.toGeometry, [c.omega[0][k], c.omega[1][k], c.omega[2][k]]);
      path.x.push(p[0] * m.sw); path.y.push(p[1] * m.sw); path.z.push(p[2] * m.sw);
    }
    body.push({type: "scatter3d", mode: "lines", x: path.x, y: path.y, z: path.z, name: "path of omega's tip",
               hoverinfo: "skip", line: {color: RED, width: 2}, opacity: 0.5});
    index.bw = body.length; body.push(arrowTrace(RED, "omega (rad/s), same scale"));
    index.bL = body.length; body.push(arrowTrace(BLUE, "L (kg m^2/s), same scale"));
    if (m.extra) { index.xb = body.length; body.push.apply(body, m.extra.traces("body", size)); }

    var lim = 0;
    c.omega.forEach(function (row) { row.forEach(function (x) { lim = Math.max(lim, Math.abs(x)); }); });
    lim = 1.05 * lim || 1;
    var curves = c.omega.map(function (row, j) {
      return {type: "scatter", mode: "lines", x: c.t, y: row, name: "omega_" + (j + 1) + " (" + ROLES[j] + ")",
              line: {color: CURVE_COLORS[j], width: 1.5}};
    });
    curves.push({type: "scatter", mode: "lines", x: [0, 0], y: [-lim, lim], name: "now",  // dashed: not the zero line
                 line: {color: "black", width: 1, dash: "dash"}, hoverinfo: "skip"});
    if (m.extra && m.extra.omegaTraces) { curves.push.apply(curves, m.extra.omegaTraces()); }  // after "now" (index 3)
    var omegaLayout = {
      margin: {l: 60, r: 10, t: 30, b: 45}, title: {text: "omega in the principal frame", font: {size: 15}},
      xaxis: {title: {text: "t (s)"}}, yaxis: {title: {text: "omega (rad/s)"}, range: [-lim, lim]},
      legend: {x: 1.01, xanchor: "left", y: 1},  // outside the plot: never covers the curves
    };
    ui.note.textContent = c.stride > 1
      ? "Long run: the omega(t) curves and the omega path show every " + c.stride + "th of the " +
        c.samples + " samples."
      : "";
    document.getElementById("tumble-title").textContent = m.title;
    state.motion = m;
    state.frame = 0; state.pos = 0;
    ui.slider.max = String(m.t.length - 1);
    ui.slider.value = "0";
    var gl = sceneLayout(size, "ground frame (axes in m): the body tumbles; without torque L stays fixed", ["x", "y", "z"]);
    var bl = sceneLayout(size, "body frame (" + m.frameName + ", m): omega wanders, L with it", ["x", "y", "z"]);
    gl.uirevision = bl.uirevision = String(Math.random());  // a new run: new camera defaults
    return Promise.all([
      Plotly.react(gd.ground, ground, gl, CONFIG),
      Plotly.react(gd.body, body, bl, CONFIG),
      Plotly.react(gd.omega, curves, omegaLayout, CONFIG),
      m.extra ? m.extra.install(size) : null,
    ]).then(function () { return show(0); });
  }

  function show(frame) {
    var m = state.motion, k = Math.max(0, Math.min(m.t.length - 1, frame | 0));
    state.frame = k;
    ui.slider.value = String(k);
    ui.time.textContent = "t = " + m.t[k].toFixed(2) + " s of " + fmt(m.t[m.t.length - 1]) + " s";
    var M = matrix(m.q[k]), w = scaled(m.w[k], m.sw), L = scaled(m.L[k], m.sL);
    var solid = turned(m.geometry.solid, M);
    var xs = [solid[0]], ys = [solid[1]], zs = [solid[2]], which = [index.solid];
    if (m.geometry.removed) {
      var hole = turned(m.geometry.removed, M);
      xs.push(hole[0]); ys.push(hole[1]); zs.push(hole[2]); which.push(index.removed);
    }
    [[w, index.w], [L, index.L]].forEach(function (a) {
      xs.push([0, a[0][0]]); ys.push([0, a[0][1]]); zs.push([0, a[0][2]]); which.push(a[1]);
    });
    var wb = applyT(M, w), Lb = applyT(M, L), t = m.t[k];
    var bx = [[0, wb[0]], [0, Lb[0]]], by = [[0, wb[1]], [0, Lb[1]]], bz = [[0, wb[2]], [0, Lb[2]]];
    var bwhich = [index.bw, index.bL], extra = m.extra ? m.extra.frame(k, M, t) : null;
    if (extra) {
      extra.ground.forEach(function (p, j) { xs.push(p.x); ys.push(p.y); zs.push(p.z); which.push(index.xg + j); });
      extra.body.forEach(function (p, j) { bx.push(p.x); by.push(p.y); bz.push(p.z); bwhich.push(index.xb + j); });
    }
    return Promise.all([
      Plotly.restyle(gd.ground, {x: xs, y: ys, z: zs}, which),
      Plotly.restyle(gd.body, {x: bx, y: by, z: bz}, bwhich),
      Plotly.restyle(gd.omega, {x: [[t, t]]}, [3]),
      extra ? extra.done : null,
    ]);
  }

  function tick(now) {
    if (!state.playing) { return; }
    if (state.last !== null) { state.pos += (now - state.last) / 1000 * FPS * state.speed; }
    state.last = now;
    var n = state.motion.t.length;
    if (state.pos >= n) { state.pos %= n; }
    var k = Math.floor(state.pos);
    if (!state.busy && k !== state.frame) {
      state.busy = true;
      show(k).then(function () { state.busy = false; }, function () { state.busy = false; });
    }
    window.requestAnimationFrame(tick);
  }

  function play() {
    if (state.playing) { return; }
    state.playing = true; state.last = null; state.pos = state.frame;
    ui.play.textContent = "Pause";
    window.requestAnimationFrame(tick);
  }
  function pause() {
    state.playing = false;
    ui.play.textContent = "Play";
  }
  function setSpeed(factor) {
    state.speed = factor;
    ui.speeds.forEach(function (b) { b.classList.toggle("active", Number(b.dataset.speed) === factor); });
  }

  ui.play.addEventListener("click", function () { if (state.playing) { pause(); } else { play(); } });
  ui.slider.addEventListener("input", function () {
    state.pos = Number(ui.slider.value);
    show(state.pos);
  });
  ui.speeds.forEach(function (b) { b.addEventListener("click", function () { setSpeed(Number(b.dataset.speed)); }); });

  window.tumbleViewer = {
    ready: false,
    setRun: function (run) { pause(); return install(runMotion(run)); },
    reset: function () { pause(); return install(originalMotion()); },
    state: function () { return {playing: state.playing, frame: state.frame, frames: state.motion.t.length}; },
    play: play, pause: pause, show: show, setSpeed: setSpeed,
  };
  setSpeed(1);
  install(window.tumbleFirstRun ? runMotion(window.tumbleFirstRun()) : originalMotion()).then(function () {
    window.tumbleViewer.ready = true;
    document.dispatchEvent(new Event("tumble:ready"));
  });
})();
