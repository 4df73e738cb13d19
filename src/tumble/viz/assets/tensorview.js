/*
 * tumble's page of a tumble tensor output folder (tumble view DIR; tumble.viz.tensor_page).
 *
 * Data: tumble-data (tumble.viz.tensor_page.tensor_page_data): the object's estimate
 * ("object": mass kg, principal moments and their std kg m^2, principal axes as columns, centre
 * of mass and its std m, sensor frame), "adequate", "chi2_dof", "z95", the equivalent uniform
 * box ("box": edges, corners and triangles, sensor frame, mm) and one entry per throw ("throws":
 * t s from the release, measured and model rates as three rows rad/s, rotor rad/s, its own
 * principal moments and their std or null, status, reason).
 *
 * Draws, with plotly.js (inlined before this file): the chosen throw's rates (samples as dots,
 * the fitted model as lines) and its rotor speed; the principal moments throw by throw with the
 * pooled value and its 95 % interval; the equivalent box in the sensor frame. Sets
 * window.tumbleTensor = {ready, show(k) -> Promise, shown} and fires "tumble:ready" on document
 * once everything is drawn.
 */
(function () {
  "use strict";

  var COLORS = ["#1f77b4", "#ff7f0e", "#2ca02c"];  // as the matplotlib figures (C0, C1, C2)
  var AXES = ["x", "y", "z"];
  var CONFIG = {displaylogo: false, responsive: true, topojsonURL: ""};
  var data = JSON.parse(document.getElementById("tumble-data").textContent);
  var obj = data.object;
  var el = function (id) { return document.getElementById(id); };
  var select = el("tumble-throw"), readout = el("tumble-throw-readout");

  function fmt(x, digits) { return Number(Number(x).toPrecision(digits || 4)).toString(); }
  function vec(v, scale, digits) {
    return "(" + v.map(function (x) { return fmt(x * (scale || 1), digits || 3); }).join(", ") + ")";
  }
  function fitted(th) { return th.samples > 0; }

  function summary() {
    var m = obj.principal_moments, s = obj.principal_moments_std;
    var parts = ["object " + fmt(obj.mass) + " kg (as weighed)",
                 "centre of mass " + vec(obj.center_of_mass, 1e3) + " \u00b1 " + vec(obj.center_of_mass_std, 1e3, 2) +
                 " mm from the accelerometer (sensor frame)",
                 "principal moments " + [0, 1, 2].map(function (j) {
                   return "I" + (j + 1) + " = " + fmt(m[j], 5) + " \u00b1 " + fmt(s[j], 2);
                 }).join(", ") + " kg m^2 (about its centre of mass; \u00b1 one standard uncertainty)"];
    var used = data.throws.filter(function (th) { return th.status === "used"; }).length;
    parts.push(used + " of " + data.throws.length + " throws used" +
               (data.chi2_dof === null ? "" : ", chi2/dof " + fmt(data.chi2_dof, 2)));
    parts.push(data.adequate ? "the model describes the throws" : "NOT ADEQUATE: the model does not describe every throw");
    el("tumble-summary").textContent = parts.join("; ") + ".";
    var skipped = data.throws.filter(function (th) { return th.status !== "used"; }).map(function (th) {
      return "throw " + th.number + " (" + th.input + "): " + th.reason;
    });
    el("tumble-notes").textContent = (skipped.length ? "Skipped: " + skipped.join("; ") + ". " : "") +
      "Rates in the sensor frame, the model with the fitted gyroscope bias; time from each throw's release. " +
      "The box is the uniform box of the object's mass with the estimated principal moments, drawn at the " +
      "estimated centre of mass along the principal axes (minor = longest edge).";
  }

  function ratesTraces(th) {
    var traces = [];  // as tensor.png: the samples as grey dots, the model's coloured lines over them
    [0, 1, 2].forEach(function (j) {
      traces.push({type: "scatter", mode: "markers", x: th.t, y: th.measured[j], name: "measured w" + AXES[j],
                   marker: {color: "#8c8c8c", size: 3, opacity: 0.5}});
    });
    [0, 1, 2].forEach(function (j) {
      traces.push({type: "scatter", mode: "lines", x: th.t, y: th.model[j], name: "model w" + AXES[j],
                   line: {color: COLORS[j], width: 1.5}});
    });
    return traces;
  }

  function show(k) {
    var th = data.throws[k];
    var flight = (th.t_release !== null && th.t_end !== null) ? ", flight " + fmt(th.t_release, 6) + " to " +
      fmt(th.t_end, 6) + " s (" + fmt(th.t_end - th.t_release, 3) + " s)" : "";
    var parts = ["throw " + th.number + ": " + th.input + ", " + th.status + (th.reason ? " (" + th.reason + ")" : "") +
                 flight, th.samples + " samples" + (th.stride > 1 ? " (1 in " + th.stride + " drawn)" : "")];
    if (th.residual_rms !== null) { parts.push("residual RMS " + fmt(th.residual_rms, 3) + " rad/s"); }
    if (th.moments) {
      parts.push("its own moments " + vec(th.moments, 1, 4) + " \u00b1 " + vec(th.moments_std, 1, 2) + " kg m^2");
    }
    readout.textContent = parts.join("; ");
    var xaxis = {title: {text: "time since the release (s)"}, zeroline: false};
    var rates = Plotly.react(el("tumble-rates"), ratesTraces(th), {
      title: {text: "throw " + th.number + ": gyroscope samples (dots) and the fitted model (lines)", font: {size: 14}},
      margin: {l: 60, r: 10, t: 36, b: 44}, xaxis: xaxis, yaxis: {title: {text: "angular velocity (rad/s)"}},
      legend: {orientation: "h", y: -0.22}, uirevision: "rates" + k,
    }, CONFIG);
    var rotor = Plotly.react(el("tumble-rotor"), [
      {type: "scatter", mode: "lines", x: th.t, y: th.rotor, name: "rotor speed", line: {color: "#555", width: 1.5}},
    ], {
      title: {text: "the rotor's logged speed relative to the device", font: {size: 13}},
      margin: {l: 60, r: 10, t: 32, b: 40}, xaxis: xaxis, yaxis: {title: {text: "rad/s"}}, showlegend: false,
      uirevision: "rotor" + k,
    }, CONFIG);
    window.tumbleTensor.shown = k;
    return Promise.all([rates, rotor]);
  }

  function moments() {
    var n = data.throws.length, traces = [], layout = {
      title: {text: "principal moments of the object: each throw \u00b1 1 std, pooled with its 95 % interval",
              font: {size: 14}, y: 0.98, yanchor: "top"},
      margin: {l: 70, r: 10, t: 64, b: 44}, showlegend: true,
      legend: {orientation: "h", x: 0, y: 1.02, yanchor: "bottom", font: {size: 11}},
    };
    var used = data.throws.filter(function (th) { return th.moments; });
    [0, 1, 2].forEach(function (j) {
      var suffix = j === 0 ? "" : String(j + 1), value = obj.principal_moments[j];
      var half = data.z95 * obj.principal_moments_std[j], lo = 0.5, hi = n + 0.5;
      var axes = {xaxis: "x" + suffix, yaxis: "y" + suffix};
      traces.push(Object.assign({type: "scatter", mode: "lines", x: [lo, hi, hi, lo, lo],
        y: [value - half, value - half, value + half, value + half, value - half], fill: "toself",
        fillcolor: "rgba(80,80,80,0.15)", line: {width: 0}, name: "pooled 95 % interval", legendgroup: "band",
        showlegend: j === 0, hoverinfo: "skip"}, axes));
      traces.push(Object.assign({type: "scatter", mode: "lines", x: [lo, hi], y: [value, value],
        line: {color: "black", width: 1.5}, name: "pooled", legendgroup: "pooled", showlegend: j === 0}, axes));
      traces.push(Object.assign({type: "scatter", mode: "markers",
        x: used.map(function (th) { return th.number; }), y: used.map(function (th) { return th.moments[j]; }),
        error_y: {type: "data", array: used.map(function (th) { return th.moments_std[j]; }), visible: true},
        marker: {color: COLORS[j], size: 7}, name: "I" + (j + 1) + " of each throw"}, axes));
      var left = j / 3 + 0.04, right = (j + 1) / 3 - 0.02;
      layout["xaxis" + suffix] = {domain: [left, right], range: [lo, hi], dtick: 1, title: {text: "throw"},
                                  anchor: "y" + suffix};
      layout["yaxis" + suffix] = {title: {text: "I" + (j + 1) + " (kg m^2)"}, exponentformat: "e",
                                  anchor: "x" + suffix};
    });
    return Plotly.newPlot(el("tumble-moments"), traces, layout, CONFIG);
  }

  function shape() {
    var box = data.box, c = box.corners, traces = [];
    var col = function (rows, j) { return rows.map(function (r) { return r[j]; }); };
    traces.push({type: "mesh3d", x: col(c, 0), y: col(c, 1), z: col(c, 2), i: col(box.faces, 0),
                 j: col(box.faces, 1), k: col(box.faces, 2), color: "#9fb3c8", opacity: 0.45, flatshading: true,
                 name: "equivalent uniform box " + box.edges.map(function (e) { return fmt(e, 3); }).join(" x ") +
                       " mm", showlegend: true, hoverinfo: "name"});
    var com = obj.center_of_mass.map(function (x) { return 1e3 * x; });
    var reach = Math.max.apply(null, box.edges.concat([1]));
    [0, 1, 2].forEach(function (j) {
      var half = 0.6 * Math.max(box.edges[j], 0.15 * reach), a = [0, 1, 2].map(function (i) {
        return obj.principal_axes[i][j];
      });
      traces.push({type: "scatter3d", mode: "lines", x: [com[0] - half * a[0], com[0] + half * a[0]],
                   y: [com[1] - half * a[1], com[1] + half * a[1]], z: [com[2] - half * a[2], com[2] + half * a[2]],
                   line: {color: COLORS[j], width: 6}, name: "principal axis " + (j + 1) + " (I" + (j + 1) + ")"});
    });
    traces.push({type: "scatter3d", mode: "markers", x: [com[0]], y: [com[1]], z: [com[2]],
                 marker: {color: "black", size: 4}, name: "centre of mass"});
    var s = 0.25 * reach;
    traces.push({type: "scatter3d", mode: "lines+markers", x: [s, 0, 0, 0, 0], y: [0, 0, s, 0, 0], z: [0, 0, 0, 0, s],
                 marker: {size: 2, color: "#d62728"}, line: {color: "#d62728", width: 3},
                 name: "sensor axes x, y, z from the accelerometer (origin)"});
    return Plotly.newPlot(el("tumble-shape"), traces, {
      title: {text: "the object's equivalent uniform box in the sensor frame (mm)", font: {size: 14}},
      margin: {l: 0, r: 0, t: 40, b: 0}, legend: {x: 0, y: 0.98, bgcolor: "rgba(255,255,255,0.7)", font: {size: 11}},
      scene: {aspectmode: "data", xaxis: {title: {text: "x (mm)"}}, yaxis: {title: {text: "y (mm)"}},
              zaxis: {title: {text: "z (mm)"}}},
    }, CONFIG);
  }

  window.tumbleTensor = {ready: false, show: show, shown: null};
  summary();
  var first = -1;
  data.throws.forEach(function (th, k) {
    if (!fitted(th)) { return; }
    if (first < 0) { first = k; }
    var option = document.createElement("option");
    option.value = String(k);
    option.textContent = "throw " + th.number + ": " + th.input + " (" + th.status + ")";
    select.appendChild(option);
  });
  select.addEventListener("change", function () { show(Number(select.value)); });
  var drawn = [moments(), shape()];
  if (first >= 0) { drawn.push(show(first)); }
  else {
    select.disabled = true;
    readout.textContent = "no throw has fitted samples to show";
  }
  Promise.all(drawn).then(function () {
    window.tumbleTensor.ready = true;
    document.dispatchEvent(new Event("tumble:ready"));
  });
})();
