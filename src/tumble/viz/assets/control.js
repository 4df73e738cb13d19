/*
 * tumble's interactive page, closed-loop runs: the reaction wheels, the commanded torque and the
 * magnetorquer dipole on the body, a readout and a time plot of the attitude error or |omega|.
 *
 * Data: tumble-data's "control" (tumble.viz.control_page.control_page_data), one row per page
 * frame: wheel angles relative to the body (rad), wheel speeds (rad/s), the commanded torque
 * (principal frame, N m), the dipole (principal frame, A m^2, or null). Vectors in the principal
 * frame go to the drawn (design) frame by tumble-data's principal_axes, then to the world by the
 * frame's attitude.
 *
 * Inlined before viewer.js; it only sets window.tumbleExtra (the interface is described at the
 * head of viewer.js), which the viewer calls for its own run.
 */
(function () {
  "use strict";

  var GREEN = "#2ca02c", PURPLE = "#9467bd", RED = "#d62728", WHEEL_LIGHT = "#f2c14e", WHEEL_DARK = "#3a3a3a", WHEEL_RIM = "#8c8c8c";
  var SEGMENTS = 24;  // facets round a wheel; its faces alternate light and dark by quarter turns
  var LIGHT = {ambient: 0.55, diffuse: 0.7, specular: 0.2, roughness: 0.5, fresnel: 0.1};
  var CONFIG = {displaylogo: false, responsive: true, topojsonURL: ""};
  var RPM = 60 / (2 * Math.PI);

  var data = JSON.parse(document.getElementById("tumble-data").textContent);
  var c = data.control;
  if (!c) { return; }
  var AXES = data.principal_axes;  // principal -> design (rows)

  function apply(M, v) {
    return [M[0][0] * v[0] + M[0][1] * v[1] + M[0][2] * v[2],
            M[1][0] * v[0] + M[1][1] * v[1] + M[1][2] * v[2],
            M[2][0] * v[0] + M[2][1] * v[1] + M[2][2] * v[2]];
  }
  function norm(v) { return Math.hypot(v[0], v[1], v[2]); }
  function unit(v) { var n = norm(v); return [v[0] / n, v[1] / n, v[2] / n]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function fmt(x) { return Number(x.toPrecision(3)).toString(); }
  function peak(rows) { return rows.reduce(function (m, v) { return Math.max(m, norm(v)); }, 0); }

  // ---- the wheels: discs on the body's surface along their axes (design frame) ---------------
  var geometry = data.geometry.solid, vertexUnit = data.geometry.unit;
  function support(g) {  // farthest extent of the body along the unit vector g, m
    var most = 0;
    for (var a = 0; a < geometry.v.length; a += 3) {
      most = Math.max(most, (geometry.v[a] * g[0] + geometry.v[a + 1] * g[1] + geometry.v[a + 2] * g[2]) * vertexUnit);
    }
    return most;
  }
  var wheels = [], size = data.size, radius = 0.14 * size, thick = 0.06 * size, gap = 0.015 * size;
  c.wheel_axes.forEach(function (p) {
    var g = unit(apply(AXES, p));
    var other = Math.abs(g[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
    var e1 = unit(cross(g, other)), e2 = cross(g, e1);
    var out = support(g) + gap + thick / 2;
    wheels.forEach(function (w) {  // a second wheel on the same axis sits further out
      if (w.g[0] * g[0] + w.g[1] * g[1] + w.g[2] * g[2] > 0.999) { out = Math.max(out, w.out + thick + gap); }
    });
    wheels.push({g: g, e1: e1, e2: e2, out: out});
  });

  // One mesh for all wheels: per wheel, two caps (a centre and SEGMENTS rim points each).
  var PER = 2 * (SEGMENTS + 1), I = [], J = [], K = [], facecolor = [];
  wheels.forEach(function (_, w) {
    var o = w * PER, top = o, bottom = o + SEGMENTS + 1;
    for (var s = 0; s < SEGMENTS; s++) {
      var a = 1 + s, b = 1 + (s + 1) % SEGMENTS;
      var shade = Math.floor(4 * s / SEGMENTS) % 2 ? WHEEL_DARK : WHEEL_LIGHT;
      [[top, top + a, top + b, shade], [bottom, bottom + b, bottom + a, shade],  // the two caps
       [top + a, bottom + a, bottom + b, WHEEL_RIM], [top + a, bottom + b, top + b, WHEEL_RIM]].forEach(function (f) {
        I.push(f[0]); J.push(f[1]); K.push(f[2]); facecolor.push(f[3]);
      });
    }
  });

  function wheelVertices(k) {  // design-frame vertices of every wheel at frame k (its angles)
    var out = [];
    wheels.forEach(function (w, n) {
      var angle = c.frames.angle[k][n];
      [1, -1].forEach(function (side) {
        var centre = [0, 1, 2].map(function (i) { return w.g[i] * (w.out + side * thick / 2); });
        out.push(centre);
        for (var s = 0; s < SEGMENTS; s++) {
          var phi = angle + 2 * Math.PI * s / SEGMENTS, cs = radius * Math.cos(phi), sn = radius * Math.sin(phi);
          out.push([0, 1, 2].map(function (i) { return centre[i] + cs * w.e1[i] + sn * w.e2[i]; }));
        }
      });
    });
    return out;
  }

  function columns(points, M) {  // {x, y, z} of the points turned by M
    var x = [], y = [], z = [];
    points.forEach(function (p) { var q = apply(M, p); x.push(q[0]); y.push(q[1]); z.push(q[2]); });
    return {x: x, y: y, z: z};
  }

  // ---- arrows: the commanded torque and the dipole, each with its own scale -------------------
  var torques = c.frames.torque, dipoles = c.frames.dipole;
  var sT = 0.9 * size / (peak(torques) || 1), sM = dipoles ? 0.9 * size / (peak(dipoles) || 1) : 0;
  function arrow(color, name) {
    return {type: "scatter3d", mode: "lines+markers", x: [0, 0], y: [0, 0], z: [0, 0], name: name,
            hoverinfo: "skip", line: {color: color, width: 7, dash: "dash"},
            marker: {size: [0, 6], color: color, symbol: "diamond"}};
  }
  function segment(v, s, M) {
    var q = apply(M, apply(AXES, v));
    return {x: [0, q[0] * s], y: [0, q[1] * s], z: [0, q[2] * s]};
  }

  function traces(view) {
    var out = [];
    if (wheels.length) {
      out.push({type: "mesh3d", x: [], y: [], z: [], i: I, j: J, k: K, facecolor: facecolor, flatshading: true,
                lighting: LIGHT, hoverinfo: "skip", showlegend: true,
                name: "reaction wheels (" + wheels.length + "), turned by their angle relative to the body"});
    }
    out.push(arrow(GREEN, view === "ground"
      ? "commanded torque, green (N m): 1 mN m drawn as " + fmt(sT * 1e-3) + " m"
      : "commanded torque (N m), same scale"));
    if (dipoles) {
      out.push(arrow(PURPLE, view === "ground"
        ? "magnetorquer dipole, purple (A m^2): 1 A m^2 drawn as " + fmt(sM) + " m"
        : "magnetorquer dipole (A m^2), same scale"));
    }
    if (c.estimate) {
      out.push({type: "scatter3d", mode: "lines", x: [], y: [], z: [], hoverinfo: "skip",
                name: "estimated principal axes (the filter's attitude), red dashed",
                line: {color: RED, width: 4, dash: "dash"}});
    }
    return out;
  }

  // ---- the filter's estimate: its principal axes, turned from the body's by turn[k] -----------
  var reach = 1.3 * size;
  function estimateAxes(k, M) {
    var x = [], y = [], z = [], turn = c.estimate.turn[k];
    if (!turn) { return {x: x, y: y, z: z}; }  // the filter has not started
    for (var i = 0; i < 3; i++) {
      var q = apply(M, apply(AXES, [turn[0][i], turn[1][i], turn[2][i]]));
      x.push(0, q[0] * reach, null); y.push(0, q[1] * reach, null); z.push(0, q[2] * reach, null);
    }
    return {x: x, y: y, z: z};
  }

  // ---- the readout and the time plot ------------------------------------------------------------
  var readout = document.getElementById("tumble-readout"), plot = document.getElementById("tumble-error");
  var curve = c.curve, marker = 0;
  function install() {
    var lo = Infinity, hi = 0;
    curve.y.forEach(function (y) { if (y > 0) { lo = Math.min(lo, y); hi = Math.max(hi, y); } });
    if (!(hi > 0)) { lo = 1e-3; hi = 1; }
    var lines = [{type: "scatter", mode: "lines", x: curve.t, y: curve.y, line: {color: "#1f77b4", width: 1.5},
                  name: curve.name + " (" + curve.unit + ")"}];
    if (c.estimate) {
      var known = c.estimate.curve;
      lines.push({type: "scatter", mode: "lines", x: known.t, y: known.y, line: {color: RED, width: 1.2},
                  name: known.name + " (" + known.unit + ")"});
      known.y.forEach(function (y) { if (y > 0) { lo = Math.min(lo, y); hi = Math.max(hi, y); } });
    }
    if (curve.threshold != null) {
      lines.push({type: "scatter", mode: "lines", x: [curve.t[0], curve.t[curve.t.length - 1]],
                  y: [curve.threshold, curve.threshold], name: "detumble threshold",
                  line: {color: "#7f7f7f", width: 1, dash: "dot"}, hoverinfo: "skip"});
      lo = Math.min(lo, curve.threshold); hi = Math.max(hi, curve.threshold);
    }
    marker = lines.length;
    lines.push({type: "scatter", mode: "lines", x: [0, 0], y: [lo, hi], name: "now",  // dashed: not an axis line
                line: {color: "black", width: 1, dash: "dash"}, hoverinfo: "skip"});
    var what = curve.name === "|omega|" ? "|omega|, the body's rate" : "attitude error: the angle from the target to the body";
    var layout = {
      margin: {l: 60, r: 10, t: 30, b: 45}, title: {text: what + " (log scale)", font: {size: 15}},
      xaxis: {title: {text: "t (s)"}}, yaxis: {title: {text: curve.name + " (" + curve.unit + ")"}, type: "log"},
      legend: {x: 1.01, xanchor: "left", y: 1},
    };
    var notes = ["Live mode (a free body integrated in the browser) does not apply to a closed-loop run: the page " +
                 "plays the simulated run only."];
    if (curve.stride > 1) {
      notes.push("The " + curve.name + " curve keeps one sample in " + curve.stride + " of the " + curve.samples + ".");
    }
    if (c.aliased) {
      notes.push("The wheels turn by more than half a revolution between frames: their discs move stroboscopically " +
                 "(the wagon-wheel effect); the readout gives their speed. Raise --frames to see them turn.");
    }
    document.getElementById("tumble-control-note").textContent = notes.join(" ");
    return Plotly.react(plot, lines, layout, CONFIG);
  }

  function describe(k) {
    var parts = c.frames.speed[k].map(function (s, n) { return "wheel " + (n + 1) + ": " + (s * RPM).toFixed(0) + " rpm"; });
    parts.push("commanded torque " + norm(torques[k]).toExponential(2) + " N m");
    if (dipoles) { parts.push("dipole " + norm(dipoles[k]).toExponential(2) + " A m^2"); }
    return parts.join(" \u00b7 ");
  }

  function frame(k, M) {
    var one = [[1, 0, 0], [0, 1, 0], [0, 0, 1]], ground = [], body = [];
    if (wheels.length) {
      var points = wheelVertices(k);
      ground.push(columns(points, M)); body.push(columns(points, one));
    }
    ground.push(segment(torques[k], sT, M)); body.push(segment(torques[k], sT, one));
    if (dipoles) { ground.push(segment(dipoles[k], sM, M)); body.push(segment(dipoles[k], sM, one)); }
    if (c.estimate) { ground.push(estimateAxes(k, M)); body.push(estimateAxes(k, one)); }
    readout.textContent = describe(k);
    var t = c.frames.t[k];
    return {ground: ground, body: body, done: Plotly.restyle(plot, {x: [[t, t]]}, [marker])};
  }

  window.tumbleExtra = {traces: traces, install: install, frame: frame};
})();
