/*
 * Live mode of tumble's interactive page: edit the principal moments and the initial omega (or
 * pick a preset), press Run, and the free motion is recomputed in the browser by tumble's
 * splitting integrator (splitting.js, window.tumbleSplitting) and played by the page's viewer
 * (viewer.js, window.tumbleViewer.setRun).
 *
 * Conventions (docs/conventions.md): SI units; moments ascending I1 <= I2 <= I3 (kg m^2); omega in
 * the principal frame (rad/s); quaternions principal -> world, scalar last.
 *
 * A body other than the page's is drawn as the uniform box with the given principal moments:
 * for a box of mass m and half-sizes a, b, c along the principal axes,
 * I1 = m (b^2 + c^2) / 3, I2 = m (a^2 + c^2) / 3, I3 = m (a^2 + b^2) / 3 (edges 2a, 2b, 2c in
 * I_x = m (b^2 + c^2) / 12 and cyclic, Meriam & Kraige Table D/4, as tumble.mass.Box), hence
 * a^2 = 3 (I2 + I3 - I1) / (2 m) and cyclic: real exactly when the triangle inequality holds.
 *
 * window.tumbleLive: {run(), reset(), presets, lastRun: {t, omega, quat, moments, omega0, quat0,
 * order, step, box}, drawn: runs the viewer has installed, error: the last error message or ""}.
 * Nothing here throws: every error is shown in the form (#tumble-live-error).
 */
(function () {
  "use strict";

  var FRAMES = 401;          // samples of a live run, evenly spaced over [0, t_end]
  var MAX_T_END = 1000.0;    // s: a live run must stay quick in the browser
  // Yoshida's 6th order: 1e-9 to 1e-8 of |omega| over 20 s at the default step (against the closed form)
  var ORDER = 6;
  var BOX_MASS = 1.0;        // kg: mass of the box drawn for moments other than the page's body's
  var THIN = 0.02;           // a planar body's box is drawn THIN times its longest half-size thick
  var RTOL = 1e-9;           // moments this close (relative) are the page's body's

  var live = { lastRun: null, drawn: 0, error: "", presets: [] };
  window.tumbleLive = live;

  function pageData() {
    var node = document.getElementById("tumble-data");
    if (!node) return null;
    try { return JSON.parse(node.textContent); } catch (e) { return null; }
  }

  function round(x, digits) { return Number(x.toPrecision(digits)); }

  /** Half-sizes (m) of the uniform box of mass m (kg) with principal moments I (kg m^2). */
  function boxHalfSizes(I, m) {
    var h = [I[1] + I[2] - I[0], I[0] + I[2] - I[1], I[0] + I[1] - I[2]].map(function (s) {
      return Math.sqrt(Math.max(0.0, 1.5 * s / m));
    });
    var floor = THIN * Math.max(h[0], h[1], h[2]);
    return h.map(function (x) { return Math.max(x, floor); });
  }

  function presets(data) {
    var list = [];
    if (data && data.moments && data.omega0) {
      var I = data.moments, w = data.omega0;
      var spin = round(Math.hypot(w[0], w[1], w[2]), 3) || 10.0, p = round(0.01 * spin, 3);
      list.push({ name: "this body (" + data.body_name + "), the page's initial omega", moments: I, omega0: w });
      list.push({ name: "stable: this body spun about its smallest axis (1)", moments: I, omega0: [spin, p, p] });
      list.push({ name: "stable: this body spun about its largest axis (3)", moments: I, omega0: [p, p, spin] });
    }
    // the fixed presets come from tumble (tumble.viz.page.live_presets): the seed's T-handle, a
    // near-symmetric plate and Brody's measured racket, with their sources
    (data && data.presets || []).forEach(function (p) { list.push(p); });
    return list;
  }

  // ---- the form --------------------------------------------------------------------------------
  var el = {};

  function field(parent, id, label, unit, width) {
    var wrap = document.createElement("label");
    wrap.style.marginRight = "6px";
    wrap.appendChild(document.createTextNode(label + " "));
    var input = document.createElement("input");
    input.id = id;
    input.type = "text";
    input.inputMode = "decimal";
    input.size = width || 15;  // the 12 significant digits a preset fills in, sign and exponent: none cut
    input.setAttribute("aria-label", label + " (" + unit + ")");
    wrap.appendChild(input);
    if (unit) wrap.appendChild(document.createTextNode(" " + unit));
    parent.appendChild(wrap);
    return input;
  }

  function row(parent) {
    var div = document.createElement("div");
    div.style.margin = "3px 0";
    parent.appendChild(div);
    return div;
  }

  function build(root, data) {
    var box = document.createElement("fieldset");
    box.style.cssText = "border: 1px solid #bbb; padding: 4px 10px; margin: 4px 0; font-size: 14px;";
    var legend = document.createElement("legend");
    legend.textContent = "Live mode: a new free motion, computed in this browser";
    box.appendChild(legend);

    var r0 = row(box);
    r0.appendChild(document.createTextNode("preset "));
    el.preset = document.createElement("select");
    el.preset.id = "tumble-live-preset";
    live.presets.forEach(function (p, k) {
      var o = document.createElement("option");
      o.value = String(k);
      o.textContent = p.name;
      el.preset.appendChild(o);
    });
    r0.appendChild(el.preset);

    var r1 = row(box);
    r1.appendChild(document.createTextNode("principal moments, ascending: "));
    el.I = [1, 2, 3].map(function (i) { return field(r1, "tumble-live-I" + i, "I" + i, i === 3 ? "kg m^2" : ""); });
    var r2 = row(box);
    r2.appendChild(document.createTextNode("initial omega, principal frame: "));
    el.w = [1, 2, 3].map(function (i) { return field(r2, "tumble-live-w" + i, "omega_" + i, i === 3 ? "rad/s" : ""); });
    el.tEnd = field(r2, "tumble-live-tend", " t_end", "s", 6);
    el.run = document.createElement("button");
    el.run.id = "tumble-live-run";
    el.run.textContent = "Run";
    el.reset = document.createElement("button");
    el.reset.id = "tumble-live-reset";
    el.reset.textContent = "Reset";
    el.reset.title = "back to the page's own run";
    r2.appendChild(el.run);
    r2.appendChild(document.createTextNode(" "));
    r2.appendChild(el.reset);

    el.error = document.createElement("div");
    el.error.id = "tumble-live-error";
    el.error.setAttribute("role", "alert");
    el.error.style.cssText = "color: #b00020; margin: 2px 0;";
    box.appendChild(el.error);
    el.status = document.createElement("div");
    el.status.id = "tumble-live-status";
    el.status.style.cssText = "color: #444; margin: 2px 0; font-size: 13px;";
    box.appendChild(el.status);
    root.appendChild(box);

    el.preset.addEventListener("change", function () { fill(live.presets[Number(el.preset.value)]); });
    el.run.addEventListener("click", function (event) { event.preventDefault(); run(); });
    el.reset.addEventListener("click", function (event) { event.preventDefault(); reset(); });
    el.tEnd.value = pageTEnd(data);
    if (live.presets.length) fill(live.presets[0]);
  }

  /** The t_end field's value for the page's own run: its duration, or 20 s where it has none the
   * browser takes. Reset puts it back too (a t_end typed before it stayed: a teacher's walkthrough). */
  function pageTEnd(data) {
    return String(data && data.t_end > 0 && data.t_end <= MAX_T_END ? round(data.t_end, 6) : 20);
  }

  /** What the numbers do not say of a run started exactly on the intermediate axis (as tumble's
   * stability report notes it): it stays there, an unstable equilibrium, until perturbed. */
  function onAxisNote(moments, omega0, h) {
    var spun = omega0.filter(function (x) { return x !== 0; }).length;
    if (h || spun !== 1 || omega0[1] === 0 || !(moments[0] < moments[1] && moments[1] < moments[2])) return "";
    return " A spin exactly about the intermediate axis: an unstable equilibrium, which flips only once perturbed " +
      "(give omega_1 or omega_3 a little, 1 % of omega_2).";
  }

  function fill(preset) {
    for (var i = 0; i < 3; i++) {
      el.I[i].value = String(round(preset.moments[i], 12));
      el.w[i].value = String(round(preset.omega0[i], 12));
    }
    showError("");
  }

  function showError(message) {
    live.error = message;
    el.error.textContent = message;
  }

  function number(input, name, unit) {
    var text = input.value.trim(), x = Number(text);
    if (text === "" || !isFinite(x)) {
      throw new RangeError(name + " = '" + input.value + "' must be a finite number (" + unit + ")");
    }
    return x;
  }

  // ---- running -----------------------------------------------------------------------------------
  var data = null, pending = null;

  function samePage(moments) {
    if (!data || !data.moments) return false;
    return moments.every(function (m, i) { return Math.abs(m - data.moments[i]) <= RTOL * Math.abs(data.moments[i]); });
  }

  function massOf(moments) {
    var chosen = live.presets.filter(function (p) {
      return p.mass && p.moments.every(function (m, i) { return m === moments[i]; });
    });
    return chosen.length ? chosen[0].mass : BOX_MASS;
  }

  /** Largest relative change of the energy, |L| and L_world over the run (they are invariants).
   * With a rotor's constant momentum h: L = I w + h, and the energy is the gyrostat's conserved
   * sum I w^2 / 2 (tumble's traj.hamiltonian). */
  function drift(moments, omega, quat, h) {
    var S = window.tumbleSplitting, e = 0, l = 0, lw = 0, L0 = null, first = null;
    for (var k = 0; k < omega.length; k++) {
      var q = quat[k], x = q[0], y = q[1], z = q[2], w = q[3];
      var Lb = [moments[0] * omega[k][0] + h[0], moments[1] * omega[k][1] + h[1], moments[2] * omega[k][2] + h[2]];
      var inv = {energy: S.invariants(moments, omega[k]).energy, momentum: Math.hypot(Lb[0], Lb[1], Lb[2])};
      if (first === null) first = inv;
      var Lw = [  // R L with R the rotation of q (principal -> world)
        (1 - 2 * (y * y + z * z)) * Lb[0] + 2 * (x * y - z * w) * Lb[1] + 2 * (x * z + y * w) * Lb[2],
        2 * (x * y + z * w) * Lb[0] + (1 - 2 * (x * x + z * z)) * Lb[1] + 2 * (y * z - x * w) * Lb[2],
        2 * (x * z - y * w) * Lb[0] + 2 * (y * z + x * w) * Lb[1] + (1 - 2 * (x * x + y * y)) * Lb[2]];
      if (L0 === null) L0 = Lw;
      e = Math.max(e, Math.abs(inv.energy - first.energy));
      l = Math.max(l, Math.abs(inv.momentum - first.momentum));
      lw = Math.max(lw, Math.hypot(Lw[0] - L0[0], Lw[1] - L0[1], Lw[2] - L0[2]));
    }
    return { energy: first.energy > 0 ? e / first.energy : e, momentum: first.momentum > 0 ? l / first.momentum : l,
             world: first.momentum > 0 ? lw / first.momentum : lw };
  }

  function run() {
    try {
      var S = window.tumbleSplitting;
      if (!S) throw new Error("the integrator (splitting.js) is missing from this page");
      var moments = el.I.map(function (input, i) { return number(input, "I" + (i + 1), "kg m^2"); });
      var omega0 = el.w.map(function (input, i) { return number(input, "omega_" + (i + 1), "rad/s"); });
      var tEnd = number(el.tEnd, "t_end", "s");
      if (!(tEnd > 0 && tEnd <= MAX_T_END)) {
        throw new RangeError("t_end = " + tEnd + " s must be after 0 and at most " + MAX_T_END + " s in the browser");
      }
      var mine = samePage(moments);
      var quat0 = mine && data.quat0 ? data.quat0 : [0.0, 0.0, 0.0, 1.0];
      // the page's body with its wheels spinning at a constant rate: their momentum h goes into
      // Euler's equations, I w' + w x (I w + h) = 0, as in tumble's own run
      var h = mine && data.rotor_momentum ? data.rotor_momentum : null;
      var t = [];
      for (var k = 0; k < FRAMES; k++) t.push(k === FRAMES - 1 ? tEnd : tEnd * k / (FRAMES - 1));
      var out = S.propagate(moments, omega0, quat0, t, { order: ORDER, momentum: h });
      var box = mine ? null : boxHalfSizes(moments, massOf(moments));
      var d = drift(moments, out.omega, out.quat, h || [0, 0, 0]);
      live.lastRun = { t: t, omega: out.omega, quat: out.quat, moments: moments, omega0: omega0, quat0: quat0,
                       order: ORDER, step: out.step, box: box, momentum: h };
      showError("");
      el.status.textContent = "Computed here: tumble's splitting integrator (order " + ORDER + ", step " +
        (isFinite(out.step) ? out.step.toPrecision(3) + " s" : "one per sample: the body is at rest") +
        "), " + FRAMES + " samples over " + tEnd + " s. Largest change over the run (relative; invariants of " +
        "the free body): energy " + d.energy.toExponential(1) + ", |L| " + d.momentum.toExponential(1) +
        ", L_world " + d.world.toExponential(1) + "." + (box ? " Drawn as the uniform box with these moments (" +
        box.map(function (h) { return (2 * h).toPrecision(3); }).join(" x ") + " m)." : "") +
        (h ? " With the wheels' momentum h = [" + h.map(function (x) { return round(x, 4); }).join(", ") +
             "] kg m^2/s (principal frame), as in this page's run." :
         data && (data.torque_free === false || data.rigid === false)
          ? " This page's own run has a torque, rotors or a damper; the live run is the free rigid body." : "") +
        onAxisNote(moments, omega0, h);
      var title = "live run: I = [" + moments.join(", ") + "] kg m^2, omega0 = [" + omega0.join(", ") +
        "] rad/s, " + tEnd + " s";
      show({ t: t, quat: out.quat, omega: out.omega, moments: moments, box: box, title: title, momentum: h });
    } catch (e) {
      showError(e && e.message ? e.message : String(e));
    }
  }

  function viewerReady() {
    return window.tumbleViewer && window.tumbleViewer.ready;
  }

  function show(runData) {
    if (!viewerReady()) { pending = runData; return; }
    pending = null;
    try {
      Promise.resolve(window.tumbleViewer.setRun(runData)).then(function () { live.drawn += 1; }, function (e) {
        showError("the viewer could not show the run: " + (e && e.message ? e.message : e));
      });
    } catch (e) {
      showError("the viewer could not show the run: " + (e && e.message ? e.message : e));
    }
  }

  function reset() {
    showError("");
    pending = null;
    if (live.presets.length) {
      el.preset.value = "0";
      fill(live.presets[0]);
    }
    el.tEnd.value = pageTEnd(data);
    el.status.textContent = "";
    if (viewerReady()) {
      try {
        Promise.resolve(window.tumbleViewer.reset()).then(function () { live.drawn += 1; }, function (e) {
          showError("the viewer could not restore the page's run: " + (e && e.message ? e.message : e));
        });
      } catch (e) {
        showError("the viewer could not restore the page's run: " + (e && e.message ? e.message : e));
      }
    }
  }

  function init() {
    var root = document.getElementById("tumble-live");
    if (!root || root.childNodes.length) return;
    data = pageData();
    live.presets = presets(data);
    build(root, data);
    live.run = run;
    live.reset = reset;
    live.boxHalfSizes = boxHalfSizes;
  }

  document.addEventListener("tumble:ready", function () { if (pending) show(pending); });
  if (document.readyState === "loading") document.addEventListener("DOMContentLoaded", init);
  else init();
})();
