/*
 * tumble's splitting integrator of the FREE rigid body, ported to dependency-free JavaScript.
 *
 * A port of tumble.dynamics.methods.geometric.propagate for one torque-free body (its path
 * _propagate_free, with default_step and free_flow_substeps): the same sub-flows in the same
 * order, the same step choice and the same arithmetic for the momentum, so that the browser's
 * run agrees with tumble's Python run of the same input to round-off: the momentum bit for bit
 * wherever the C library's sin and cos round correctly (all but about 3 in 1e5 of these
 * angles with glibc), the attitude (a product of the same rotations, grouped differently) to a
 * few ulps. tests/test_page_live.py holds the two to 1e-9 of |omega| over 20 s; a run near the
 * separatrix (the seed's flip, 0.8 degrees off the intermediate axis) amplifies one ulp to ~2e-9
 * in 20 s, in tumble itself as here, and is held to that round-off floor instead.
 *
 * The method (as tumble.dynamics.methods.geometric cites it): the Hamiltonian
 * H = L1^2/(2 I1) + L2^2/(2 I2) + L3^2/(2 I3) splits into three terms whose flows are exact
 * rotations (McLachlan, Nonlinearity 6 (1993) 585; Touma & Wisdom, Astron. J. 107 (1994) 1189;
 * Dullweber, Leimkuhler & McLachlan, J. Chem. Phys. 107 (1997) 5840): under H_i the body-frame
 * momentum turns about e_i by -a and the attitude by +a, a = tau L_i / I_i. The step is the
 * symmetric (Strang) composition phi_1(h/2) phi_2(h/2) phi_3(h) phi_2(h/2) phi_1(h/2), 2nd
 * order, composed by Yoshida's coefficients (Phys. Lett. A 150 (1990) 262) to 4th order (triple
 * jump) or 6th order (his solution A). Every sub-step is a rotation, so |L| and the world-frame
 * momentum R L are kept to round-off and the energy error stays bounded (Hairer, Lubich &
 * Wanner, Geometric Numerical Integration, ch. VII.5, IX).
 *
 * Conventions (docs/conventions.md): SI units (kg m^2, rad/s, s); omega in the principal frame,
 * moments ascending I1 <= I2 <= I3; attitude quaternions map the principal (body) frame to the
 * world frame and are [x, y, z, w], scalar last, as scipy's.
 *
 * window.tumbleSplitting (and module.exports under Node):
 *   propagate(moments, omega0, quat0, times, {order: 2|4|6 = 4, step}) -> {omega, quat}
 *   defaultStep(spin, gain = 0, rate = 0), freeFlowSubsteps(order), checkMoments(moments),
 *   invariants(moments, omega) -> {energy, momentum}.
 * Bad input throws a SplittingInputError naming the field, the value and what is allowed.
 */
(function (root) {
  "use strict";

  /** Largest rotation per step of the default step, rad (geometric.MAX_STEP_ANGLE). */
  var MAX_STEP_ANGLE = 0.05;
  /** Relative tolerance of the physical-validity checks (tumble.mass.tensor.INERTIA_RTOL). */
  var INERTIA_RTOL = 1e-9;
  /** Most steps of one run in the browser (tumble allows 2e7): about a second, so the page stays responsive. */
  var MAX_STEPS = 1e6;

  var CBRT2 = Math.pow(2.0, 1.0 / 3.0);
  var Y4 = [1.0 / (2.0 - CBRT2), -CBRT2 / (2.0 - CBRT2), 1.0 / (2.0 - CBRT2)];
  var W6 = [0.784513610477560, 0.235573213359357, -1.17767998417887]; // Yoshida 1990, solution A
  var Y6 = W6.concat([1.0 - 2.0 * (W6[0] + W6[1] + W6[2])], W6.slice().reverse());
  /** Composition coefficients of the Strang step, by order. */
  var COMPOSITIONS = { 2: [1.0], 4: Y4, 6: Y6 };
  /** The Strang step as [axis, fraction of the step]: symmetric, so compositions merge the ends. */
  var STRANG = [[0, 0.5], [1, 0.5], [2, 1.0], [1, 0.5], [0, 0.5]];
  var NEXT = [[1, 2], [2, 0], [0, 1]];

  function SplittingInputError(message) {
    this.name = "SplittingInputError";
    this.message = message;
    this.stack = new Error(message).stack;
  }
  SplittingInputError.prototype = Object.create(Error.prototype);
  SplittingInputError.prototype.constructor = SplittingInputError;

  function refuse(message) {
    throw new SplittingInputError(message);
  }

  function show(v) {
    return Array.isArray(v) ? "[" + v.join(", ") + "]" : String(v);
  }

  /*
   * sin and cos rounded correctly (to the double nearest the exact value), for the momentum's
   * sub-flow angles. V8's Math.sin/cos (fdlibm, error < 1 ulp) and the C library behind
   * Python's math.sin/cos (glibc, correctly rounded in nearly every case) differ by 1 ulp for
   * about 1 argument in 1000 (measured on 2e5 angles in [-0.035, 0.035]); near the separatrix
   * of a flip such a difference grows some ten-millionfold over 20 s (measured: one ulp in omega0
   * moves tumble's own 20 s seed flip by up to 2e-9). Here sin x = x + x^3 P(x^2) and
   * cos x = 1 + x^2 Q(x^2) are summed in double and kept where every value within the error
   * bound rounds the same way; the rest (0.5 % on the seed's flip) sum the Taylor series in double-double
   * arithmetic (Dekker, Numer. Math. 18 (1971) 224: exact products by Veltkamp's splitting,
   * exact sums by Knuth's two-sum) and round once. Either way the result is the correctly
   * rounded value: the browser follows tumble's momentum bit for bit wherever glibc rounds
   * correctly too. |x| <= 1 only (the default step turns at most ~0.1 rad per sub-flow); beyond
   * it Math.sin/cos.
   */
  var SPLIT = 134217729.0; // 2^27 + 1: Veltkamp's split of a double into two 26-bit halves

  /**
   * sum_k (-1)^k x^(start + 2k) / (start + 2k)! in double-double (hi, lo), rounded once to a
   * double. Each term is the previous one times x^2 (an exact product: Dekker's two-product)
   * divided by (n + 1)(n + 2) (a double-double quotient); each sum is Knuth's two-sum. Written
   * out on scalars: no arrays, as it runs four times per sub-flow.
   */
  function taylor(x, start) {
    var c = SPLIT * x, xh = c - (c - x), xl = x - xh;
    var x2h = x * x, x2l = ((xh * xh - x2h) + 2.0 * xh * xl) + xl * xl;
    c = SPLIT * x2h;
    var bh = c - (c - x2h), bl = x2h - bh;
    var th = start === 0 ? 1.0 : x, tl = 0.0, sh = th, sl = 0.0;
    for (var n = start; ; n += 2) {
      // (th, tl) * (x2h, x2l), renormalised
      var p = th * x2h;
      c = SPLIT * th;
      var ah = c - (c - th), al = th - ah;
      var e = ((ah * bh - p) + ah * bl + al * bh) + al * bl + (th * x2l + tl * x2h);
      var mh = p + e, ml = e - (mh - p);
      // divided by d = -(n + 1)(n + 2), an integer of a few bits: q1 d is exact in two parts
      var d = -(n + 1) * (n + 2), q1 = mh / d;
      c = SPLIT * q1;
      var qh = c - (c - q1), ql = q1 - qh, qd = q1 * d, qe = (qh * d - qd) + ql * d;
      var r = mh - qd, rb = r - mh, re = (mh - (r - rb)) + (-qd - rb);
      var q2 = (r + (re - qe + ml)) / d;
      th = q1 + q2;
      tl = q2 - (th - q1);
      // (sh, sl) += (th, tl)
      var s = sh + th, sb = s - sh, se = (sh - (s - sb)) + (th - sb) + sl + tl;
      sh = s + se;
      sl = se - (sh - s);
      if (!(Math.abs(th) > 1e-34 * Math.abs(sh))) return sh + sl;
    }
  }

  // Taylor coefficients 1/3!, -1/5!, ... of (sin x - x) / x^3 and 1/2!, ... of (cos x - 1) / x^2,
  // to x^21 and x^20: the first omitted term is below 1e-21 of the sum for |x| <= 1
  var SIN_C = [3, 5, 7, 9, 11, 13, 15, 17, 19, 21].map(inverseFactorial);
  var COS_C = [2, 4, 6, 8, 10, 12, 14, 16, 18, 20].map(inverseFactorial);

  function inverseFactorial(n) {
    var f = 1.0;
    for (var k = 2; k <= n; k++) f *= k;
    return ((n / 2) | 0) % 2 === 1 ? -1.0 / f : 1.0 / f;
  }

  function horner(c, z) {
    var p = c[c.length - 1];
    for (var k = c.length - 2; k >= 0; k--) p = p * z + c[k];
    return p;
  }

  /**
   * head + t rounded correctly, t known to within 2^-48 |t| (a bound four times the Horner
   * sum's error): y = fl(head + t) and its exact remainder (Knuth's fast two-sum, |t| <= |head|);
   * when every value that close rounds to y too, y is the correctly rounded result; otherwise
   * (under 1 argument in 100 at the default step) the double-double series decides.
   */
  function roundedOrSeries(head, t, x, start) {
    var y = head + t, err = t - (y - head), b = Math.abs(t) * 3.552713678800501e-15;
    return y + (err + b) === y && y + (err - b) === y ? y : taylor(x, start);
  }

  function sinCR(x) {
    var ax = Math.abs(x);
    if (!(ax <= 1.0)) return Math.sin(x);
    if (ax < 1.4901161193847656e-8) return x; // |x| < 2^-26: x^3 / 6 is below half an ulp of x
    var z = x * x;
    return roundedOrSeries(x, x * (z * horner(SIN_C, z)), x, 1);
  }

  function cosCR(x) {
    if (!(Math.abs(x) <= 1.0)) return Math.cos(x);
    var z = x * x;
    return roundedOrSeries(1.0, z * horner(COS_C, z), x, 0);
  }

  /** The default largest step, s: MAX_STEP_ANGLE of rotation at the fastest spin (rad/s). */
  function defaultStep(spin, gain, rate) {
    var top = Math.max(spin + (gain || 0.0), rate || 0.0);
    return top > 0 ? MAX_STEP_ANGLE / top : Infinity;
  }

  /** The flattened sequence of exact sub-flows [axis, fraction of h] of one step. */
  function freeFlowSubsteps(order) {
    var gammas = COMPOSITIONS[order];
    if (gammas === undefined) refuse("order = " + show(order) + " is not available; allowed: 2, 4, 6");
    var seq = [];
    for (var g = 0; g < gammas.length; g++) {
      for (var s = 0; s < STRANG.length; s++) {
        var axis = STRANG[s][0], frac = STRANG[s][1];
        var last = seq[seq.length - 1];
        if (last !== undefined && last[0] === axis) last[1] = last[1] + gammas[g] * frac;
        else seq.push([axis, gammas[g] * frac]);
      }
    }
    return seq;
  }

  function isVector(v, n) {
    if (!Array.isArray(v) || v.length !== n) return false;
    for (var i = 0; i < n; i++) if (typeof v[i] !== "number" || !isFinite(v[i])) return false;
    return true;
  }

  /**
   * Principal moments a body can have (Goldstein sec. 5.4, as tumble.mass.tensor.check_inertia):
   * three finite positive numbers, ascending, with the triangle inequality I1 + I2 >= I3 (to
   * INERTIA_RTOL of the trace, as tumble allows for planar bodies).
   */
  function checkMoments(moments) {
    if (!isVector(moments, 3)) refuse("moments = " + show(moments) + " must be three finite numbers (kg m^2)");
    var tol = INERTIA_RTOL * (moments[0] + moments[1] + moments[2]);
    for (var i = 0; i < 3; i++) {
      if (!(moments[i] > tol)) {
        refuse("moments = " + show(moments) + ": I" + (i + 1) + " = " + moments[i] +
               " must be positive (kg m^2); a body with a zero moment has no well-posed rotation");
      }
    }
    if (!(moments[0] <= moments[1] && moments[1] <= moments[2])) {
      refuse("moments = " + show(moments) + " must be ascending, I1 <= I2 <= I3 (kg m^2)");
    }
    if (moments[2] - moments[0] - moments[1] > tol) {
      refuse("moments = " + show(moments) + " violate the triangle inequality I1 + I2 >= I3 (" +
             moments[0] + " + " + moments[1] + " < " + moments[2] + "); no distribution of positive mass has them");
    }
    return moments;
  }

  function checkTimes(times) {
    if (!Array.isArray(times) || times.length < 2) refuse("times must be at least two sample times (s)");
    for (var k = 0; k < times.length; k++) {
      if (typeof times[k] !== "number" || !isFinite(times[k])) {
        refuse("times[" + k + "] = " + times[k] + " is not a finite number (s)");
      }
      if (k > 0 && !(times[k] > times[k - 1])) {
        refuse("times must increase strictly; times[" + k + "] = " + times[k] + " follows " + times[k - 1]);
      }
    }
  }

  /** Kinetic energy 0.5 sum I w^2 (J) and |L| = |I w| (kg m^2/s) of one principal-frame omega. */
  function invariants(moments, omega) {
    var e = 0.0, l2 = 0.0;
    for (var i = 0; i < 3; i++) {
      var Li = moments[i] * omega[i];
      e += 0.5 * Li * omega[i];
      l2 += Li * Li;
    }
    return { energy: e, momentum: Math.sqrt(l2) };
  }

  /** Equal steps no longer than step that fill a sample interval dt (geometric._steps). */
  function steps(dt, step) {
    var n = Math.max(1, Math.ceil(dt / step - 1e-9));
    return [n, dt / n];
  }

  /**
   * Integrate one free body with the composed splitting, sampled at times.
   *
   * moments: [I1, I2, I3], kg m^2, ascending. omega0: principal frame, rad/s. quat0: principal
   * to world, [x, y, z, w] (normalised here). times: increasing, s, starting at the initial
   * time. options.order: 2, 4 (default) or 6; options.step: largest step, s (default
   * defaultStep(|omega0|)); options.momentum: a constant rotor momentum h (principal frame,
   * kg m^2/s; default none), a gyrostat I w' + w x (I w + h) = 0: L = I w + h and each sub-flow
   * turns by a = tau (L_i - h_i) / I_i, still an exact rotation about e_i (L_i is constant
   * under it), as tumble's geometric methods do. Returns {omega: n x 3 (rad/s), quat: n x 4,
   * step: s, substeps: h}.
   */
  function propagate(moments, omega0, quat0, times, options) {
    options = options || {};
    var order = options.order === undefined ? 4 : options.order;
    checkMoments(moments);
    if (!isVector(omega0, 3)) refuse("omega0 = " + show(omega0) + " must be three finite numbers (rad/s)");
    if (!isVector(quat0, 4)) refuse("quat0 = " + show(quat0) + " must be four finite numbers [x, y, z, w]");
    checkTimes(times);
    var subflows = freeFlowSubsteps(order);
    var inv = invariants(moments, omega0);
    if (!isFinite(inv.energy) || !isFinite(inv.momentum)) {
      refuse("omega0 = " + show(omega0) + " rad/s is too large: the kinetic energy of this body overflows");
    }
    var hv = options.momentum === undefined || options.momentum === null ? [0, 0, 0] : options.momentum;
    if (!isVector(hv, 3)) refuse("momentum = " + show(hv) + " must be three finite numbers (kg m^2/s)");
    var I = moments.slice(), L = [0, 0, 0], invI = [0, 0, 0];
    for (var i = 0; i < 3; i++) {
      L[i] = omega0[i] * I[i] + hv[i];
      invI[i] = 1.0 / I[i];
    }
    var qn = Math.sqrt(quat0[0] * quat0[0] + quat0[1] * quat0[1] + quat0[2] * quat0[2] + quat0[3] * quat0[3]);
    if (!(qn > 0)) refuse("quat0 must be a unit quaternion [x, y, z, w], not zero");
    var q = [quat0[0] / qn, quat0[1] / qn, quat0[2] / qn, quat0[3] / qn];
    var step = options.step;
    if (step === undefined || step === null) {
      var w0 = (L[0] - hv[0]) * invI[0], w1 = (L[1] - hv[1]) * invI[1], w2 = (L[2] - hv[2]) * invI[2];
      step = defaultStep(Math.sqrt(w0 * w0 + w1 * w1 + w2 * w2));
    } else if (typeof step !== "number" || !(isFinite(step) && step > 0)) {
      refuse("step = " + step + " must be a positive finite number (s)");
    }
    var total = 0;
    for (var k = 1; k < times.length; k++) total += steps(times[k] - times[k - 1], step)[0];
    if (total > MAX_STEPS) {
      refuse("the run needs " + total + " steps of at most " + step.toPrecision(3) + " s; at most " + MAX_STEPS +
             " in the browser: shorten t_end or lower omega");
    }

    var n = times.length;
    var omegaOut = [[(L[0] - hv[0]) * invI[0], (L[1] - hv[1]) * invI[1], (L[2] - hv[2]) * invI[2]]];
    var quatOut = [q.slice()];
    for (var s = 1; s < n; s++) {
      var plan = steps(times[s] - times[s - 1], step), ns = plan[0], h = plan[1];
      // the sample's segment: ordered product of the sub-flows' rotations exp(a e_axis)
      var seg = [0.0, 0.0, 0.0, 1.0];
      for (var m = 0; m < ns; m++) {
        for (var f = 0; f < subflows.length; f++) {
          var axis = subflows[f][0], j = NEXT[axis][0], l = NEXT[axis][1];
          var a = subflows[f][1] * h * (L[axis] - hv[axis]) * invI[axis];
          var c = cosCR(a), sn = sinCR(a), Lj = L[j], Ll = L[l];
          L[j] = c * Lj + sn * Ll; // body momentum turns by -a about e_axis
          L[l] = c * Ll - sn * Lj;
          // the attitude turns by +a: seg <- seg (x) (sin(a/2) e_axis, cos(a/2))
          var ch = Math.cos(0.5 * a), sh = Math.sin(0.5 * a);
          var qa = seg[axis], qj = seg[j], qk = seg[l], qw = seg[3];
          seg[axis] = ch * qa + sh * qw;
          seg[j] = ch * qj + sh * qk;
          seg[l] = ch * qk - sh * qj;
          seg[3] = ch * qw - sh * qa;
        }
      }
      // q <- q (x) seg (Hamilton product, scalar last), renormalised once per sample
      var sx = seg[0], sy = seg[1], sz = seg[2], sw = seg[3];
      var x = q[3] * sx + q[0] * sw + q[1] * sz - q[2] * sy;
      var y = q[3] * sy - q[0] * sz + q[1] * sw + q[2] * sx;
      var z = q[3] * sz + q[0] * sy - q[1] * sx + q[2] * sw;
      var w = q[3] * sw - q[0] * sx - q[1] * sy - q[2] * sz;
      var norm = Math.sqrt(x * x + y * y + z * z + w * w);
      q = [x / norm, y / norm, z / norm, w / norm];
      omegaOut.push([(L[0] - hv[0]) * invI[0], (L[1] - hv[1]) * invI[1], (L[2] - hv[2]) * invI[2]]);
      quatOut.push(q);
    }
    return { omega: omegaOut, quat: quatOut, step: step };
  }

  var api = {
    propagate: propagate,
    defaultStep: defaultStep,
    freeFlowSubsteps: freeFlowSubsteps,
    checkMoments: checkMoments,
    invariants: invariants,
    sinCR: sinCR,
    cosCR: cosCR,
    SplittingInputError: SplittingInputError,
    MAX_STEP_ANGLE: MAX_STEP_ANGLE,
    MAX_STEPS: MAX_STEPS,
    COMPOSITIONS: COMPOSITIONS
  };
  if (typeof module === "object" && module.exports) module.exports = api;
  if (root) root.tumbleSplitting = api;
})(typeof window !== "undefined" ? window : null);
