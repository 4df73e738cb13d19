/*
 * tumble's interactive page, a fit's flights (tumble view DIR of a tumble fit output folder).
 *
 * Data: tumble-data's "fit" (tumble.viz.fit_page.fit_page_data): one entry per used flight with
 * the fitted body (moments in units of I3, the drawn box's half-sizes along the principal axes),
 * the replay at the flight's sample times (t from its first sample, s; quat principal -> world;
 * omega of the fit's model, principal frame, rad/s), the measured rates (principal frame, bias
 * removed, or null), and the polhode picture (L in the body frame, I3 = 1 kg m^2: the sphere
 * |L| = L_norm, the energy ellipsoid sum L_i^2 / I_i = energy2, the torque-free polhode through
 * the start, the separatrices, the flight's L traced on the sphere).
 *
 * Inlined before viewer.js; it gives the viewer the first flight to draw (window.tumbleFirstRun),
 * waits for "tumble:ready", then fills the flight selector and plays the chosen flight with
 * window.tumbleViewer.setRun({..., extra}) (the interface is described at
 * the head of viewer.js): the extra adds the measured rates to the omega(t) plot, draws the
 * polhode plot and moves its marker with the frames.
 */
(function () {
  "use strict";

  var CURVE_COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c"];  // as viewer.js's omega curves
  var ROLES = ["minor", "intermediate", "major"];
  var CONFIG = {displaylogo: false, responsive: true, topojsonURL: ""};
  var data = JSON.parse(document.getElementById("tumble-data").textContent);
  var fit = data.fit;
  if (!fit) { return; }
  var select = document.getElementById("tumble-flight");
  var readout = document.getElementById("tumble-fit-readout");
  var note = document.getElementById("tumble-fit-note");
  var plot = document.getElementById("tumble-polhode");

  function fmt(x) { return Number(Number(x).toPrecision(3)).toString(); }
  function column(rows, j) { return rows.map(function (r) { return r[j]; }); }

  function surface(semi, name, color, opacity) {  // an ellipsoid of semi-axes semi (a sphere if equal)
    var x = [], y = [], z = [], n = 36, m = 18;
    for (var i = 0; i <= m; i++) {
      var th = Math.PI * i / m, rx = [], ry = [], rz = [];
      for (var k = 0; k <= n; k++) {
        var ph = 2 * Math.PI * k / n;
        rx.push(semi[0] * Math.sin(th) * Math.cos(ph));
        ry.push(semi[1] * Math.sin(th) * Math.sin(ph));
        rz.push(semi[2] * Math.cos(th));
      }
      x.push(rx); y.push(ry); z.push(rz);
    }
    return {type: "surface", x: x, y: y, z: z, name: name, showscale: false, opacity: opacity, hoverinfo: "skip",
            colorscale: [[0, color], [1, color]], showlegend: true};
  }

  function line(points, name, color, width, dash) {
    return {type: "scatter3d", mode: "lines", x: column(points, 0), y: column(points, 1), z: column(points, 2),
            name: name, hoverinfo: "skip", line: {color: color, width: width, dash: dash || "solid"}};
  }

  function nearest(ts, t) {  // index of the sample time nearest t (ts ascending)
    var lo = 0, hi = ts.length - 1;
    while (hi - lo > 1) { var mid = (lo + hi) >> 1; if (ts[mid] <= t) { lo = mid; } else { hi = mid; } }
    return Math.abs(ts[hi] - t) < Math.abs(ts[lo] - t) ? hi : lo;
  }

  function extraFor(f) {
    var marker = 0;
    return {
      translucent: false,
      traces: function () { return []; },
      omegaTraces: function () {
        if (!f.measured) { return []; }
        return [0, 1, 2].map(function (j) {
          return {type: "scatter", mode: "markers", x: f.t, y: column(f.measured, j),
                  name: "measured omega_" + (j + 1) + " (" + ROLES[j] + ")",
                  marker: {color: CURVE_COLORS[j], size: 4, opacity: 0.6}};
        });
      },
      install: function () {
        var I = f.moments, r = f.L_norm, e = f.energy2;
        var traces = [
          surface([r, r, r], "momentum sphere |L| = " + fmt(r) + " (I3 rad/s)", "#9fb3c8", 0.25),
          surface([Math.sqrt(e * I[0]), Math.sqrt(e * I[1]), Math.sqrt(e * I[2])],
                  "energy ellipsoid of the start (2E = " + fmt(e) + " I3 rad^2/s^2)", "#f2c14e", 0.12),
        ];
        f.separatrices.forEach(function (c, k) {
          var t = line(c, "separatrices (meet at the intermediate axis)", "#7f7f7f", 2, "dot");
          t.showlegend = k === 0; t.legendgroup = "sep";
          traces.push(t);
        });
        traces.push(line(f.polhode, "polhode through the start (sphere meets ellipsoid)", "black", 4, "dash"));
        traces.push(line(f.trace, "the flight's L (body frame)" + (f.L_drop > 1e-6 ? ", on the sphere" : ""),
                         "#d62728", 5));
        marker = traces.length;
        traces.push({type: "scatter3d", mode: "markers", x: [f.trace[0][0]], y: [f.trace[0][1]], z: [f.trace[0][2]],
                     name: "L now", hoverinfo: "skip", marker: {color: "#d62728", size: 6}});
        var R = 1.3 * r, axis = function (name) {
          return {title: {text: name}, range: [-R, R], autorange: false};
        };
        var layout = {
          title: {text: "polhode: L in the body frame on the momentum sphere (principal axes; units of I3 rad/s)",
                  font: {size: 15}},
          margin: {l: 0, r: 0, t: 40, b: 0}, uirevision: String(Math.random()),
          legend: {x: 0, y: 0.99, bgcolor: "rgba(255,255,255,0.7)", font: {size: 11}},
          scene: {xaxis: axis("L1 (minor)"), yaxis: axis("L2 (intermediate)"), zaxis: axis("L3 (major)"),
                  aspectmode: "cube", camera: {eye: {x: 1.3, y: 1.1, z: 0.8}}},
        };
        var notes = ["The body: a uniform box whose principal moments stand in the fitted ratios (I1/I3 = " +
                     fmt(f.ratios[0]) + ", I2/I3 = " + fmt(f.ratios[1]) + "), longest edge 1 (lengths in units of " +
                     "it), I3 = 1 (L in units of I3 times rad/s); drawn at least 1 % of its length thick. The ground " +
                     "frame is chosen with L at the flight's start along +z. omega(t): the fit's model (lines) and " +
                     "the gyroscope's samples (dots), both in the principal frame, the bias removed; t from the " +
                     "flight's first sample."];
        if (f.drag !== "none") {
          notes.push("The model has " + f.drag + " drag: |L| falls by " + fmt(100 * f.L_drop) +
                     " % over the flight, so L's direction is traced, scaled onto the sphere of the start.");
        }
        if (f.note) { notes.push(f.note + "."); }
        note.textContent = notes.join(" ");
        return Plotly.react(plot, traces, layout, CONFIG);
      },
      frame: function (k, M, t) {
        var i = nearest(f.t, t), p = f.trace[i], parts = [];
        parts.push("t = " + t.toFixed(3) + " s: model omega = (" + f.omega[i].map(fmt).join(", ") + ") rad/s");
        if (f.measured) { parts.push("measured (" + f.measured[i].map(fmt).join(", ") + ") rad/s"); }
        readout.textContent = header(f) + " \u00b7 " + parts.join(", ");
        return {ground: [], body: [],
                done: Plotly.restyle(plot, {x: [[p[0]]], y: [[p[1]]], z: [[p[2]]]}, [marker])};
      },
    };
  }

  function header(f) {
    var parts = ["I1/I3 = " + fmt(f.ratios[0]), "I2/I3 = " + fmt(f.ratios[1]), "drag " + f.drag];
    if (f.residual_rms != null) { parts.push("residual " + fmt(f.residual_rms) + " rad/s"); }
    return parts.join(", ");
  }

  function run(k) {
    var f = fit.flights[k];
    return {
      t: f.t, quat: f.quat, omega: f.omega, moments: f.moments, box: f.box, frames: f.frames,
      torqueFree: f.torque_free, title: data.title + " \u2014 " + f.label, extra: extraFor(f),
    };
  }
  function play(k) { return window.tumbleViewer.setRun(run(k)); }
  window.tumbleFirstRun = function () { return run(0); };  // the viewer draws the first flight first

  function start() {
    fit.flights.forEach(function (f, k) {
      var option = document.createElement("option");
      option.value = String(k);
      option.textContent = f.label;
      select.appendChild(option);
    });
    select.addEventListener("change", function () { play(Number(select.value)); });
  }

  if (window.tumbleViewer && window.tumbleViewer.ready) { start(); }
  else { document.addEventListener("tumble:ready", start, {once: true}); }
})();
